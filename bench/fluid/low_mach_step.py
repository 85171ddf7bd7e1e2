#!/usr/bin/python3
"""Paper 9.1: Mach 0.05 flow over a step, with and without the low-Mach correction.

Runs configs/low_mach_step.yaml without the correction and with it for each cutoff Mach number of
--cutoffs (fluid.numerics.low_mach_cutoff, default 0: z = min(1, max(M_L, M_R))), 640 x 320 by default
(--cells for a smaller run), then plots the vorticity of the last snapshots and prints their enstrophy.
Writes bench/results/low_mach_step_vorticity[_TAG].png. Usage:
  /usr/bin/python3 bench/fluid/low_mach_step.py [--cells 640 320] [--end 12] [--cutoffs 0 0.05] [--tag T]
"""
import argparse
import glob
import os
import subprocess

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def run(low_mach, cells, end, out, cutoff=0.0):
    subprocess.run([os.path.join(ROOT, "build", "bin", "fluid_solver"), os.path.join(ROOT, "configs", "low_mach_step.yaml"),
                    "--out", out, "--quiet", "--set", f"fluid.numerics.low_mach={'true' if low_mach else 'false'}",
                    "--set", f"fluid.numerics.low_mach_cutoff={cutoff}",
                    "--set", f"fluid.mesh.cells=[{cells[0]}, {cells[1]}]", "--set", f"fluid.time.end={end}",
                    "--set", f"fluid.output.interval={end / 4}"], check=True)
    with h5py.File(sorted(glob.glob(os.path.join(out, "fluid_*.h5")))[-1], "r") as f:
        g = f["grid"].attrs
        dx, dy = g["spacing"][0], g["spacing"][1]
        u = f["cell"]["gas_velocity"][()]
        kind = f["cell"]["embedded_category"][()]
    w = np.gradient(u[..., 1], dx, axis=1) - np.gradient(u[..., 0], dy, axis=0)
    w[kind > 1] = np.nan
    enstrophy = np.nansum(w ** 2) * dx * dy
    return w, enstrophy


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--cells", type=int, nargs=2, default=[640, 320])
    ap.add_argument("--end", type=float, default=12.0)
    ap.add_argument("--cutoffs", type=float, nargs="+", default=[0.0])
    ap.add_argument("--tag", default="")
    a = ap.parse_args()
    out_dir = os.path.join(ROOT, "runs", "low_mach_step_bench")
    cases = [("without the correction", False, 0.0)] + [(f"with the correction, cutoff {c:g}", True, c) for c in a.cutoffs]
    res = [run(lm, a.cells, a.end, os.path.join(out_dir, f"{'with' if lm else 'without'}_{c:g}"), c) for _, lm, c in cases]
    vmax = np.nanpercentile(np.abs(res[-1][0]), 99)
    fig, axes = plt.subplots(len(cases), 1, figsize=(9, 3.75 * len(cases)), squeeze=False)
    for ax, (label, _, _), (w, ens) in zip(axes[:, 0], cases, res):
        im = ax.imshow(w, origin="lower", extent=[0, 2, 0, 1], cmap="RdBu_r", vmin=-vmax, vmax=vmax)
        ax.set_title(f"vorticity, {label} (enstrophy {ens:.3g})", fontsize=10)
        fig.colorbar(im, ax=ax, shrink=0.8)
    fig.suptitle(f"Mach 0.05 flow over a step, {a.cells[0]} x {a.cells[1]}, t = {a.end:g}")
    fig.tight_layout()
    os.makedirs(os.path.join(ROOT, "bench", "results"), exist_ok=True)
    png = os.path.join(ROOT, "bench", "results", f"low_mach_step_vorticity{'_' + a.tag if a.tag else ''}.png")
    fig.savefig(png, dpi=100)
    print("| run | enstrophy | ratio to without |\n|---|---|---|")
    for (label, _, _), (_, ens) in zip(cases, res):
        print(f"| {label} | {ens:.4g} | {ens / res[0][1]:.2f} |")
    print(f"plot: {png}")


if __name__ == "__main__":
    main()
