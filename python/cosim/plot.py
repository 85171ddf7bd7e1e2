"""Figures of a run (PNG, matplotlib with the Agg backend): what python/plot_run.py draws.

Each plot_* function writes one file into out_dir and prints its path.
"""
import math
import os

import matplotlib
import numpy as np

from .errors import RunDirError
from .piston import force as ode_force
from .tables import split_by

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

SOLID_CATEGORY = 4  # embedded_category: 0 fluid, 1 fluid cut, 2 solid cut, 3 ghost, 4 solid
LAST_FLOW_CATEGORY = 1  # categories above it are inside a body (their values are ghost states)
DPI = 110


def save(fig, out_dir, name):
    path = os.path.join(out_dir, name)
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    print(f"wrote {path}")
    return path


def plot_motion(hist, refs, title, out_dir):
    """motion.png: displacement and velocity of the structure (interface_history.csv) against time, with the
    reference curves refs ([{t, x, v, label, style}])."""
    t = hist["time"]
    fig, (ax_x, ax_v) = plt.subplots(2, 1, figsize=(11, 6.5), sharex=True)
    for comp in "xyz":
        disp = hist[f"centre_{comp}"] - hist[f"centre_{comp}"][0]
        vel = hist[f"velocity_{comp}"]
        scale = max(np.max(np.abs(hist["centre_x"] - hist["centre_x"][0])), 1e-30)
        if comp != "x" and np.max(np.abs(disp)) < 1e-3 * scale:  # would be a flat line on this scale
            if np.any(disp) or np.any(vel):
                print(f"motion in {comp} not plotted: max |displacement| {np.max(np.abs(disp)):.3g} m, "
                      f"max |velocity| {np.max(np.abs(vel)):.3g} m/s")
            continue
        ax_x.plot(t, disp, lw=1.6, label=f"coupled run ({comp})")
        ax_v.plot(t, vel, lw=1.6, label=f"coupled run ({comp})")
    for r in refs:
        ax_x.plot(r["t"], r["x"], **r["style"], label=r["label"])
        ax_v.plot(r["t"], r["v"], **r["style"], label=r["label"])
    ax_x.set_ylabel("displacement [m]")
    ax_v.set_ylabel("velocity [m/s]")
    ax_v.set_xlabel("time [s]")
    ax_x.set_title(title)
    for ax in (ax_x, ax_v):
        ax.grid(alpha=0.3)
    ax_x.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return save(fig, out_dir, "motion.png")


def plot_interface(hist, par, title, out_dir):
    """interface.png: area-mean interface pressure and the interface force against time (with the piston ODE's
    force at the run's displacement when par, the ODE's parameters, is given)."""
    t = hist["time"]
    fig, (ax_p, ax_f) = plt.subplots(2, 1, figsize=(11, 6.5), sharex=True)
    ax_p.plot(t, hist["pressure"], lw=1.4, color="C0")
    ax_p.set_ylabel("mean interface pressure [Pa]\n(area mean over all faces)")
    for comp in "xyz":
        f = hist[f"force_{comp}"]
        if comp == "x" or np.max(np.abs(f)) > 1e-3 * np.max(np.abs(hist["force_x"])):
            ax_f.plot(t, f, lw=1.4, label=f"force_{comp} (run)")
    if par is not None:
        x = hist["centre_x"] - hist["centre_x"][0]
        ax_f.plot(t, ode_force(par, x), "k--", lw=1.0,
                  label="A [pL(x) - pR(x)]\nat the run's x\n(adiabatic chambers)")
    ax_f.set_ylabel("force [N]")
    ax_f.set_xlabel("time [s]")
    ax_f.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax_p.set_title(title)
    for ax in (ax_p, ax_f):
        ax.grid(alpha=0.3)
    return save(fig, out_dir, "interface.png")


def fluid_field_set(snap):
    """(label prefix, pressure, density, velocity) of a fluid snapshot: the mixture fields if there are, else
    the first phase's."""
    names = snap.cell
    if "mixture_pressure" in names:
        prefix = "mixture"
    else:
        phases = sorted(k[:-len("_pressure")] for k in names if k.endswith("_pressure"))
        if not phases:
            raise RunDirError(f"{snap.path}: fluid snapshot has no *_pressure field")
        prefix = phases[0]
    return prefix, snap[f"{prefix}_pressure"], snap[f"{prefix}_density"], snap[f"{prefix}_velocity"]


def colour_limits(values):
    """(vmin, vmax, note): a field uniform to round-off gets a +-1% range instead of a colour bar of noise."""
    lo, hi = float(np.ma.min(values)), float(np.ma.max(values))
    ref = max(abs(lo), abs(hi))
    if hi - lo > 1e-9 * ref:
        return lo, hi, ""
    centre, half = 0.5 * (lo + hi), 0.01 * ref if ref > 0 else 1.0
    return centre - half, centre + half, f" (uniform, max - min = {hi - lo:.2g})"


def _fluid_fields_1d(snap, out_dir):
    prefix, p, rho, vel = fluid_field_set(snap)
    x = snap.grid.axes[0]
    rows = [(p, "pressure [Pa]"), (rho, "density [kg/m^3]"), (vel[:, 0], "velocity x [m/s]")]
    fig, axes = plt.subplots(3, 1, figsize=(8, 7), sharex=True)
    for ax, (v, label) in zip(axes, rows):
        ax.plot(x, v, lw=1.3)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].set_title(f"{prefix} at t = {snap.time:.4g} s ({snap.path.name})")
    axes[-1].set_xlabel("x [m]")
    return save(fig, out_dir, "fields.png")


def _interface_points(faces, dim, z_mid, dz):
    """(x, y) of the embedded interface segments (3D: those near the z mid-plane), or None."""
    if not faces or "cx" not in faces:
        return None
    keep = np.ones(len(faces["cx"]), bool) if dim < 3 else np.abs(faces["cz"] - z_mid) <= 0.5 * dz
    return faces["cx"][keep], faces["cy"][keep]


def _panel_layout(width, height):
    """(figure, axes, wide) for three images of a width x height domain."""
    wide = width > 1.5 * height
    if wide:
        fig, axes = plt.subplots(3, 1, figsize=(10, min(12, 0.6 + 3 * (1.0 + 8.5 * height / width))))
    else:
        fig, axes = plt.subplots(1, 3, figsize=(15, min(6, 1.2 + 3.9 * height / width)))
    return fig, axes, wide


def _fluid_fields_2d(snap, out_dir, mask_ghosts):
    prefix, p, rho, vel = fluid_field_set(snap)
    grid = snap.grid
    dim = grid.dim
    k_mid = grid.cells[2] // 2 if dim == 3 else 0
    plane = (lambda a: a[k_mid]) if dim == 3 else (lambda a: a)
    speed = np.linalg.norm(vel, axis=-1)
    mask = None
    if "embedded_category" in snap.cell:
        category = plane(snap["embedded_category"])
        mask = category > LAST_FLOW_CATEGORY if mask_ghosts else category == SOLID_CATEGORY
    o, h, n = grid.origin, grid.spacing, grid.cells
    extent = [o[0], o[0] + n[0] * h[0], o[1], o[1] + n[1] * h[1]]
    z_mid = o[2] + (k_mid + 0.5) * h[2] if dim == 3 else 0.0
    points = _interface_points(snap.embedded_faces, dim, z_mid, h[2] if dim == 3 else 1.0)
    fig, axes, wide = _panel_layout(extent[1] - extent[0], extent[3] - extent[2])
    panels = [(p, "pressure [Pa]", "viridis"), (rho, "density [kg/m^3]", "cividis"),
              (speed, "velocity magnitude [m/s]", "magma")]
    for ax, (v, label, cmap_name) in zip(axes, panels):
        img = np.ma.masked_where(mask, plane(v)) if mask is not None else plane(v)
        cmap = matplotlib.colormaps[cmap_name].copy()
        cmap.set_bad("0.75")
        vmin, vmax, note = colour_limits(img)
        im = ax.imshow(img, origin="lower", extent=extent, cmap=cmap, interpolation="nearest", aspect="equal",
                       vmin=vmin, vmax=vmax)
        fig.colorbar(im, cax=ax.inset_axes([1.02, 0.0, 0.025 if wide else 0.05, 1.0]))  # as tall as the image
        if points is not None and len(points[0]):
            ax.plot(points[0], points[1], ".", color="red", ms=3, label="interface faces")
        ax.set_title(label + note, fontsize=10)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_xlim(extent[0], extent[1])
        ax.set_ylim(extent[2], extent[3])
    where = f", z = {z_mid:.3g} m mid-plane" if dim == 3 else ""
    masked = ""
    if mask is not None:
        masked = ", cells inside the body grey" if mask_ghosts else ", solid cells grey"
    fig.suptitle(f"{prefix} at t = {snap.time:.4g} s ({snap.path.name}{where}{masked})", fontsize=11)
    if points is not None and len(points[0]):
        axes[0].legend(fontsize=8, loc="upper right")
    return save(fig, out_dir, "fields.png")


def plot_fluid_fields(snap, out_dir, mask_ghosts=True):
    """fields.png: pressure, density and velocity of a fluid snapshot (1D: lines; 2D: images; 3D: the
    mid-plane z slice); cells inside a body grey (mask_ghosts False: only the solid ones), the embedded interface
    segments as red points."""
    if snap.grid.dim == 1:
        return _fluid_fields_1d(snap, out_dir)
    return _fluid_fields_2d(snap, out_dir, mask_ghosts)


def _solid_polygons(snap):
    """(polygons [cells, corners, 2], keep): the cells in the xy plane (3D hexahedra: their z-lower face, for
    the cells crossing the mid-plane z of the mesh)."""
    grid = snap.grid
    xyz, conn = grid.coordinates, grid.connectivity
    if grid.dim == 3:
        z = xyz[conn][:, :, 2]
        z_mid = 0.5 * (xyz[:, 2].min() + xyz[:, 2].max())
        keep = (z.min(axis=1) <= z_mid) & (z.max(axis=1) >= z_mid)
        return xyz[conn[:, :4]][:, :, :2], keep, z_mid
    return xyz[conn][:, :, :2], np.ones(len(conn), bool), None


def plot_solid_fields(snap, out_dir):
    """fields.png of a solid snapshot: pressure, density and velocity magnitude (the mean of each cell's nodes)
    on the deformed mesh (3D: the cells crossing the mid-plane z)."""
    polygons, keep, z_mid = _solid_polygons(snap)
    polygons = polygons[keep]
    conn = snap.grid.connectivity[keep]
    speed = np.linalg.norm(snap["velocity"][conn].mean(axis=1), axis=-1)
    panels = [(snap["pressure"][keep], "pressure [Pa]", "viridis"),
              (snap["density"][keep], "density [kg/m^3]", "cividis"),
              (speed, "velocity magnitude [m/s]", "magma")]
    lo, hi = polygons.reshape(-1, 2).min(axis=0), polygons.reshape(-1, 2).max(axis=0)
    width, height = max(hi[0] - lo[0], 1e-30), max(hi[1] - lo[1], 1e-30)
    stretched = width > 8 * height or height > 8 * width  # a strip: equal axes would show a line
    fig, axes, wide = _panel_layout(width, height if not stretched else width / 8)
    for ax, (v, label, cmap_name) in zip(axes, panels):
        vmin, vmax, note = colour_limits(v)
        pc = PolyCollection(polygons, array=v, cmap=cmap_name, edgecolors="face", linewidths=0.2)
        pc.set_clim(vmin, vmax)
        ax.add_collection(pc)
        fig.colorbar(pc, cax=ax.inset_axes([1.02, 0.0, 0.025 if wide else 0.05, 1.0]))
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
        ax.set_aspect("auto" if stretched else "equal")
        ax.set_title(label + note, fontsize=10)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
    where = f", z = {z_mid:.3g} m mid-plane" if z_mid is not None else ""
    scale = ", axes not to scale" if stretched else ""
    fig.suptitle(f"solid at t = {snap.time:.4g} s ({snap.path.name}{where}{scale})", fontsize=11)
    return save(fig, out_dir, "fields.png")


def plot_blocks(history, out_dir):
    """blocks.png: per block of block_history.csv, the mass-averaged velocity x, and the kinetic and internal
    energy, against time."""
    blocks = split_by(history, "block")
    fig, (ax_v, ax_e) = plt.subplots(2, 1, figsize=(11, 6.5), sharex=True)
    for i, (name, rows) in enumerate(blocks.items()):
        colour = f"C{i % 10}"
        ax_v.plot(rows["time"], rows["velocity_x"], lw=1.4, color=colour, label=name)
        ax_e.plot(rows["time"], rows["kinetic_energy"], lw=1.4, color=colour, label=f"{name} kinetic")
        ax_e.plot(rows["time"], rows["internal_energy"], lw=1.0, ls="--", color=colour, label=f"{name} internal")
    ax_v.set_ylabel("mass-averaged velocity x [m/s]")
    ax_e.set_ylabel("energy [J]")
    ax_e.set_xlabel("time [s]")
    ax_v.set_title("solid blocks (block_history.csv)")
    for ax in (ax_v, ax_e):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return save(fig, out_dir, "blocks.png")


def plot_timing(cols, summary, out_dir, max_bins=600):
    """timing.png: stacked wall time per cycle (solid, fluid, coupler, output, comm of coupler/timing.csv); cycles
    averaged in bins when there are many. In the pipelined cycle (summary: coupler_summary.json) the solid works
    while the fluid does: the longer of the two is stacked, the solid drawn as a line."""
    summary = summary or {}
    overlapped = summary.get("scheme") == "pipelined"
    cycle = cols["cycle"]
    solid = cols["solid"] * 1e3
    rest = [k for k in ("coupler", "output", "comm") if k in cols]  # output: runs written before it was a column
    if overlapped:
        parts = ["solver (max of solid, fluid)"] + rest
        values = [np.maximum(cols["solid"], cols["fluid"]) * 1e3] + [cols[k] * 1e3 for k in rest]
    else:
        parts = ["solid", "fluid"] + rest
        values = [cols[k] * 1e3 for k in parts]
    wall = cols["wall"] * 1e3
    per_bin = max(1, int(math.ceil(len(cycle) / max_bins)))
    if per_bin > 1:
        nb = len(cycle) // per_bin
        binned = lambda a: a[: nb * per_bin].reshape(nb, per_bin).mean(axis=1)  # noqa: E731
        cycle, values, wall, solid = binned(cycle), [binned(v) for v in values], binned(wall), binned(solid)
    fig, ax = plt.subplots(figsize=(9, 4.5))
    ax.stackplot(cycle, *values, labels=parts, alpha=0.85)
    ax.plot(cycle, wall, "k-", lw=0.8, label="wall")
    if overlapped:
        ax.plot(cycle, solid, "b-", lw=0.8, label="solid (overlapped)")
    ax.set_xlabel("cycle")
    ax.set_ylabel("time per cycle [ms]" + (f" (mean of {per_bin} cycles)" if per_bin > 1 else ""))
    title = "coupled cycle timing" + (f" ({summary['scheme']})" if "scheme" in summary else "")
    if "comm_fraction" in summary:
        title += f": {summary.get('cycles', len(cols['cycle']))} cycles, comm {100 * summary['comm_fraction']:.0f}% of wall"
    ax.set_title(title)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper right", ncol=5)
    return save(fig, out_dir, "timing.png")
