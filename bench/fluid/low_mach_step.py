#!/usr/bin/python3
"""Paper 9.1: Mach 0.05 flow over a step, with and without the low-Mach correction.

Runs configs/low_mach_step.yaml (a block 0.3 x 0.35 on the floor) without the correction and with it for
each cutoff Mach number of --cutoffs (fluid.numerics.low_mach_cutoff, default 0: z = min(1, max(M_L, M_R))),
side by side (one thread each), 640 x 320 by default (--cells for a smaller run). Prints the enstrophy of the
wake at every snapshot (8 per run) and plots the vorticity of the last snapshots with the enstrophy history.
Writes bench/results/low_mach_step_vorticity[_TAG].png. Usage:
  /usr/bin/python3 bench/fluid/low_mach_step.py [--cells 640 320] [--end 20] [--cutoffs 0 0.05] [--tag T]
"""
import argparse
import glob
import os
import shutil
import subprocess

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SNAPSHOTS = 8


def start(low_mach, cells, end, out, cutoff=0.0):
    cmd = [os.path.join(ROOT, "build", "bin", "fluid_solver"), os.path.join(ROOT, "configs", "low_mach_step.yaml"),
           "--out", out, "--quiet", "--set", f"fluid.numerics.low_mach={'true' if low_mach else 'false'}",
           "--set", f"fluid.numerics.low_mach_cutoff={cutoff}", "--set", f"fluid.mesh.cells=[{cells[0]}, {cells[1]}]",
           "--set", f"fluid.time.end={end}", "--set", f"fluid.output.interval={end / SNAPSHOTS}"]
    return subprocess.Popen(cmd, env=dict(os.environ, OMP_NUM_THREADS="1"))


def vorticity(path):
    """Time, vorticity (NaN inside the step) and enstrophy (integral of w^2 over the flow) of one snapshot."""
    with h5py.File(path, "r") as f:
        g = f["grid"].attrs
        dx, dy = g["spacing"][0], g["spacing"][1]
        u = f["cell"]["gas_velocity"][()]
        kind = f["cell"]["embedded_category"][()]
        t = float(f.attrs["time"])
    w = np.gradient(u[..., 1], dx, axis=1) - np.gradient(u[..., 0], dy, axis=0)
    w[kind > 1] = np.nan
    return t, w, np.nansum(w ** 2) * dx * dy


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--cells", type=int, nargs=2, default=[640, 320])
    ap.add_argument("--end", type=float, default=20.0)
    ap.add_argument("--cutoffs", type=float, nargs="+", default=[0.0])
    ap.add_argument("--tag", default="")
    a = ap.parse_args()
    out_dir = os.path.join(ROOT, "runs", "low_mach_step_bench")
    cases = [("without the correction", False, 0.0)] + [(f"with the correction, cutoff {c:g}", True, c) for c in a.cutoffs]
    outs = [os.path.join(out_dir, f"{'with' if lm else 'without'}_{c:g}") for _, lm, c in cases]
    for out in outs:  # no snapshots of an earlier run mixed into this one's
        shutil.rmtree(out, ignore_errors=True)
    procs = [start(lm, a.cells, a.end, out, c) for (_, lm, c), out in zip(cases, outs)]
    for p in procs:
        if p.wait() != 0:
            raise SystemExit(f"fluid_solver failed (exit {p.returncode})")
    history = [[vorticity(f) for f in sorted(glob.glob(os.path.join(out, "fluid_*.h5")))] for out in outs]

    print("| t | " + " | ".join(label for label, _, _ in cases) + " | ratio |")
    print("|---" * (len(cases) + 2) + "|")
    for i in range(1, len(history[0])):
        z = [h[i][2] for h in history]
        print(f"| {history[0][i][0]:g} | " + " | ".join(f"{v:.4g}" for v in z) + f" | {z[-1] / z[0]:.2f} |")

    last = [h[-1] for h in history]
    vmax = np.nanpercentile(np.abs(last[-1][1]), 99)
    fig, axes = plt.subplots(len(cases) + 1, 1, figsize=(9, 3.75 * (len(cases) + 1)), squeeze=False)
    for ax, (label, _, _), (t, w, ens) in zip(axes[:, 0], cases, last):
        im = ax.imshow(w, origin="lower", extent=[0, 2, 0, 1], cmap="RdBu_r", vmin=-vmax, vmax=vmax)
        ax.set_title(f"vorticity at t = {t:g}, {label} (enstrophy {ens:.3g})", fontsize=10)
        fig.colorbar(im, ax=ax, shrink=0.8)
    ax = axes[-1, 0]
    for (label, _, _), h in zip(cases, history):
        ax.plot([s[0] for s in h], [s[2] for s in h], "o-", label=label)
    ax.set_xlabel("t")
    ax.set_ylabel("enstrophy")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.suptitle(f"Mach 0.05 flow over a step, {a.cells[0]} x {a.cells[1]}")
    fig.tight_layout()
    os.makedirs(os.path.join(ROOT, "bench", "results"), exist_ok=True)
    png = os.path.join(ROOT, "bench", "results", f"low_mach_step_vorticity{'_' + a.tag if a.tag else ''}.png")
    fig.savefig(png, dpi=100)
    print(f"plot: {png}")


if __name__ == "__main__":
    main()
