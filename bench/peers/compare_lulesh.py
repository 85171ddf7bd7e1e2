#!/usr/bin/python3
"""Side-by-side comparison of solid_solver with LULESH 2.0 on LULESH's own Sedov problem.

Runs ours (configs/solid_sedov_lulesh.yaml, one thread) and the LULESH executable given (`-s N`, one OpenMP
thread) in alternation, pair after pair, so that both see the same state of a shared machine; LULESH runs
both as built and with glibc's allocator told to keep its memory (GLIBC_TUNABLES, no code change: LULESH
frees and re-allocates its temporaries every cycle, and by default glibc returns them to the kernel each
time). For each pair it takes two ratios, ours over theirs:

  rate             zone-cycles per second (theirs: iterations * N^3 / LULESH's own elapsed time)
  time-to-solution process wall time to t = 0.01 (theirs over ours; the step counts differ)

and prints the median, min and max over the pairs, with both codes' step counts. Our energy balance
error and shock radius (density peak, radial bins of one cell) come from one extra run with snapshots.

The script never downloads or builds a peer: build LULESH yourself and pass its path.

Usage:
  compare_lulesh.py --lulesh PATH/lulesh2.0 [--lulesh-commit HASH] [--solid build/bin/solid_solver]
                    [--sizes 30] [--pairs 5] [--strength off,on] [--variants as_built,tuned]
                    [--csv bench/results/lulesh_pairs.csv] [--png bench/results/lulesh_pairs.png]
Exit status: 0 done, 2 bad arguments or a run that failed (its output is printed).
"""
import argparse
import csv
import glob
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from datetime import date
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "configs" / "solid_sedov_lulesh.yaml"
TUNED_MALLOC = "glibc.malloc.mmap_threshold=268435456:glibc.malloc.trim_threshold=1073741824"
# "Strength on": the same gas with a tiny shear modulus and yield stress, so that the whole deviatoric path
# (midpoint velocity gradient, Jaumann rotation, radial return) runs in every element on the same flow.
STRENGTH_BLOCK = ("solid.blocks=[{name: gas, eos: {type: ideal_gas, gamma: 1.6666666666666667}, density: 1.0, "
                  "strength: {shear_modulus: 1.0e-3, yield_stress: 1.0e-3}}]")
LULESH_FIELDS = {
    "size": r"Problem size\s*=\s*(\d+)",
    "iterations": r"Iteration count\s*=\s*(\d+)",
    "origin_energy": r"Final Origin Energy\s*=\s*([-+0-9.eE]+)",
    "elapsed_s": r"Elapsed time\s*=\s*([-+0-9.eE]+)",
    "grind_us": r"Grind time \(us/z/c\)\s*=\s*([-+0-9.eE]+)",
}


class RunError(Exception):
    pass


def fail(msg):
    print(f"compare_lulesh: {msg}", file=sys.stderr)
    sys.exit(2)


def executable(path, what):
    p = Path(path)
    if not p.is_file() or not os.access(p, os.X_OK):
        fail(f"{what} '{path}' is not an executable file")
    return p.resolve()


def run_ours(solid, n, strength, workdir, snapshots=False, timeout=1800):
    out = Path(workdir) / "ours"
    shutil.rmtree(out, ignore_errors=True)
    cmd = [str(solid), str(SCENE), "--quiet", "--threads", "1", "--out", str(out),
           "--set", f"solid.mesh.cells=[{n},{n},{n}]", "--set", f"solid.output.snapshots={str(snapshots).lower()}"]
    if strength == "on":
        cmd += ["--set", STRENGTH_BLOCK]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    t0 = time.perf_counter()
    r = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=timeout)
    wall = time.perf_counter() - t0
    if r.returncode != 0:
        raise RunError(f"{' '.join(cmd)} exited {r.returncode}:\n{r.stdout}{r.stderr}")
    s = json.loads((out / "summary.json").read_text())
    return {"steps": s["steps"], "zone_cycles_per_s": s["zone_cycles_per_s"], "process_wall_s": wall,
            "energy_error": s["energy"]["relative_balance_error"], "out": out}


def parse_lulesh(text):
    vals = {}
    for key, pat in LULESH_FIELDS.items():
        m = re.search(pat, text)
        if not m:
            raise RunError(f"LULESH output has no '{pat}':\n{text}")
        vals[key] = float(m.group(1))
    if "Run completed" not in text:
        raise RunError(f"LULESH output lacks 'Run completed':\n{text}")
    return vals


def run_lulesh(lulesh, n, variant, timeout=1800):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    env.pop("GLIBC_TUNABLES", None)
    if variant == "tuned":
        env["GLIBC_TUNABLES"] = TUNED_MALLOC
    t0 = time.perf_counter()
    r = subprocess.run([str(lulesh), "-s", str(n)], env=env, capture_output=True, text=True, timeout=timeout)
    wall = time.perf_counter() - t0
    if r.returncode != 0:
        raise RunError(f"{lulesh} -s {n} exited {r.returncode}:\n{r.stdout}{r.stderr}")
    v = parse_lulesh(r.stdout)
    if int(v["size"]) != n:
        raise RunError(f"LULESH ran size {int(v['size'])}, asked {n}")
    v["zone_cycles_per_s"] = v["iterations"] * n ** 3 / v["elapsed_s"]
    v["process_wall_s"] = wall
    return v


def shock_radius(out, n):
    """Density-peak radius of our final snapshot (radial bins of one cell width, parabolic peak)."""
    import h5py
    import numpy as np

    last = sorted(glob.glob(str(out / "solid_*.h5")))[-1]
    with h5py.File(last, "r") as f:
        x = f["grid/coordinates"][()]
        conn = f["grid/connectivity"][()]
        rho = f["cell/density"][()]
    h = 1.125 / n
    r = np.linalg.norm(x[conn].mean(axis=1), axis=1)
    b = (r / h).astype(int)
    sums, counts = np.bincount(b, weights=rho), np.bincount(b)
    prof = np.where(counts > 0, sums / np.maximum(counts, 1), 1.0)
    k = int(np.argmax(prof))
    if 0 < k < len(prof) - 1:
        a, c, d = prof[k - 1], prof[k], prof[k + 1]
        return (k + 0.5 + 0.5 * (a - d) / (a - 2 * c + d)) * h
    return (k + 0.5) * h


def summarize(v):
    return statistics.median(v), min(v), max(v)


def write_csv(path, rows):
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name, suffix=".tmp")
    with os.fdopen(fd, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    os.replace(tmp, path)


def plot(path, table):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, key, title in ((axes[0], "rate", "zone-cycles/s, ours / LULESH"),
                           (axes[1], "tts", "time to solution, LULESH / ours")):
        labels = [f"{t['n']}^3 str {t['strength']}\nLULESH {t['variant'].replace('_', ' ')}" for t in table]
        med = [t[key][0] for t in table]
        lo = [t[key][0] - t[key][1] for t in table]
        hi = [t[key][2] - t[key][0] for t in table]
        colors = ["tab:blue" if t["strength"] == "off" else "tab:orange" for t in table]
        ax.bar(range(len(table)), med, yerr=[lo, hi], color=colors, capsize=4)
        ax.axhline(1.0, color="k", lw=1)
        ax.set_xticks(range(len(table)))
        ax.set_xticklabels(labels, fontsize=7)
        ax.set_ylabel("ratio (median of pairs, bars: min-max)")
        ax.set_title(title, fontsize=10)
    fig.suptitle("solid_solver vs LULESH 2.0, Sedov, one thread, in alternation", fontsize=10)
    fig.tight_layout()
    tmp = path.with_name(path.stem + ".tmp.png")
    fig.savefig(tmp, dpi=120)
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--lulesh", required=True, help="LULESH 2.0 executable (serial or OpenMP build)")
    ap.add_argument("--lulesh-commit", default="unknown", help="the LULESH commit it was built from (printed)")
    ap.add_argument("--solid", default=str(ROOT / "build" / "bin" / "solid_solver"))
    ap.add_argument("--sizes", default="30", help="comma-separated N (N^3 elements)")
    ap.add_argument("--pairs", type=int, default=5)
    ap.add_argument("--strength", default="off,on")
    ap.add_argument("--variants", default="as_built,tuned")
    ap.add_argument("--csv", default=str(ROOT / "bench" / "results" / "lulesh_pairs.csv"))
    ap.add_argument("--png", default=str(ROOT / "bench" / "results" / "lulesh_pairs.png"))
    a = ap.parse_args()
    lulesh = executable(a.lulesh, "--lulesh")
    solid = executable(a.solid, "--solid")
    try:
        sizes = [int(s) for s in a.sizes.split(",")]
    except ValueError:
        fail(f"--sizes '{a.sizes}': expected comma-separated integers")
    if any(n < 2 for n in sizes):
        fail(f"--sizes '{a.sizes}': each N must be at least 2")
    strengths = a.strength.split(",")
    variants = a.variants.split(",")
    if not set(strengths) <= {"off", "on"}:
        fail(f"--strength '{a.strength}': expected off, on or off,on")
    if not set(variants) <= {"as_built", "tuned"}:
        fail(f"--variants '{a.variants}': expected as_built, tuned or as_built,tuned")
    if a.pairs < 1:
        fail("--pairs must be at least 1")
    host = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
    print(f"solid_solver {solid}\nLULESH {lulesh} (commit {a.lulesh_commit})\nhost {host}, {date.today()}\n")

    rows, table = [], []
    with tempfile.TemporaryDirectory() as work:
        try:
            for n in sizes:
                for strength in strengths:
                    for variant in variants:
                        rate, tts = [], []
                        for i in range(a.pairs):
                            # alternate who goes first, so neither always follows the other
                            if i % 2 == 0:
                                ours, theirs = run_ours(solid, n, strength, work), run_lulesh(lulesh, n, variant)
                            else:
                                theirs = run_lulesh(lulesh, n, variant)
                                ours = run_ours(solid, n, strength, work)
                            rate.append(ours["zone_cycles_per_s"] / theirs["zone_cycles_per_s"])
                            tts.append(theirs["process_wall_s"] / ours["process_wall_s"])
                            rows.append({"n": n, "strength": strength, "lulesh": variant, "pair": i,
                                         "ours_steps": ours["steps"], "ours_zcps": f"{ours['zone_cycles_per_s']:.4e}",
                                         "ours_wall_s": f"{ours['process_wall_s']:.6f}",
                                         "lulesh_steps": int(theirs["iterations"]),
                                         "lulesh_zcps": f"{theirs['zone_cycles_per_s']:.4e}",
                                         "lulesh_wall_s": f"{theirs['process_wall_s']:.6f}",
                                         "lulesh_origin_energy": f"{theirs['origin_energy']:.6e}",
                                         "rate_ratio": f"{rate[-1]:.4f}", "tts_ratio": f"{tts[-1]:.4f}",
                                         "load1": open("/proc/loadavg").read().split()[0]})
                            print(f"  {n}^3 strength {strength:3s} LULESH {variant:8s} pair {i}: "
                                  f"ours {ours['zone_cycles_per_s'] / 1e6:.2f} M/s {ours['process_wall_s']:.2f} s, "
                                  f"LULESH {theirs['zone_cycles_per_s'] / 1e6:.2f} M/s "
                                  f"{theirs['process_wall_s']:.2f} s", flush=True)
                        table.append({"n": n, "strength": strength, "variant": variant, "rate": summarize(rate),
                                      "tts": summarize(tts), "ours_steps": ours["steps"],
                                      "lulesh_steps": int(theirs["iterations"]),
                                      "lulesh_origin_energy": theirs["origin_energy"]})
            accuracy = {}
            for n in sizes:
                ours = run_ours(solid, n, "off", work, snapshots=True)
                accuracy[n] = (ours["energy_error"], shock_radius(ours["out"], n))
        except (RunError, subprocess.TimeoutExpired) as e:
            fail(f"a run failed: {e}")

    print("\n| N^3 | strength | LULESH | steps ours / LULESH | zone-cycles/s ratio, median (min-max) "
          "| time-to-solution ratio, median (min-max) |")
    print("|---|---|---|---|---|---|")
    for t in table:
        r, s = t["rate"], t["tts"]
        print(f"| {t['n']}^3 | {t['strength']} | {t['variant'].replace('_', ' ')} | {t['ours_steps']} / "
              f"{t['lulesh_steps']} | {r[0]:.2f}x ({r[1]:.2f}-{r[2]:.2f}) | {s[0]:.2f}x ({s[1]:.2f}-{s[2]:.2f}) |")
    print(f"\n{a.pairs} pairs each; 'tuned': GLIBC_TUNABLES={TUNED_MALLOC}")
    for n, (err, radius) in accuracy.items():
        print(f"ours at {n}^3: relative energy balance error {err:.1e}, shock radius {radius:.4f} (exact 1.000); "
              f"LULESH final origin energy {next(t['lulesh_origin_energy'] for t in table if t['n'] == n):.6e}")
    write_csv(Path(a.csv), rows)
    plot(Path(a.png), table)
    print(f"wrote {a.csv} and {a.png}")


if __name__ == "__main__":
    main()
