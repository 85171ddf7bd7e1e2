"""cosim.run: failures carry the exit code and the reason; the launcher is found as documented."""
import os
import shutil
import subprocess

import pytest

import cosim
from support import CONFIGS, COUPLED, PACKAGE_PARENT, PYTHON


def test_bad_key_raises_with_exit_code_and_reason(launcher, tmp_path):
    out = tmp_path / "bad"
    with pytest.raises(cosim.RunFailed) as info:
        cosim.run(CONFIGS / COUPLED[0], out, set={"coupling.time.end": 1e-3, "coupling.bogus": 1}, exe=launcher)
    e = info.value
    assert e.returncode == 2  # bad input, nothing started
    assert "coupling.bogus" in e.reason and "unknown key" in e.reason
    assert e.summary is None and not out.exists()
    assert "exit code 2" in str(e)


def test_failing_process_reason_comes_from_run_summary(launcher, tmp_path):
    out = tmp_path / "failed"
    with pytest.raises(cosim.RunFailed) as info:
        cosim.run(CONFIGS / COUPLED[0], out, set=dict(COUPLED[1], **{"launcher.solid": "/bin/false"}), exe=launcher)
    e = info.value
    assert e.returncode == 1
    assert e.summary is not None and e.summary["status"] == "failed"
    assert e.summary["failed_process"]["name"] == "solid"
    assert e.reason.startswith(e.summary["reason"]) and "solid failed" in e.reason


def test_stale_run_summary_is_not_taken_as_the_reason(coupled_dir, launcher, tmp_path):
    """A refused scene writes nothing: the completed summary of an earlier run there is not the reason."""
    out = tmp_path / "again"
    shutil.copytree(coupled_dir, out)
    with pytest.raises(cosim.RunFailed) as info:
        cosim.run(CONFIGS / COUPLED[0], out, set=["coupling.time.end=oops"], exe=launcher)
    assert info.value.summary is None and "coupling.time.end" in info.value.reason


def test_launcher_from_cosim_bin(bin_dir, monkeypatch, tmp_path):
    monkeypatch.setenv("COSIM_BIN", str(bin_dir))
    assert cosim.find_executable() == bin_dir / "cosim"
    assert cosim.find_executable("solid_solver") == bin_dir / "solid_solver"
    monkeypatch.setenv("COSIM_BIN", str(tmp_path))
    with pytest.raises(FileNotFoundError, match="COSIM_BIN"):
        cosim.find_executable()
    # the argument comes first: a directory or the program itself
    assert cosim.find_executable(exe=bin_dir) == bin_dir / "cosim"
    assert cosim.find_executable(exe=bin_dir / "cosim") == bin_dir / "cosim"
    with pytest.raises(FileNotFoundError, match="given as exe"):
        cosim.find_executable(exe=tmp_path)


def _installed_copy(prefix):
    """The package under test copied into <prefix>/lib/python3/dist-packages, and a program <prefix>/bin/cosim."""
    site = prefix / "lib" / "python3" / "dist-packages"
    shutil.copytree(PACKAGE_PARENT / "cosim", site / "cosim", ignore=shutil.ignore_patterns("__pycache__"))
    (prefix / "bin").mkdir()
    program = prefix / "bin" / "cosim"
    program.write_text("#!/bin/sh\nexit 0\n")
    program.chmod(0o755)
    return site, program


def test_launcher_next_to_an_installed_package(tmp_path):
    site, program = _installed_copy(tmp_path / "prefix")
    env = {k: v for k, v in os.environ.items() if k not in ("COSIM_BIN", "PYTHONPATH")}
    env["PYTHONPATH"] = str(site)
    done = subprocess.run([PYTHON, "-c", "import cosim; print(cosim.find_executable())"], env=env, cwd=tmp_path,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == str(program)


def test_set_values_are_written_as_the_scene_holds_them():
    fmt, parse = cosim.scene.format_value, cosim.scene.parse_value
    assert fmt(1e-3) == "0.001" and fmt([160, 8]) == "[160, 8]" and fmt(True) == "true" and fmt("robin") == "robin"
    assert parse("2e5") == 200000.0 and parse("1e-3") == 0.001  # YAML 1.2 floats, as the programs read them
    assert parse("[160, 8]") == [160, 8] and parse("robin") == "robin" and parse("true") is True
