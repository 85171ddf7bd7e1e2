#!/usr/bin/python3
"""Error against run time of the three embedded wall treatments, on the two scenes with a deformable structure
and a measure of accuracy, side by side in one run through `cosim run`:

- first-order walls (`fluid.embedded.order: 1`),
- second-order walls (`order: 2`, the default; docs/methods.md §5.5),
- the conservative boundary on second-order walls (`order: 2`, `conservative: true`; methods §5.8);

on the blast on a steel panel (paper 9.5, configs/shock_panel_2d.yaml, panel n/10 x n/2, to 1 ms: the error of the
panel's peak mean x velocity against the default at the finest size) and on the modified Sod problem (paper 9.4,
configs/modified_sod_2d.yaml under its Robin conditions, foreground N/4: the L1 density error against the exact
solution at t = 0.28, background flow cells and foreground elements). Wall times are of the whole command (median
of --repeat runs, the variants' order rotated per repeat).

Prints markdown tables and writes bench/results/coupled_wall_treatments.png (the error-against-time plot of both
scenes, one curve per treatment).

Usage: bench/coupled/run_wall_treatments.py [--quick] [--repeat N] [--build DIR] [--work DIR]
"""
import argparse
import sys
import tempfile
from pathlib import Path

import matplotlib

from bench_common import RESULTS, ROOT, panel_history, provenance, run_rotated, timed_run
from run_modified_sod import l1_errors

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TREATMENTS = [("first order", ["--set", "fluid.embedded.order=1"]),
              ("second order (default)", ["--set", "fluid.embedded.order=2"]),
              ("conservative", ["--set", "fluid.embedded.order=2", "--set", "fluid.embedded.conservative=true"])]
STYLE = {"first order": "o--", "second order (default)": "s-", "conservative": "^-."}


def run_treatments(cosim, work, repeat, label, scene, sizes, solid_cells, measure):
    """{(treatment, n): measure's dict of the first round's run, with the median wall time `wall`}: the scene (a
    configs/ file) on an n x n background, its solid on solid_cells(n) cells, for each n in sizes and each treatment
    (the treatments' order rotated per round), into work/<label>_<treatment>_<n>_<round>; measure(out) reads a run's
    output folder."""
    names = [t[0] for t in TREATMENTS]
    sets = dict(TREATMENTS)

    def out_dir(name, n, r):
        return work / f"{label}_{name.split()[0]}_{n}_{r}"

    results = {}
    for n in sizes:
        def one(name, r, n=n):
            out = out_dir(name, n, r)
            return timed_run([cosim, "run", str(ROOT / "configs" / scene), "--out", str(out), "--quiet", "--set",
                              f"fluid.mesh.cells=[{n},{n}]", "--set", f"solid.mesh.cells={solid_cells(n)}"]
                             + sets[name], str(out) + ".log")
        wall = run_rotated(names, repeat, one)
        for name in names:
            results[(name, n)] = dict(measure(out_dir(name, n, 0)), wall=wall[name])
    return results


def panel_peak(out):
    """The panel's peak mean x velocity of a run."""
    return dict(peak=float(panel_history(out / "solid" / "block_history.csv")[1].max()))


def sod_errors(out):
    """L1(rho) against the exact solution: background flow cells, foreground elements, the domain (both)."""
    bg, fg, dom = l1_errors(str(out), domain=True)
    return dict(bg=bg, fg=fg, dom=dom)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="panel 50, 100; Sod 32, 64; one repeat")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--work", default=None)
    args = ap.parse_args()
    cosim = str(Path(args.build) / "bin" / "cosim")
    work = Path(args.work or tempfile.mkdtemp(prefix="cosim_wall_treatments_"))
    work.mkdir(parents=True, exist_ok=True)
    repeat = 1 if args.quick else args.repeat
    names = [t[0] for t in TREATMENTS]

    # 9.5: the panel's peak against the default at the finest size.
    panel_sizes = [50, 100] if args.quick else [50, 100, 200]
    panel = run_treatments(cosim, work, repeat, "panel", "shock_panel_2d.yaml", panel_sizes,
                           lambda n: f"[{n // 10},{n // 2}]", panel_peak)
    ref = panel[("second order (default)", max(panel_sizes))]["peak"]

    # 9.4: L1(rho) against the exact solution.
    sod_sizes = [32, 64] if args.quick else [32, 64, 128, 256]
    sod = run_treatments(cosim, work, repeat, "sod", "modified_sod_2d.yaml", sod_sizes,
                         lambda n: f"[{n // 4},{n // 4}]", sod_errors)

    print(f"Embedded wall treatments; {provenance(Path(args.build) / 'bin')}; median of {repeat} run(s)\n")
    print(f"Blast on a steel panel (9.5), panel n/10 x n/2; reference: the default at {max(panel_sizes)}^2, peak "
          f"{ref:.2f} m/s\n")
    print("| walls | background | panel peak [m/s] | peak error | wall [s] |")
    print("|---|---|---|---|---|")
    for name in names:
        for n in panel_sizes:
            p = panel[(name, n)]
            print(f"| {name} | {n}^2 | {p['peak']:.2f} | {100 * abs(p['peak'] - ref) / ref:.1f}% | {p['wall']:.1f} |")
    print("\nModified Sod (9.4), L1(rho) at t = 0.28 against the exact solution\n")
    print("| walls | background / foreground | L1 background | L1 foreground | L1 domain | wall [s] |")
    print("|---|---|---|---|---|---|")
    for name in names:
        for n in sod_sizes:
            s = sod[(name, n)]
            print(f"| {name} | {n}^2 / {n // 4}^2 | {s['bg']:.4e} | {s['fg']:.4e} | {s['dom']:.4e} | {s['wall']:.1f} |")

    fig, axes = plt.subplots(1, 3, figsize=(16, 4.8))
    for name in names:
        w = [panel[(name, n)]["wall"] for n in panel_sizes]
        e = [max(abs(panel[(name, n)]["peak"] - ref) / ref, 1e-4) for n in panel_sizes]
        axes[0].loglog(w, e, STYLE[name], label=name)
        for k, key in enumerate(("bg", "fg")):
            axes[1 + k].loglog([sod[(name, n)]["wall"] for n in sod_sizes], [sod[(name, n)][key] for n in sod_sizes],
                               STYLE[name], label=name)
    for n in panel_sizes:
        axes[0].annotate(f"{n}^2", (panel[(names[0], n)]["wall"], max(abs(panel[(names[0], n)]["peak"] - ref) / ref,
                                                                      1e-4)), fontsize=7)
    for k, key in enumerate(("bg", "fg")):
        for n in sod_sizes:
            axes[1 + k].annotate(f"{n}^2", (sod[(names[0], n)]["wall"], sod[(names[0], n)][key]), fontsize=7)
    axes[0].set_title(f"9.5 panel: peak error against the default at {max(panel_sizes)}^2")
    axes[1].set_title("9.4 modified Sod: L1(rho), background")
    axes[2].set_title("9.4 modified Sod: L1(rho), foreground")
    for ax in axes:
        ax.set_xlabel("wall time of cosim run [s]")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    axes[0].set_ylabel("error")
    RESULTS.mkdir(parents=True, exist_ok=True)
    path = RESULTS / ("coupled_wall_treatments" + ("_quick" if args.quick else "") + ".png")
    fig.savefig(path, dpi=120, bbox_inches="tight")
    print(f"\nplot: {path.relative_to(ROOT)}; runs in {work}")


if __name__ == "__main__":
    sys.exit(main())
