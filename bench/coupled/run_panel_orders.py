#!/usr/bin/python3
"""The embedded boundary's wall order on the blast on a steel panel (paper 9.5, configs/shock_panel_2d.yaml):
the panel's peak mean x velocity (solid/block_history.csv) with first-order walls (`fluid.embedded.order: 1`) and
second-order walls (the default, order 2) at 50^2 / 100^2 / 200^2 (panel 5 x 25 / 10 x 50 / 20 x 100; with
--fixed-panel the scene's 5 x 25 at every size, only fluid.mesh.cells set), their errors against the finest run
and the wall time of each `cosim run`.

The reference is the default (second order) at the finest size: the error of a run is |peak - reference peak|
and, for the whole history, the largest |v(t) - v_ref(t)| over 0 to the end time, both in % of the reference peak.
With --old-build DIR (a build of the code before the mend of the second-order wall velocity, docs/methods.md
§5.5), its second order is run beside them as "old second order".

Prints a markdown table and writes bench/results/coupled_panel_orders.png (error against run time).

Usage: bench/coupled/run_panel_orders.py [--sizes 50 100 200] [--build DIR] [--old-build DIR] [--fixed-panel] [--work DIR [--reuse]]
"""
import argparse
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
    ap.add_argument("--old-build", default=None, help="build dir of the code before the mend (optional)")
    ap.add_argument("--fixed-panel", action="store_true", help="keep the scene's 5 x 25 panel at every size")
    ap.add_argument("--work", default=None)
    ap.add_argument("--reuse", action="store_true", help="keep the runs already in --work (their wall_seconds.txt)")
    args = ap.parse_args()
    bin_dir = Path(args.build) / "bin"
    work = Path(args.work or tempfile.mkdtemp(prefix="cosim_panel_orders_"))
    work.mkdir(parents=True, exist_ok=True)
    variants = [("first order", bin_dir, 1), ("second order (default)", bin_dir, 2)]
    if args.old_build:
        variants.insert(1, ("old second order", Path(args.old_build) / "bin", 2))
    end = 1.0e-3
    grid = np.linspace(0, end, 2001)
    res = {}
    for n in args.sizes:
        for name, bdir, order in variants:
            out = work / f"{name.split()[0]}_o{order}_{n}"
            stamp = out / "wall_seconds.txt"
            if args.reuse and stamp.exists():
                wall = float(stamp.read_text())
                t, v = panel_history(out / "solid" / "block_history.csv")
                i = int(np.argmax(v))
                res[(name, n)] = dict(v=np.interp(grid, t, v), peak=v[i], t_peak=t[i], wall=wall)
                continue
            panel = [] if args.fixed_panel else ["--set", f"solid.mesh.cells=[{n // 10},{n // 2}]"]
            wall = timed_run([str(bdir / "cosim"), "run", str(ROOT / "configs/shock_panel_2d.yaml"), "--out", str(out),
                              "--quiet", "--set", f"fluid.mesh.cells=[{n},{n}]", "--set",
                              f"fluid.embedded.order={order}"] + panel, str(out) + ".log")
            stamp.write_text(f"{wall:.3f}\n")
            t, v = panel_history(out / "solid" / "block_history.csv")
            i = int(np.argmax(v))
            res[(name, n)] = dict(v=np.interp(grid, t, v), peak=v[i], t_peak=t[i], wall=wall)

    finest = max(args.sizes)
    ref = res[("second order (default)", finest)]
    panel = "the scene's 5 x 25 panel" if args.fixed_panel else "panel n/10 x n/2"
    print(f"Blast on a steel panel (paper 9.5), {panel}: peak panel mean x velocity by wall order; reference: the "
          f"default at {finest}^2 (peak {ref['peak']:.2f} m/s); {provenance(bin_dir)}\n")
    print("| walls | background | peak [m/s] (at [ms]) | peak error | largest history error | wall [s] |")
    print("|---|---|---|---|---|---|")
    for name, _, _ in variants:
        for n in args.sizes:
            r = res[(name, n)]
            r["err"] = abs(r["peak"] - ref["peak"]) / ref["peak"]
            r["herr"] = float(np.max(np.abs(r["v"] - ref["v"]))) / ref["peak"]
            print(f"| {name} | {n}^2 | {r['peak']:.2f} ({1e3 * r['t_peak']:.3f}) | {100 * r['err']:.1f}% | "
                  f"{100 * r['herr']:.1f}% | {r['wall']:.1f} |")

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    styles = {"first order": "o--", "old second order": "x:", "second order (default)": "s-"}
    for name, _, _ in variants:
        pts = [(res[(name, n)]["wall"], res[(name, n)]["err"], res[(name, n)]["herr"], n) for n in args.sizes]
        pts = [p for p in pts if p[1] > 0 and p[2] > 0]  # the reference itself has none
        axes[0].loglog([p[0] for p in pts], [100 * p[1] for p in pts], styles[name], label=name)
        axes[1].loglog([p[0] for p in pts], [100 * p[2] for p in pts], styles[name], label=name)
        for p in pts:
            axes[0].annotate(f"{p[3]}^2", (p[0], 100 * p[1]), fontsize=7)
            axes[1].annotate(f"{p[3]}^2", (p[0], 100 * p[2]), fontsize=7)
    axes[0].set_ylabel(f"peak error [% of the {finest}^2 peak]")
    axes[1].set_ylabel(f"largest history error over 0-1 ms [% of the {finest}^2 peak]")
    for ax in axes:
        ax.set_xlabel("wall time of cosim run [s]")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    fig.suptitle(f"blast on a steel panel (paper 9.5), {panel}: error against run time by wall order")
    RESULTS.mkdir(parents=True, exist_ok=True)
    path = RESULTS / ("coupled_panel_orders" + ("_fixed_panel" if args.fixed_panel else "") + ".png")
    fig.savefig(path, dpi=120, bbox_inches="tight")
    print(f"\nplot: {path.relative_to(ROOT)}; runs in {work}")


if __name__ == "__main__":
    main()
