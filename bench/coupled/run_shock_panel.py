#!/usr/bin/python3
"""Grid convergence of the blast on a steel panel (paper 9.5, configs/shock_panel_2d.yaml) and its conforming
reference (configs/shock_panel_2d_conforming.yaml, ALE air): background 50^2 / 100^2 / 200^2 with the panel
5 x 25 / 10 x 50 / 20 x 100 (the conforming mesh of the same element size), the panel's mass-averaged velocity
history of each (solid/block_history.csv).

Prints, per resolution: the peak and the most negative mean velocity of both runs, the largest difference of the
two histories over the run against the conforming peak, the wall time of each; and per method the differences
between successive resolutions (max over the run) with the observed order. Plots the histories of all runs
(bench/results/coupled_shock_panel_convergence.png) and, with python/plot_paper_scenes.py, the fields of both
runs at 0.2 and 0.65 ms at 200^2 (bench/results/shock_panel_fields.png, shock_panel_velocity.png).

Usage: bench/coupled/run_shock_panel.py [--sizes 50 100 200] [--build DIR] [--work DIR]
"""
import argparse
import math
import subprocess
import tempfile
from pathlib import Path

import matplotlib
import numpy as np

from bench_common import RESULTS, ROOT, panel_history, provenance, timed_run

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=int, nargs="+", default=[50, 100, 200])
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--work", default=None)
    args = ap.parse_args()
    bin_dir = Path(args.build) / "bin"
    work = Path(args.work or tempfile.mkdtemp(prefix="cosim_shock_panel_"))
    grid = np.linspace(0, 1e-3, 2001)
    res = {}
    for n in args.sizes:
        emb, conf = work / f"embedded_{n}", work / f"conforming_{n}"
        we = timed_run([str(bin_dir / "cosim"), "run", str(ROOT / "configs/shock_panel_2d.yaml"), "--out", str(emb),
                    "--quiet", "--set", f"fluid.mesh.cells=[{n},{n}]", "--set",
                    f"solid.mesh.cells=[{n // 10},{n // 2}]"], str(emb) + ".log")
        box = [] if n == 50 else ["--set", f"solid.mesh.cells=[{n},{n}]", "--set", "solid.mesh.lower=[0,0]", "--set",
                                  "solid.mesh.upper=[1,1]"]
        wc = timed_run([str(bin_dir / "solid_solver"), str(ROOT / "configs/shock_panel_2d_conforming.yaml"), "--out",
                    str(conf), "--quiet"] + box, str(conf) + ".log")
        te, ve = panel_history(emb / "solid" / "block_history.csv")
        tc, vc = panel_history(conf / "block_history.csv")
        res[n] = dict(e=np.interp(grid, te, ve), c=np.interp(grid, tc, vc), we=we, wc=wc, emb=emb, conf=conf)

    print(f"Blast on a steel panel (paper 9.5), panel mean velocity over 0-1 ms; {provenance(bin_dir)}\n")
    print("| background | panel | embedded peak / min [m/s] | conforming peak / min [m/s] | largest difference "
          "(of the conforming peak) | wall embedded / conforming [s] |")
    print("|---|---|---|---|---|---|")
    for n, r in res.items():
        d = np.max(np.abs(r["e"] - r["c"]))
        pk = np.max(np.abs(r["c"]))
        print(f"| {n}^2 | {n // 10} x {n // 2} | {r['e'].max():.2f} / {r['e'].min():.2f} | {r['c'].max():.2f} / "
              f"{r['c'].min():.2f} | {d:.2f} m/s ({100 * d / pk:.1f}%) | {r['we']:.1f} / {r['wc']:.1f} |")
    sizes = list(res)
    if len(sizes) >= 3:
        print("\n| method | max difference 50->100 / 100->200 [m/s] | observed order |")
        print("|---|---|---|")
        for key, name in (("e", "embedded"), ("c", "conforming")):
            d1 = np.max(np.abs(res[sizes[0]][key] - res[sizes[1]][key]))
            d2 = np.max(np.abs(res[sizes[1]][key] - res[sizes[2]][key]))
            print(f"| {name} | {d1:.2f} / {d2:.2f} | {math.log2(d1 / d2):.2f} |")

    fig, ax = plt.subplots(figsize=(9, 5))
    for k, (n, r) in enumerate(res.items()):
        ax.plot(grid * 1e3, r["e"], "-", color=f"C{k}", label=f"embedded {n}^2")
        ax.plot(grid * 1e3, r["c"], "--", color=f"C{k}", label=f"conforming {n}^2")
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("panel mean velocity $u_x$ [m/s]")
    ax.set_title("blast on a steel panel (paper 9.5): grid convergence")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    RESULTS.mkdir(parents=True, exist_ok=True)
    fig.savefig(RESULTS / "coupled_shock_panel_convergence.png", dpi=120, bbox_inches="tight")
    finest = res[sizes[-1]]
    subprocess.run(["/usr/bin/python3", str(ROOT / "python/plot_paper_scenes.py"), "panel", str(finest["emb"]),
                    str(finest["conf"]), "--out", str(RESULTS)], check=True)
    print(f"\nplots in {RESULTS.relative_to(ROOT)}; runs in {work}")


if __name__ == "__main__":
    main()
