#!/usr/bin/python3
"""Plots of the deformable-structure scenes of the method paper, from their run directories.

  plot_paper_scenes.py sod RUN [--eulerian DIR] [--out DIR]
      Scene 9.4 (configs/modified_sod_2d.yaml, modified_sod_square_2d.yaml), paper Fig. 8: density, velocity and
      pressure along y = 0.5 on the background (flow cells) and the foreground (element centres near y = 0.5)
      with the exact Riemann solution (and the plain Eulerian run without the foreground, if given); the
      foreground mesh drawn over the background density at three times. Writes modified_sod_profiles.png and
      modified_sod_meshes.png.
  plot_paper_scenes.py panel EMBEDDED CONFORMING [--out DIR]
      Scene 9.5 (configs/shock_panel_2d.yaml and its conforming reference), paper Fig. 9: the velocity
      magnitude of both runs side by side at the snapshots nearest 0.2 ms and 0.65 ms with the panel deformed,
      and the panel's mass-averaged velocity of both runs over time (solid/block_history.csv). Writes
      shock_panel_fields.png and shock_panel_velocity.png.

EMBEDDED and RUN are `cosim run` directories (fluid/, solid/); CONFORMING and --eulerian are the output
directories of a standalone solid_solver / fluid_solver run. Plots go to --out (default RUN/plots).
"""
import argparse
import csv
import math
import os

import matplotlib
import numpy as np

from cosim.series import Series
from cosim.snapshot import Snapshot

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

GAMMA = 1.4


def series(directory, prefix):
    """The snapshot series `prefix` of a run directory (in DIR/prefix/ or DIR itself), as its XDMF index lists it."""
    sub = os.path.join(directory, prefix)
    return Series(prefix, sub if os.path.isdir(sub) else directory)


def snapshots(directory, prefix):
    """Paths of the snapshots of series(directory, prefix), in time order."""
    return [str(p) for p in series(directory, prefix).files]


def read_fluid(path, phase):
    """Grid and the fields of `phase` of a fluid snapshot; flow: the cells outside any body."""
    snap = Snapshot.open(path)
    g = snap.grid
    f = {"t": snap.time, "nx": g.cells[0], "ny": g.cells[1], "x0": g.origin, "dx": g.spacing}
    f["rho"] = snap[f"{phase}_density"]
    f["p"] = snap[f"{phase}_pressure"]
    f["vel"] = snap[f"{phase}_velocity"]
    cat = snap["embedded_category"] if "embedded_category" in snap else np.zeros_like(f["rho"])
    f["flow"] = cat <= 1
    return f


def read_solid(path):
    """Mesh, density, pressure, block and node velocity of a solid snapshot."""
    snap = Snapshot.open(path)
    s = {"t": snap.time, "x": snap.grid.coordinates, "conn": snap.grid.connectivity}
    for k in ("density", "pressure", "block"):
        s[k] = snap.cell[k]
    s["v"] = snap.node["velocity"]
    return s


def exact_sod(x, t, left=(1.0, -0.5, 1.0), right=(0.125, 0.0, 0.1), x0=0.5):
    """Exact Riemann solution (Toro ch. 4) for the paper's modified Sod states, ideal gas gamma 1.4."""
    g = GAMMA
    rl, ul, pl = left
    rr, ur, pr = right
    cl, cr = math.sqrt(g * pl / rl), math.sqrt(g * pr / rr)

    def f(p, rk, pk, ck):
        if p > pk:
            a, b = 2 / ((g + 1) * rk), (g - 1) / (g + 1) * pk
            return (p - pk) * math.sqrt(a / (p + b))
        return 2 * ck / (g - 1) * ((p / pk) ** ((g - 1) / (2 * g)) - 1)

    lo, hi = 1e-10, 100.0
    for _ in range(200):
        m = 0.5 * (lo + hi)
        if f(m, rl, pl, cl) + f(m, rr, pr, cr) + ur - ul > 0:
            hi = m
        else:
            lo = m
    ps = 0.5 * (lo + hi)
    us = 0.5 * (ul + ur) + 0.5 * (f(ps, rr, pr, cr) - f(ps, rl, pl, cl))
    shock = ur + cr * math.sqrt((g + 1) / (2 * g) * ps / pr + (g - 1) / (2 * g))
    rsr = rr * (ps / pr + (g - 1) / (g + 1)) / ((g - 1) / (g + 1) * ps / pr + 1)
    rsl, csl = rl * (ps / pl) ** (1 / g), cl * (ps / pl) ** ((g - 1) / (2 * g))
    out = np.zeros((3, len(x)))
    for i, s in enumerate((np.asarray(x) - x0) / t):
        if s < ul - cl:
            out[:, i] = left
        elif s < us - csl:
            c = 2 / (g + 1) * (cl + (g - 1) / 2 * (ul - s))
            out[:, i] = (rl * (c / cl) ** (2 / (g - 1)), 2 / (g + 1) * (cl + (g - 1) / 2 * ul + s),
                         pl * (c / cl) ** (2 * g / (g - 1)))
        elif s < us:
            out[:, i] = (rsl, us, ps)
        elif s < shock:
            out[:, i] = (rsr, us, ps)
        else:
            out[:, i] = right
    return out


def element_centres(s):
    return s["x"][s["conn"]].mean(axis=1)


def mesh_polygons(s):
    return s["x"][s["conn"]][:, :, :2]


def save(fig, out_dir, name):
    os.makedirs(out_dir, exist_ok=True)
    path = os.path.join(out_dir, name)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)
    print(path)


def plot_sod(run, eulerian, out_dir):
    fl, sl = snapshots(run, "fluid"), snapshots(run, "solid")
    f, s = read_fluid(fl[-1], "gas"), read_solid(sl[-1])
    j = f["ny"] // 2
    xc = f["x0"][0] + (np.arange(f["nx"]) + 0.5) * f["dx"][0]
    row = f["flow"][j]
    c = element_centres(s)
    ny_el = max(1, int(round(math.sqrt(len(c)))))
    near = np.abs(c[:, 1] - 0.5) < 0.6 / ny_el
    order = np.argsort(c[near, 0])
    xe = c[near, 0][order]
    ue = s["v"][s["conn"]][:, :, 0].mean(axis=1)[near][order]
    xs = np.linspace(0, 1, 2000)
    ex = exact_sod(xs, f["t"])
    ref = None
    if eulerian:
        ref = read_fluid(snapshots(eulerian, "fluid")[-1], "gas")
    fig, axes = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    for k, (name, bg, fg) in enumerate((("density [kg/m$^3$]", f["rho"][j], s["density"][near][order]),
                                        ("velocity [m/s]", f["vel"][j, :, 0], ue),
                                        ("pressure [Pa]", f["p"][j], s["pressure"][near][order]))):
        ax = axes[k]
        ax.plot(xs, ex[k], "k-", lw=1, label="exact")
        if ref is not None:
            rq = (ref["rho"], ref["vel"][:, :, 0], ref["p"])[k][ref["ny"] // 2]
            ax.plot(xc, rq, "-", color="0.6", lw=1, label="Eulerian, no foreground")
        ax.plot(xc[row], bg[row], "o", ms=3, mfc="none", color="tab:blue", label="background (flow cells)")
        ax.plot(xe, fg, "s", ms=3, color="tab:red", label="foreground (element centres)")
        ax.set_ylabel(name)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    axes[0].set_title(f"modified Sod problem (paper 9.4) along y = 0.5 at t = {f['t']:.3g} s, "
                      f"{f['nx']} x {f['ny']} background, {len(c)} foreground elements")
    axes[-1].set_xlabel("x [m]")
    save(fig, out_dir, "modified_sod_profiles.png")

    picks = [0, len(sl) // 2, len(sl) - 1]
    fig, axes = plt.subplots(1, 3, figsize=(15, 5))
    for ax, k in zip(axes, picks):
        fk, sk = read_fluid(fl[k], "gas"), read_solid(sl[k])
        rho = np.where(fk["flow"], fk["rho"], np.nan)
        ext = [fk["x0"][0], fk["x0"][0] + fk["nx"] * fk["dx"][0], fk["x0"][1], fk["x0"][1] + fk["ny"] * fk["dx"][1]]
        im = ax.imshow(rho, origin="lower", extent=ext, cmap="viridis", vmin=0.1, vmax=1.0)
        ax.add_collection(PolyCollection(mesh_polygons(sk), facecolors="none", edgecolors="w", linewidths=0.3))
        ax.set_title(f"t = {fk['t']:.3g} s")
        ax.set_aspect("equal")
    fig.colorbar(im, ax=axes, shrink=0.8, label="background density [kg/m$^3$]")
    save(fig, out_dir, "modified_sod_meshes.png")


def block_velocity(path, block):
    t, v = [], []
    with open(path) as fh:
        for r in csv.DictReader(fh):
            if r["block"] == block:
                t.append(float(r["time"]))
                v.append(float(r["velocity_x"]))
    return np.array(t), np.array(v)


def nearest(files, times, target):
    return files[int(np.argmin(np.abs(np.array(times) - target)))]


def plot_panel(embedded, conforming, out_dir):
    fs, cs = series(embedded, "fluid"), series(conforming, "solid")
    fl, sl, cl = snapshots(embedded, "fluid"), snapshots(embedded, "solid"), snapshots(conforming, "solid")
    ft, ct = list(fs.times), list(cs.times)
    fig, axes = plt.subplots(2, 2, figsize=(11, 10))
    for row, target in enumerate((2.0e-4, 6.5e-4)):
        f = read_fluid(nearest(fl, ft, target), "air")
        s = read_solid(nearest(sl, ft, target))
        speed = np.where(f["flow"], np.linalg.norm(f["vel"][..., :2], axis=-1), np.nan)
        ext = [f["x0"][0], f["x0"][0] + f["nx"] * f["dx"][0], f["x0"][1], f["x0"][1] + f["ny"] * f["dx"][1]]
        c = read_solid(nearest(cl, ct, target))
        cv = np.linalg.norm(c["v"][c["conn"]][:, :, :2].mean(axis=1), axis=-1)
        vmax = np.nanmax(speed)
        ax = axes[row, 0]
        im = ax.imshow(speed, origin="lower", extent=ext, cmap="inferno", vmin=0, vmax=vmax)
        ax.add_collection(PolyCollection(mesh_polygons(s), facecolors="0.7", edgecolors="k", linewidths=0.3))
        ax.set_title(f"embedded, t = {f['t'] * 1e3:.3g} ms")
        ax = axes[row, 1]
        gas = c["block"] != c["block"].max()
        pc = PolyCollection(mesh_polygons(c)[gas], array=cv[gas], cmap="inferno", edgecolors="face", linewidths=0,
                            antialiased=False)
        pc.set_clim(0, vmax)
        ax.add_collection(pc)
        ax.add_collection(PolyCollection(mesh_polygons(c)[~gas], facecolors="0.7", edgecolors="k", linewidths=0.3))
        ax.set_title(f"conforming (ALE air), t = {c['t'] * 1e3:.3g} ms")
        for a in axes[row]:
            a.set_xlim(0, 1)
            a.set_ylim(0, 1)
            a.set_aspect("equal")
        fig.colorbar(im, ax=axes[row].tolist(), shrink=0.8, label="velocity magnitude [m/s]")
    save(fig, out_dir, "shock_panel_fields.png")

    te, ve = block_velocity(os.path.join(embedded, "solid", "block_history.csv"), "panel")
    tc, vc = block_velocity(os.path.join(conforming, "block_history.csv"), "panel")
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(te * 1e3, ve, label="embedded (fluid_solver + solid_solver)")
    ax.plot(tc * 1e3, vc, "--", label="conforming (solid_solver, ALE air)")
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("panel mean velocity $u_x$ [m/s]")
    ax.set_title("blast on a steel panel (paper 9.5, Fig. 9b)")
    ax.grid(alpha=0.3)
    ax.legend()
    save(fig, out_dir, "shock_panel_velocity.png")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="scene", required=True)
    a = sub.add_parser("sod")
    a.add_argument("run")
    a.add_argument("--eulerian")
    a.add_argument("--out")
    b = sub.add_parser("panel")
    b.add_argument("embedded")
    b.add_argument("conforming")
    b.add_argument("--out")
    args = ap.parse_args()
    if args.scene == "sod":
        plot_sod(args.run, args.eulerian, args.out or os.path.join(args.run, "plots"))
    else:
        plot_panel(args.embedded, args.conforming, args.out or os.path.join(args.embedded, "plots"))


if __name__ == "__main__":
    main()
