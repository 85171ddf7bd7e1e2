"""What the coupled benchmark scripts share: the repository paths, the provenance line of a run, timed runs (and
their median over rounds in rotated order) and the panel's velocity history."""
import csv
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
RESULTS = ROOT / "bench" / "results"


def provenance(bin_dir):
    """One line: git HEAD of the tree (read-only query) and the modification time of the binaries used."""
    try:
        head = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, text=True).stdout.strip()
    except OSError:
        head = "?"
    stamps = []
    for exe in ("coupler", "fluid_solver", "solid_solver"):
        p = Path(bin_dir) / exe
        if p.exists():
            stamps.append(f"{exe} {time.strftime('%Y-%m-%d %H:%M:%S', time.localtime(p.stat().st_mtime))}")
    return f"git HEAD {head or '?'}; binaries built: " + ", ".join(stamps)


def timed_run(cmd, log):
    """Runs cmd with its output in the file `log`; returns the wall time [s]; exits naming the log on failure."""
    t0 = time.perf_counter()
    with open(log, "w") as fh:
        rc = subprocess.run(cmd, stdout=fh, stderr=subprocess.STDOUT).returncode
    if rc != 0:
        sys.exit(f"failed ({rc}): {' '.join(cmd)}; see {log}")
    return time.perf_counter() - t0


def run_rotated(names, repeat, run_one):
    """{name: median wall time} of run_one(name, r) over `repeat` rounds r, each round starting one variant later (a
    drift of the machine favours none)."""
    times = {n: [] for n in names}
    for r in range(repeat):
        for name in names[r % len(names):] + names[:r % len(names)]:
            times[name].append(run_one(name, r))
    return {n: statistics.median(t) for n, t in times.items()}


def panel_history(path):
    """(time, mean x velocity) of the block named panel in a solid's block_history.csv, as numpy arrays."""
    import numpy as np
    t, v = [], []
    with open(path) as fh:
        for r in csv.DictReader(fh):
            if r["block"] == "panel":
                t.append(float(r["time"]))
                v.append(float(r["velocity_x"]))
    return np.array(t), np.array(v)
