#!/usr/bin/python3
"""The flagship figure of configs/tungsten_blast_3d.yaml (after the method paper's Fig. 10) from a run directory.

On the mid-plane z = 0.5, at three times (before, at and after the particle cloud's impact on the target):
  top row     the air's velocity, its magnitude as colour and its direction as arrows;
  middle row  the particles' (tungsten's) mass fraction alpha_t rho_t / (alpha_a rho_a + alpha_t rho_t);
  both with the target's element layer next to the mid-plane coloured by its von Mises stress;
  bottom row  the force each phase puts on the target along x over time, and each phase's share of the impulse
              delivered so far, from the coupler's coupler/interface_phases.csv (per cycle and phase,
              F_k = -sum_faces (alpha_k / sum_j alpha_j) p_I,k A n_x; the shares add up to the force of
              coupler/interface_history.csv).
Impact: the first time the particles' force reaches a tenth of its peak; "before" and "after" are the snapshots
nearest to half and three times that time (or the ones --times names).

Usage: /usr/bin/python3 scripts/plot_flagship.py RUN_DIR [--out PNG] [--times T1 T2 T3] [--caption TEXT]
(default output RUN_DIR/flagship.png). Needs matplotlib and h5py (scripts/install_deps.sh).
"""
import argparse
import csv
import glob
import os
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402


def fail(msg):
    print("plot_flagship.py: error: " + msg, file=sys.stderr)
    sys.exit(2)


def read_csv(path):
    """Columns of a CSV file as numpy arrays, by name."""
    try:
        with open(path) as fh:
            rows = list(csv.reader(fh))
    except OSError as e:
        fail("%s: %s" % (path, e.strerror))
    if len(rows) < 2:
        fail("%s: no rows" % path)
    header = rows[0]
    data = np.array([[float(v) for v in r] for r in rows[1:] if len(r) == len(header)])
    return {name: data[:, i] for i, name in enumerate(header)}


def snapshots(run, solver):
    """[(time, file)] of a solver's snapshots, by time."""
    out = []
    for fn in glob.glob(os.path.join(run, solver, solver + "_*.h5")):
        with h5py.File(fn, "r") as f:
            out.append((float(f.attrs["time"]), fn))
    if not out:
        fail("%s: no %s snapshots (%s_*.h5)" % (os.path.join(run, solver), solver, solver))
    return sorted(out)


def nearest(snaps, t):
    return min(snaps, key=lambda s: abs(s[0] - t))


def fluid_plane(fn):
    """Mid-plane (z index n/2) fields of a fluid snapshot, arrays [y, x]: air velocity (x, y), |u| and the
    tungsten mass fraction, flow cells only (NaN inside the target)."""
    with h5py.File(fn, "r") as f:
        cells = f["cell"]
        for name in ("air_velocity", "air_alpha", "air_density", "tungsten_alpha", "tungsten_density"):
            if name not in cells:
                fail("%s: no cell/%s (a run of configs/tungsten_blast_3d.yaml expected)" % (fn, name))
        mid = cells["air_alpha"].shape[0] // 2
        u = cells["air_velocity"][mid]
        ma = cells["air_alpha"][mid] * cells["air_density"][mid]
        mt = cells["tungsten_alpha"][mid] * cells["tungsten_density"][mid]
        flow = cells["embedded_category"][mid] <= 1 if "embedded_category" in cells else np.ones(ma.shape, bool)
    mask = np.where(flow, 1.0, np.nan)
    speed = np.hypot(u[..., 0], u[..., 1]) * mask  # in the plane; |u_z| is 0 on the symmetry plane
    return u[..., 0] * mask, u[..., 1] * mask, speed, mt / (ma + mt) * mask


def target_layer(fn):
    """The target's element layer next to z = 0.5: (x-y outlines, von Mises [Pa])."""
    with h5py.File(fn, "r") as f:
        xyz = f["grid/coordinates"][...]
        conn = f["grid/connectivity"][...]
        vm = f["cell/von_mises"][...]
    corners = xyz[conn]
    cz = corners[:, :, 2].mean(axis=1)
    layer = np.abs(cz - cz[np.argmin(np.abs(cz - 0.5))]) < 1e-6 + 0.25 * np.ptp(corners[0, :, 2])
    boxes = [[(c[:, 0].min(), c[:, 1].min()), (c[:, 0].max(), c[:, 1].min()), (c[:, 0].max(), c[:, 1].max()),
              (c[:, 0].min(), c[:, 1].max())] for c in corners[layer]]
    return boxes, vm[layer]


def impulse_shares(run):
    """Times, force x per phase and the cumulative impulse per phase (the force of cycle n acts over its step)."""
    path = os.path.join(run, "coupler", "interface_phases.csv")
    if not os.path.exists(path):
        fail("%s: missing (the coupler writes it for a fluid of two or more phases)" % path)
    ph = read_csv(path)
    names = [c[: -len("_force_x")] for c in ph if c.endswith("_force_x")]
    t = ph["time"]
    dt = np.diff(t, append=t[-1])
    force = {n: ph[n + "_force_x"] for n in names}
    impulse = {n: np.cumsum(force[n] * dt) for n in names}
    return t, force, impulse


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run", help="the run directory of configs/tungsten_blast_3d.yaml")
    ap.add_argument("--out", help="PNG to write (default RUN/flagship.png)")
    ap.add_argument("--times", type=float, nargs=3, help="the three times [s] (default: around the impact)")
    ap.add_argument("--caption", default="", help="a line under the title (e.g. the resolution)")
    a = ap.parse_args()
    out = a.out or os.path.join(a.run, "flagship.png")

    t, force, impulse = impulse_shares(a.run)
    fsnaps, ssnaps = snapshots(a.run, "fluid"), snapshots(a.run, "solid")
    particles = [n for n in force if n != "air"][0] if len(force) > 1 else None
    if a.times:
        wanted = a.times
    else:
        f = force[particles] if particles else sum(force.values())
        t_hit = t[np.argmax(f >= 0.1 * f.max())]
        wanted = [0.5 * t_hit, t_hit, 3.0 * t_hit]
    picks = []
    for w in wanted:  # three different snapshots, each the nearest one not taken
        rest = [s for s in fsnaps if s not in picks] or fsnaps
        picks.append(nearest(rest, w))
    picks.sort()
    labels = ["before impact", "at impact", "after impact"]

    planes = [fluid_plane(fn) for _, fn in picks]
    targets = [target_layer(nearest(ssnaps, tf)[1]) for tf, _ in picks]
    vmax_u = max(np.nanmax(p[2]) for p in planes)
    vmax_vm = max(1.0, max(float(np.max(vm)) for _, vm in targets)) / 1e6

    fig = plt.figure(figsize=(15, 13.5))
    gs = fig.add_gridspec(3, 6, height_ratios=[1, 1, 0.8], width_ratios=[1, 1, 1, 0.05, 0.12, 0.05], hspace=0.3,
                          wspace=0.3)
    n = planes[0][2].shape[0]
    extent = [0, 1, 0, 1]
    step = max(1, n // 20)
    xc = (np.arange(n) + 0.5) / n
    for col, ((tf, _), (ux, uy, speed, ymass), (boxes, vm)) in enumerate(zip(picks, planes, targets)):
        for row, (field, cmap, vmax, label) in enumerate(
                [(speed, "viridis", vmax_u, "air |u| [m/s]"), (ymass, "magma", 1.0, "tungsten mass fraction [-]")]):
            ax = fig.add_subplot(gs[row, col])
            im = ax.imshow(field, origin="lower", extent=extent, cmap=cmap, vmin=0, vmax=vmax)
            if row == 0:
                ax.quiver(xc[::step], xc[::step], ux[::step, ::step], uy[::step, ::step], color="white",
                          scale=25 * vmax_u, width=0.003)
            pc = PolyCollection(boxes, array=vm / 1e6, cmap="Greys", edgecolors="none")
            pc.set_clim(0, vmax_vm)
            ax.add_collection(pc)
            ax.set_xlim(0, 1)
            ax.set_ylim(0, 1)
            ax.set_title("%s, t = %.3f ms\nair velocity" % (labels[col], tf * 1e3) if row == 0 else
                         "tungsten mass fraction", fontsize=10)
            ax.set_xlabel("x [m]")
            if col == 0:
                ax.set_ylabel("y [m]")
            if col == 2:
                fig.colorbar(im, cax=fig.add_subplot(gs[row, 3]), label=label)
    fig.colorbar(pc, cax=fig.add_subplot(gs[0:2, 5]), label="target von Mises stress [MPa] (element layer at z = 0.5)")

    ax = fig.add_subplot(gs[2, 0:2])
    colours = {"air": "tab:blue"}
    for name in force:
        ax.plot(t * 1e3, force[name] / 1e3, label="%s" % name, color=colours.get(name, "tab:red"))
    ax.plot(t * 1e3, sum(force.values()) / 1e3, color="k", lw=0.8, label="total")
    for tf, _ in picks:
        ax.axvline(tf * 1e3, color="grey", ls=":", lw=0.8)
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("force on the target along x [kN]")
    ax.legend(loc="upper right")
    ax.set_title("force each phase puts on the target (coupler, per cycle)", fontsize=11)
    ax = fig.add_subplot(gs[2, 2:6])
    total = sum(impulse.values())
    # The shares from when the target has had a thousandth of its final impulse (before: round-off of nothing).
    safe = np.where(np.abs(total) > 1e-3 * abs(total[-1]), total, np.nan)
    base = np.zeros_like(t)
    for name in impulse:
        share = impulse[name] / safe
        ax.fill_between(t * 1e3, base, base + share, color=colours.get(name, "tab:red"), alpha=0.75,
                        label="%s: %.0f%% of %.0f N s" % (name, 100 * share[-1], total[-1]))
        base = base + share
    for tf, _ in picks:
        ax.axvline(tf * 1e3, color="grey", ls=":", lw=0.8)
    ax.set_ylim(0, 1)
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("share of the impulse so far")
    ax.legend(loc="lower left", fontsize=9)
    ax.set_title("impulse on the target by phase", fontsize=11)
    fig.suptitle("tungsten-laden blast on a steel target (configs/tungsten_blast_3d.yaml), mid-plane z = 0.5"
                 + ("\n" + a.caption if a.caption else ""), fontsize=13)
    fig.savefig(out, dpi=90, bbox_inches="tight")
    print("wrote %s (snapshots at %s ms; impulse %s)" % (
        out, ", ".join("%.3f" % (tf * 1e3) for tf, _ in picks),
        ", ".join("%s %.4g N s" % (k, v[-1]) for k, v in impulse.items())))


if __name__ == "__main__":
    main()
