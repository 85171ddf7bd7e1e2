#!/usr/bin/python3
"""Pictures of a fluid_solver run directory: the last snapshot's fields as PNGs.

1D: profiles of density, velocity, pressure (and volume fraction) per phase.
2D/3D: colour maps (3D: the mid-plane z slice) of density, pressure, speed and volume fraction.
Usage: /usr/bin/python3 scripts/plot_fluid.py RUN_DIR [--snapshot N]
"""
import argparse
import glob
import os

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def load(path):
    with h5py.File(path, "r") as f:
        g = f["grid"].attrs
        dim = int(g["dim"])
        cells = [int(c) for c in g["cells"]]
        origin = np.array(g["origin"], dtype=float)
        spacing = np.array(g["spacing"], dtype=float)
        fields = {k: f["cell"][k][()] for k in f["cell"].keys()}
        t = float(f.attrs["time"])
    return dim, cells, origin, spacing, fields, t


def phase_names(fields):
    return sorted({k.rsplit("_", 1)[0] for k in fields if k.endswith("_density") and not k.startswith("mixture")})


def plot_1d(out, cells, origin, spacing, fields, t):
    x = origin[0] + (np.arange(cells[0]) + 0.5) * spacing[0]
    names = phase_names(fields)
    rows = [("density", "density [kg/m^3]"), ("velocity", "velocity [m/s]"), ("pressure", "pressure [Pa]")]
    if len(names) > 1:
        rows.append(("alpha", "volume fraction"))
    fig, axes = plt.subplots(len(rows), 1, figsize=(7, 2.2 * len(rows)), sharex=True)
    for ax, (key, label) in zip(axes, rows):
        for n in names:
            v = fields[f"{n}_{key}"]
            ax.plot(x, v[:, 0] if v.ndim == 2 else v, label=n, lw=1.2)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].legend()
    axes[0].set_title(f"t = {t:.4g} s")
    axes[-1].set_xlabel("x [m]")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def plot_2d(out, dim, cells, origin, spacing, fields, t):
    names = phase_names(fields)
    def plane(v):
        if dim == 3:
            v = v[v.shape[0] // 2]
        return v
    maps = []
    pre = "mixture" if len(names) > 1 else names[0]
    maps.append((f"{pre} density [kg/m^3]", plane(fields[f"{pre}_density"])))
    maps.append((f"{pre} pressure [Pa]", plane(fields[f"{pre}_pressure"])))
    vel = plane(fields[f"{pre}_velocity"])
    maps.append((f"{pre} speed [m/s]", np.sqrt((vel ** 2).sum(axis=-1))))
    if len(names) > 1:
        maps.append((f"{names[1]} volume fraction", plane(fields[f"{names[1]}_alpha"])))
    ext = [origin[0], origin[0] + cells[0] * spacing[0], origin[1], origin[1] + cells[1] * spacing[1]]
    fig, axes = plt.subplots(1, len(maps), figsize=(4.2 * len(maps), 3.8))
    for ax, (label, v) in zip(np.atleast_1d(axes), maps):
        im = ax.imshow(v, origin="lower", extent=ext, cmap="viridis", aspect="equal")
        ax.set_title(label, fontsize=9)
        fig.colorbar(im, ax=ax, shrink=0.8)
    fig.suptitle(f"t = {t:.4g} s" + (" (mid-plane z slice)" if dim == 3 else ""))
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("run_dir")
    ap.add_argument("--snapshot", type=int, default=-1)
    a = ap.parse_args()
    snaps = sorted(glob.glob(os.path.join(a.run_dir, "fluid_*.h5")))
    if not snaps:
        raise SystemExit(f"{a.run_dir}: no fluid_*.h5 snapshots")
    dim, cells, origin, spacing, fields, t = load(snaps[a.snapshot])
    out = os.path.join(a.run_dir, "fields.png")
    if dim == 1:
        plot_1d(out, cells, origin, spacing, fields, t)
    else:
        plot_2d(out, dim, cells, origin, spacing, fields, t)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
