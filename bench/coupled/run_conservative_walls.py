#!/usr/bin/python3
"""The conservative embedded boundary (`fluid.embedded.conservative`, docs/methods.md §5.8) against the
non-conservative first- and second-order walls, in coupled runs through `cosim run`:

- the blast on a steel panel (paper 9.5, configs/shock_panel_2d.yaml) at 50^2 and 100^2 (panel n/10 x n/2): the
  fluid's mass account (summary.json: the flow cells' mass change less the domain boundary's, and what went through
  the walls and with the covered/uncovered cells), the coupled energy account (energy_account.json's
  interface_created, relative), the panel's peak mean x velocity and its error against the default at 200^2
  (with --reference), the wall time and its cost per cycle;
- the rigid piston (configs/piston_2d.yaml to 0.1 s);
- the tungsten blast at its CI size (configs/tungsten_blast_3d.yaml at 32^3, solid 4 x 10 x 10, to 0.3 ms).

Prints a markdown table and writes bench/results/coupled_conservative_walls.png (panel peak error against run
time: one point per variant and size).

Usage: bench/coupled/run_conservative_walls.py [--build DIR] [--sizes 50 100] [--reference] [--work DIR [--reuse]]
"""
import argparse
import json
import tempfile
from pathlib import Path

import matplotlib
import numpy as np

from bench_common import RESULTS, ROOT, panel_history, provenance, timed_run

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

VARIANTS = [("first order", ["--set", "fluid.embedded.order=1"]),
            ("second order", ["--set", "fluid.embedded.order=2"]),
            ("conservative (2nd order)", ["--set", "fluid.embedded.order=2", "--set", "fluid.embedded.conservative=true"]),
            ("conservative (1st order)", ["--set", "fluid.embedded.order=1", "--set", "fluid.embedded.conservative=true"])]


def accounts(out):
    """(mass change less boundary inflow / start mass, through walls, cells, energy interface_created relative,
    cycles) of one run, summed over the phases."""
    f = json.loads((out / "fluid" / "summary.json").read_text())
    t = f["totals"]
    m0 = sum(p["mass"] for p in t["start"])
    dm = sum(e["mass"] - s["mass"] - i["mass"] for e, s, i in zip(t["end"], t["start"], t["boundary_inflow"]))
    walls = sum(p["through_walls"] for p in f["embedded"]["mass"])
    cells = sum(p["cells_uncovered"] for p in f["embedded"]["mass"])
    e = json.loads((out / "energy_account.json").read_text())
    return dict(dm=dm / m0, walls=walls / m0, cells=cells / m0, energy=e.get("interface_created_relative", float("nan")),
                steps=f.get("steps", 0))


def run(bin_dir, scene, out, extra, reuse):
    stamp = out / "wall_seconds.txt"
    if reuse and stamp.exists():
        return float(stamp.read_text())
    wall = timed_run([str(bin_dir / "cosim"), "run", str(ROOT / "configs" / scene), "--out", str(out), "--quiet"] +
                     extra, str(out) + ".log")
    stamp.write_text(f"{wall:.3f}\n")
    return wall


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--sizes", type=int, nargs="+", default=[50, 100])
    ap.add_argument("--reference", action="store_true", help="also the default at 200^2 (the panel's reference)")
    ap.add_argument("--work", default=None)
    ap.add_argument("--reuse", action="store_true")
    args = ap.parse_args()
    bin_dir = Path(args.build) / "bin"
    work = Path(args.work or tempfile.mkdtemp(prefix="cosim_conservative_"))
    work.mkdir(parents=True, exist_ok=True)
    rows = []
    panel = {}
    for n in args.sizes:
        for name, sets in VARIANTS:
            out = work / f"panel_{n}_{name.split()[0]}_{name.count('1st')}_{name.count('first')}"
            wall = run(bin_dir, "shock_panel_2d.yaml", out, sets + ["--set", f"fluid.mesh.cells=[{n},{n}]", "--set",
                                                                     f"solid.mesh.cells=[{n // 10},{n // 2}]"],
                       args.reuse)
            t, v = panel_history(out / "solid" / "block_history.csv")
            panel[(name, n)] = dict(peak=float(np.max(v)), wall=wall)
            rows.append((f"9.5 panel {n}^2", name, accounts(out), wall, f"{np.max(v):.2f}"))
    ref = None
    if args.reference:
        out = work / "panel_200_reference"
        run(bin_dir, "shock_panel_2d.yaml", out, ["--set", "fluid.mesh.cells=[200,200]", "--set",
                                                   "solid.mesh.cells=[20,100]"], args.reuse)
        ref = float(np.max(panel_history(out / "solid" / "block_history.csv")[1]))
    for name, sets in VARIANTS[1:3]:
        out = work / f"piston_{name.split()[0]}"
        wall = run(bin_dir, "piston_2d.yaml", out, sets + ["--set", "coupling.time.end=0.1"], args.reuse)
        rows.append(("piston 2D to 0.1 s", name, accounts(out), wall, ""))
    for name, sets in VARIANTS[1:3]:
        out = work / f"tungsten_{name.split()[0]}"
        wall = run(bin_dir, "tungsten_blast_3d.yaml", out,
                   sets + ["--set", "fluid.mesh.cells=[32,32,32]", "--set", "solid.mesh.cells=[4,10,10]", "--set",
                           "coupling.time.end=3e-4"], args.reuse)
        rows.append(("tungsten blast 32^3", name, accounts(out), wall, ""))

    print(f"The conservative embedded boundary; {provenance(bin_dir)}\n")
    if ref is not None:
        print(f"panel reference: second order at 200^2, peak {ref:.2f} m/s\n")
    print("| scene | walls | flow mass change - boundary | through walls | covered/uncovered cells | "
          "energy created (relative) | cycles | wall [s] | ms per cycle | panel peak [m/s] |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for scene, name, a, wall, peak in rows:
        per = 1e3 * wall / a["steps"] if a["steps"] else float("nan")
        print(f"| {scene} | {name} | {a['dm']:+.2e} | {a['walls']:+.2e} | {a['cells']:+.2e} | {a['energy']:+.2e} | "
              f"{a['steps']} | {wall:.1f} | {per:.1f} | {peak} |")

    fig, ax = plt.subplots(figsize=(7, 5))
    for name, _ in VARIANTS:
        pts = [(panel[(name, n)]["wall"], panel[(name, n)]["peak"], n) for n in args.sizes]
        if ref is not None:
            ys = [100 * abs(p[1] - ref) / ref for p in pts]
            ax.set_ylabel("panel peak error [% of the 200^2 peak]")
        else:
            ys = [p[1] for p in pts]
            ax.set_ylabel("panel peak velocity [m/s]")
        ax.plot([p[0] for p in pts], ys, "o-", label=name)
        for p, y in zip(pts, ys):
            ax.annotate(f"{p[2]}^2", (p[0], y), fontsize=7)
    ax.set_xscale("log")
    ax.set_xlabel("wall time of cosim run [s]")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    ax.set_title("blast on a steel panel (9.5): error against run time by wall treatment")
    RESULTS.mkdir(parents=True, exist_ok=True)
    path = RESULTS / "coupled_conservative_walls.png"
    fig.savefig(path, dpi=120, bbox_inches="tight")
    print(f"\nplot: {path.relative_to(ROOT)}; runs in {work}")


if __name__ == "__main__":
    main()
