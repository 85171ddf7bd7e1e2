#!/usr/bin/python3
"""Run time against error for the modified Sod problem (paper 9.4, configs/modified_sod_2d.yaml), the coupled
counterpart of the fluid's Sod error-vs-time curve: which choice gives a given error fastest.

For backgrounds N x N, N = 32, 64, 128, 256 (foreground N/4 x N/4), embedded boundary order 1 and 2, and the
`impedance` and `characteristic` interface conditions, side by side in one run (the order of the variants is
rotated per repeat so that a drift of the machine favours none): `cosim run`, then the L1 density error against
the exact Riemann solution on the background's flow cells and on the foreground's element centres at t = 0.28,
and the wall time of the whole command (start of the processes and output included; the median over --repeat
runs).
The plain Eulerian run of the same background (configs/modified_sod_2d_eulerian.yaml) is the reference line.

Usage: bench/coupled/run_modified_sod.py [--quick] [--repeat N] [--build DIR] [--work DIR]
Writes bench/results/coupled_modified_sod_error_vs_time.png and prints a markdown table.
"""
import argparse
import sys
import tempfile
from pathlib import Path

import matplotlib
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "python"))
from plot_paper_scenes import element_centres, exact_sod, read_fluid, read_solid, snapshots  # noqa: E402

from bench_common import RESULTS, ROOT, provenance, run_rotated, timed_run  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def l1_errors(run, domain=False):
    """L1(rho) against the exact solution: background flow cells, foreground elements (None without one) and, with
    domain=True, the coupled solution over the domain (the foreground where it lies, the background's flow cells
    elsewhere, cut cells counted whole, each by its area; tests/coupled/sod_measures.h, domain_density_error)."""
    f = read_fluid(snapshots(run, "fluid")[-1], "gas")
    xc = f["x0"][0] + (np.arange(f["nx"]) + 0.5) * f["dx"][0]
    ex = exact_sod(xc, f["t"])[0]
    err_bg = np.abs(f["rho"] - ex[None, :])[f["flow"]]
    bg = float(err_bg.mean())
    fg, dom = None, None
    sl = snapshots(run, "solid")
    if sl:
        s = read_solid(sl[-1])
        p = s["x"][s["conn"]]
        area = 0.5 * np.abs((p[:, 2, 0] - p[:, 0, 0]) * (p[:, 3, 1] - p[:, 1, 1]) -
                            (p[:, 3, 0] - p[:, 1, 0]) * (p[:, 2, 1] - p[:, 0, 1]))
        exs = exact_sod(element_centres(s)[:, 0], s["t"])[0]
        err_fg = (area * np.abs(s["density"] - exs)).sum()
        fg = float(err_fg / area.sum())
        cell = f["dx"][0] * f["dx"][1]
        dom = float((err_bg.sum() * cell + err_fg) / (err_bg.size * cell + area.sum()))
    return (bg, fg, dom) if domain else (bg, fg)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="N = 32, 64, 128 and one repeat")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--work", default=None)
    args = ap.parse_args()
    bin_dir = Path(args.build) / "bin"
    work = Path(args.work or tempfile.mkdtemp(prefix="cosim_modified_sod_"))
    work.mkdir(parents=True, exist_ok=True)
    sizes = [32, 64, 128] if args.quick else [32, 64, 128, 256]
    repeat = 1 if args.quick else args.repeat
    variants = [(mode, order) for mode in ("impedance", "characteristic") for order in (1, 2)]
    scene = ROOT / "configs" / "modified_sod_2d.yaml"
    ref_scene = ROOT / "configs" / "modified_sod_2d_eulerian.yaml"
    names = variants + ["eulerian"]

    def out_dir(v, n):
        return work / (f"eulerian_{n}" if v == "eulerian" else f"{v[0]}_o{v[1]}_{n}")

    rows = {}
    for n in sizes:
        m = n // 4

        def one(v, r, n=n, m=m):
            out = out_dir(v, n)
            if v == "eulerian":
                cmd = [str(bin_dir / "fluid_solver"), str(ref_scene), "--out", str(out), "--quiet",
                       "--set", f"fluid.mesh.cells=[{n},{n}]"]
            else:
                mode, order = v
                cmd = [str(bin_dir / "cosim"), "run", str(scene), "--out", str(out), "--quiet",
                       "--set", f"fluid.mesh.cells=[{n},{n}]", "--set", f"solid.mesh.cells=[{m},{m}]",
                       "--set", f"coupling.mode={mode}", "--set", f"fluid.embedded.order={order}"]
            return timed_run(cmd, str(out) + ".log")
        wall = run_rotated(names, repeat, one)
        for v in names:
            bg, fg = l1_errors(str(out_dir(v, n)))
            rows[(v, n)] = (wall[v], bg, fg)

    print(f"Modified Sod (paper 9.4), L1(rho) at t = 0.28 against wall time; {provenance(bin_dir)}; "
          f"median of {repeat} run(s)\n")
    print("| variant | N (background) | foreground | wall [s] | L1(rho) background | L1(rho) foreground |")
    print("|---|---|---|---|---|---|")
    for v in variants + ["eulerian"]:
        for n in sizes:
            w, bg, fg = rows[(v, n)]
            name = "Eulerian, no foreground" if v == "eulerian" else f"{v[0]}, order {v[1]}"
            fgs = f"{fg:.3e}" if fg is not None else "-"
            print(f"| {name} | {n} | {n // 4 if v != 'eulerian' else '-'} | {w:.3f} | {bg:.3e} | {fgs} |")

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8), sharey=True)
    styles = {("impedance", 1): "o--", ("impedance", 2): "o-", ("characteristic", 1): "s--",
              ("characteristic", 2): "s-"}
    for k, which in enumerate(("background (flow cells)", "foreground (element centres)")):
        ax = axes[k]
        for v in variants:
            w = [rows[(v, n)][0] for n in sizes]
            e = [rows[(v, n)][1 + k] for n in sizes]
            ax.loglog(w, e, styles[v], label=f"{v[0]}, boundary order {v[1]}")
        if k == 0:
            ax.loglog([rows[("eulerian", n)][0] for n in sizes], [rows[("eulerian", n)][1] for n in sizes], "k^:",
                      label="Eulerian, no foreground")
        for n in sizes:
            ax.annotate(f"{n}", (rows[(variants[-1], n)][0], rows[(variants[-1], n)][1 + k]), fontsize=7)
        ax.set_xlabel("wall time [s]")
        ax.set_title(which)
        ax.grid(alpha=0.3, which="both")
    axes[0].set_ylabel("L1 density error")
    axes[0].legend(fontsize=8)
    fig.suptitle("modified Sod problem (paper 9.4): error against run time, N = " + ", ".join(map(str, sizes)))
    RESULTS.mkdir(parents=True, exist_ok=True)
    path = RESULTS / ("coupled_modified_sod_error_vs_time" + ("_quick" if args.quick else "") + ".png")
    fig.savefig(path, dpi=120, bbox_inches="tight")
    print(f"\nplot: {path.relative_to(ROOT)}; runs in {work}")


if __name__ == "__main__":
    main()
