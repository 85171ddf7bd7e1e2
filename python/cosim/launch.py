"""Running scenes through the launcher `cosim run SCENE --out OUT --set key=value ...`.

The programs (cosim, fluid_solver, solid_solver, coupler) are looked for, in this order: the `exe` argument (the
program, or a directory holding it), the directory in $COSIM_BIN, the bin/ of the install prefix this package
lives in (<prefix>/bin when it is <prefix>/lib/python3.X/dist-packages/cosim), the bin/ of a build directory whose
python/ holds this package (<build>/python/cosim -> <build>/bin), and <repo>/build/bin of the source tree
(<repo>/python/cosim).
"""
import collections
import json
import os
import subprocess
import sys
import threading
from pathlib import Path

from .errors import RunFailed
from .runs import read_run
from .scene import format_value

_PACKAGE = Path(__file__).resolve().parent


def _prefix_bin():
    """<prefix>/bin of an installed package (<prefix>/lib*/python*/{dist,site}-packages/cosim), or None."""
    site = _PACKAGE.parent
    if site.name not in ("dist-packages", "site-packages"):
        return None
    for parent in site.parents:
        if parent.name in ("lib", "lib64"):
            return parent.parent / "bin"
    return None


def candidates(name="cosim"):
    """[(where, path)] of the places `name` is looked for after the argument and $COSIM_BIN."""
    places = []
    prefix = _prefix_bin()
    if prefix is not None:
        places.append(("install prefix", prefix / name))
    places.append(("build directory", _PACKAGE.parent.parent / "bin" / name))
    places.append(("source tree", _PACKAGE.parent.parent / "build" / "bin" / name))
    return places


def find_executable(name="cosim", exe=None):
    """Path of the program `name` (see the module's docstring for the search); FileNotFoundError listing the
    places tried."""
    if exe is not None:
        path = Path(exe)
        if path.is_dir():
            path = path / name
        if not (path.is_file() and os.access(path, os.X_OK)):
            raise FileNotFoundError(f"{path}: no executable {name} there (given as exe)")
        return path
    env = os.environ.get("COSIM_BIN")
    if env:
        path = Path(env) / name
        if not (path.is_file() and os.access(path, os.X_OK)):
            raise FileNotFoundError(f"{path}: no executable {name} in $COSIM_BIN ({env})")
        return path
    tried = candidates(name)
    for _, path in tried:
        if path.is_file() and os.access(path, os.X_OK):
            return path
    raise FileNotFoundError(f"{name} not found: set COSIM_BIN to the directory of the programs or pass exe=; "
                            f"looked in " + ", ".join(f"{where} {path}" for where, path in tried))


def _set_options(settings):
    """['--set', 'k=v', ...] of a mapping {key: value} or an iterable of 'k=v' strings / (key, value) pairs."""
    if settings is None:
        return []
    items = settings.items() if hasattr(settings, "items") else settings
    out = []
    for item in items:
        if isinstance(item, str):
            if "=" not in item:
                raise ValueError(f"set: {item!r} is not key=value")
            text = item
        else:
            key, value = item
            text = f"{key}={format_value(value)}"
        out += ["--set", text]
    return out


def _summary_mark(path):
    try:
        st = path.stat()
        return st.st_mtime_ns, st.st_size, st.st_ino
    except OSError:
        return None


def _failure_reason(summary, output_lines):
    """Why a run failed: run_summary.json's reason and the failed process's last log lines, else the launcher's
    last lines."""
    if summary is not None:
        reason = str(summary.get("reason") or summary.get("status") or "no reason recorded")
        failed = summary.get("failed_process") or {}
        lines = [str(x) for x in failed.get("last_log_lines") or [] if str(x).strip()]
        if lines:
            reason += "; last lines of its log:\n" + "\n".join(lines[-10:])
        return reason
    lines = [ln for ln in output_lines if ln.strip()]
    return "\n".join(lines[-20:]) if lines else "the launcher printed nothing"


def run(scene, out, set=None, exe=None, quiet=True, args=(), timeout=None):
    """Run `scene` (a YAML file) into the run directory `out` with `cosim run` and return read_run(out).

    set: overrides, {"coupling.time.end": 1e-3, "fluid.mesh.cells": [80, 4]} (values written as the scene would
    hold them) or ["key=value", ...]; exe: the launcher (or its directory), else the search of this module;
    quiet: no progress line, the launcher's output captured (else it goes to this process's stdout / stderr as
    well); args: more launcher options ("--tcp", "--solid-exe", "CMD"); timeout: seconds, after which the launcher
    is asked to stop (it stops its processes) and RunFailed is raised.
    A non-zero exit raises RunFailed with the exit code and the reason: that of OUT/run_summary.json when the
    launcher wrote one for this run, else its last output lines (a scene refused before anything started)."""
    launcher = find_executable("cosim", exe)
    out = Path(out)
    command = [str(launcher), "run", str(scene), "--out", str(out)] + _set_options(set)
    if quiet:
        command.append("--quiet")
    command += [str(a) for a in args]
    summary_path = out / "run_summary.json"
    before = _summary_mark(summary_path)
    tail = collections.deque(maxlen=200)
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace")
    reader = threading.Thread(target=_drain, args=(proc.stdout, tail, not quiet), daemon=True)
    reader.start()
    try:
        proc.wait(timeout)
    except subprocess.TimeoutExpired:
        _stop(proc)
        reader.join()
        raise RunFailed(proc.returncode, f"stopped after the timeout of {timeout:g} s", out, None, "\n".join(tail))
    except BaseException:  # KeyboardInterrupt: the launcher stops its processes, then this goes on
        _stop(proc)
        raise
    reader.join()
    code = proc.returncode
    if code != 0:
        summary = None
        if _summary_mark(summary_path) not in (None, before):
            try:
                with open(summary_path) as f:
                    summary = json.load(f)
            except (OSError, ValueError):  # unreadable: the launcher's own words are all there is
                summary = None
        raise RunFailed(code, _failure_reason(summary, list(tail)), out, summary, "\n".join(tail))
    return read_run(out)


def _drain(stream, tail, echo):
    """Keep the last lines of the launcher's output in `tail` (and copy them to stderr when echo)."""
    with stream:
        for line in stream:
            tail.append(line.rstrip("\n"))
            if echo:
                sys.stderr.write(line)
                sys.stderr.flush()


def _stop(proc):
    """SIGTERM to the launcher (it stops its processes within seconds), SIGKILL if it is still there after 15 s."""
    if proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(15)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
