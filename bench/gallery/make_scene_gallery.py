#!/usr/bin/python3
"""Scene gallery: one picture per scene of configs/*.yaml, for the README's scene catalogue.

For every configs/STEM.yaml (or those of --only) this runs the scene through the launcher,
`BUILD/bin/cosim run configs/STEM.yaml --out WORK/STEM --quiet [--set ...]`, reads the run with the `cosim`
package (cosim.read_run) and draws ONE PNG, OUT/STEM.png (640 x 320 px): the scene's main field at its last
snapshot (or the most telling one, see PICTURES), with the structure on top in coupled scenes (the solid mesh's
deformed cells from the solid snapshot nearest in time) and the embedded body in fluid-only scenes (the cells
whose embedded_category is inside a body, grey). 1D fluid: density, velocity and pressure against x. 3D: the
z mid-plane. Solid-only scenes: the deformed mesh coloured by a field, or, for the 1D strip of
solid_piston_1d, its cells' pressure against node position and time.

Runs that would take long on a 2-core machine are shortened by the --set overrides of REDUCED (printed with the
results); each one is checked with `cosim check SCENE --set ...` before it runs. A solid-only scene (no fluid:
section) is refused by the launcher ("every run has a fluid"); it is then run with BUILD/bin/solid_solver
directly (docs/python.md, "Running a scene"), and the table says so.

Usage (from anywhere; paths relative to the repository root):
    /usr/bin/python3 bench/gallery/make_scene_gallery.py [--build build] [--only STEM ...] [--work DIR]
                                                           [--out docs/img/scenes]
--work: where the run directories go (default: a new temporary directory under /tmp, removed at the end; a
given one is kept). Exit status 1 when a scene failed to run or to draw (its error is in the table).
"""
import argparse
import shutil
import subprocess
import sys
import tempfile
import textwrap
import time
import traceback
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

# Scenes shortened for the gallery: stem -> ({key: value} of --set overrides, why). Times measured on the
# 2-core development machine at the scene's own settings.
REDUCED = {
    "tungsten_blast_3d": ({"fluid.mesh.cells": [32, 32, 32], "solid.mesh.cells": [4, 10, 10],
                           "coupling.time.end": 4.0e-4},
                          "120^3 background, 1 h at full size: CI size 32^3 / 4 x 10 x 10 to 0.4 ms (the cloud on the target), about 10 s"),
    "low_mach_step": ({"fluid.mesh.cells": [256, 128]},
                      "640 x 320 to t = 20 takes about 7 min here (320 x 160: 52-94 s); 256 x 128 (23 s) still sheds the wake vortex"),
    "particle_blast_2d": ({"fluid.mesh.cells": [160, 160]},
                          "200 x 200 takes 75 s here; 160 x 160 about 26 s"),
    "supersonic_cylinder": ({"fluid.mesh.cells": [160, 160]},
                            "240 x 240 to t = 4 takes 55 s here; 160 x 160 (R = 20 cells) about 10 s"),
    "piston_3d": ({"coupling.time.end": 0.08},
                  "3 periods take 41 s here; the picture is at the far turning point (0.061 s): to 0.08 s, about 7 s"),
}

# What each picture shows: stem -> options (defaults below, by the kind and dimension of the run).
#   field: fluid field drawn ("density", "pressure", "speed", "vorticity", "mach" or a snapshot field name);
#   log: logarithmic colour scale; symmetric: colour limits +-(99.5th percentile of |value|);
#   solid: how the structure is drawn on a coupled run: "fill" (its cells coloured like the fluid field),
#          "outline" (grey cells, dark outline), or a solid cell field name ("von_mises": own colour bar);
#   time: the snapshot nearest this time [s] instead of the last one ("max_displacement": that of the largest
#         displacement of the structure, coupler/interface_history.csv);
#   solid_field: solid-only runs, the cell field drawn; blocks_apart: blocks drawn with their own field
#                ({block name: field}); plane: 3D solid, "z_lower" (the symmetry plane z = min) or "z_mid";
#   spacetime: solid-only 1D strip, pressure against x and t.
PICTURES = {
    "sod": {},
    "toro_left_blast": {},
    "water_air_shock_tube": {},
    "piston_1d": {"time": "max_displacement"},
    "embedded_advection": {"field": "pressure"},
    "coupled_advection": {"field": "pressure", "solid": "outline"},
    "gresho_vortex": {"field": "speed"},
    "low_mach_step": {"field": "vorticity", "symmetric": True},
    "supersonic_cylinder": {"field": "mach"},
    "particle_blast_2d": {"field": "tungsten_alpha", "log": True},
    "modified_sod_2d": {"field": "density", "solid": "fill"},
    "modified_sod_square_2d": {"field": "density", "solid": "fill"},
    "modified_sod_2d_eulerian": {"field": "density"},
    "density_wave_3d": {"field": "density"},
    "piston_2d": {"field": "pressure", "solid": "outline", "time": "max_displacement"},
    "piston_3d": {"field": "pressure", "solid": "outline", "time": "max_displacement"},
    "piston_light_2d": {"field": "pressure", "solid": "fill"},
    "shock_panel_2d": {"field": "pressure", "log": True, "solid": "von_mises", "time": 2.0e-4},
    "shock_panel_2d_gmsh": {"field": "pressure", "log": True, "solid": "von_mises", "time": 2.0e-4},
    "tungsten_blast_3d": {"field": "tungsten_alpha", "log": True, "solid": "von_mises"},
    "shock_panel_2d_conforming": {"solid_field": "pressure", "log": True, "blocks_apart": {"panel": "von_mises"},
                                  "time": 2.0e-4},
    "solid_sedov_lulesh": {"solid_field": "density", "plane": "z_lower"},
    "solid_piston_1d": {"spacetime": True},
}

FIGSIZE, DPI = (6.4, 3.2), 100
FLUID_LAUNCHER_REFUSAL = "expected a fluid: section"
CURRENT = {"scene": {}, "overrides": {}}  # the scene being drawn (setting())


def import_cosim(build):
    """The cosim package: the one on sys.path, else BUILD/python's."""
    try:
        import cosim  # noqa: F401
    except ImportError:
        sys.path.insert(0, str(build / "python"))
    import cosim  # noqa: F811
    return cosim


# ----------------------------------------------------------------------------------------------- running
def set_args(overrides, fmt):
    out = []
    for key, value in overrides.items():
        out += ["--set", f"{key}={fmt(value)}"]
    return out


def fresh_run_dir(path, cosim):
    """Remove an earlier run in path (only a run directory or an empty one), so no stale snapshot is read."""
    if not path.exists():
        return
    if path.is_dir() and not any(path.iterdir()):
        path.rmdir()
        return
    try:
        cosim.read_run(path)
    except cosim.RunDirError:
        raise SystemExit(f"{path}: exists and is not a run directory; not removing it (choose another --work)")
    shutil.rmtree(path)


def check_overrides(scene_path, overrides, bin_dir, fmt, solid_only):
    """`cosim check SCENE --set ...` (solid-only scenes: `solid_solver --check`); RuntimeError with its output."""
    if solid_only:
        cmd = [str(bin_dir / "solid_solver"), str(scene_path), "--check"] + set_args(overrides, fmt)
    else:
        cmd = [str(bin_dir / "cosim"), "check", str(scene_path)] + set_args(overrides, fmt)
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"check of the overrides failed (exit {p.returncode}): "
                           f"{(p.stdout + p.stderr).strip()}")


def run_scene(cosim, scene_path, out, overrides, bin_dir, timeout):
    """Run the scene into out; returns (Run, note). Raises cosim.RunFailed / RuntimeError on failure."""
    from cosim.scene import format_value, load_scene
    solid_only = "fluid" not in load_scene(scene_path)
    if overrides:
        check_overrides(scene_path, overrides, bin_dir, format_value, solid_only)
    try:
        return cosim.run(scene_path, out, set=overrides, exe=bin_dir / "cosim", quiet=True, timeout=timeout), ""
    except cosim.RunFailed as e:
        if not (solid_only and FLUID_LAUNCHER_REFUSAL in e.reason):
            raise
        refusal = e.reason.strip()
    # Solid-only scene: the launcher refuses it; docs/python.md: run solid_solver directly.
    fresh_run_dir(out, cosim)
    cmd = [str(bin_dir / "solid_solver"), str(scene_path), "--out", str(out), "-q"] + set_args(overrides, format_value)
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    if p.returncode != 0:
        raise RuntimeError(f"solid_solver exit {p.returncode}: {(p.stdout + p.stderr).strip()}")
    return cosim.read_run(out), f"launcher: '{refusal}'; ran solid_solver directly"


# ----------------------------------------------------------------------------------------------- drawing
def setup_matplotlib():
    import matplotlib
    matplotlib.use("Agg")
    matplotlib.rcParams.update({"font.size": 8, "axes.titlesize": 9, "axes.labelsize": 8,
                                "xtick.labelsize": 7, "ytick.labelsize": 7, "figure.titlesize": 9})


def label(name, unit):
    return f"{name} [{unit}]" if unit and unit != "-" else name


def fmt_time(t):
    return f"{t:.4g} s"


def fluid_prefix(snap):
    from cosim import plot
    return plot.fluid_field_set(snap)[0]


def fluid_field(run, snap, what, cosim):
    """(array of the cell shape, label with unit) of a fluid quantity."""
    import numpy as np
    prefix = fluid_prefix(snap)
    if what in ("density", "pressure"):
        name = f"{prefix}_{what}"
        return snap[name], label(name, cosim.unit(name))
    if what == "speed":
        return np.linalg.norm(snap[f"{prefix}_velocity"], axis=-1), label(f"|{prefix}_velocity|", "m/s")
    if what == "vorticity":
        u = snap[f"{prefix}_velocity"]
        h = snap.grid.spacing
        w = np.gradient(u[..., 1], h[0], axis=-1) - np.gradient(u[..., 0], h[1], axis=-2)
        return w, label("vorticity", "1/s")
    if what == "mach":
        gamma = float(setting(run, "fluid.phases.0.eos.gamma"))
        c = np.sqrt(gamma * snap[f"{prefix}_pressure"] / snap[f"{prefix}_density"])
        return np.linalg.norm(snap[f"{prefix}_velocity"], axis=-1) / c, f"Mach number (gamma {gamma:g})"
    text = label(what, cosim.unit(what))
    if what.endswith("_alpha"):
        text += " (volume fraction)"
    return snap[what], text


def norm_for(values, opts):
    """matplotlib norm of the values shown (masked arrays: the visible ones)."""
    import numpy as np
    from matplotlib.colors import LogNorm, Normalize
    from cosim import plot
    v = np.ma.masked_invalid(values)
    if opts.get("log"):
        pos = np.ma.masked_less_equal(v, 0)
        lo, hi = float(pos.min()), float(pos.max())
        if hi > lo * 1.0001:
            return LogNorm(lo, hi), ""
    if opts.get("symmetric"):
        a = np.abs(v.compressed())
        lim = float(np.percentile(a, 99.5)) if a.size else 1.0
        return Normalize(-lim, lim), f" (colours clipped at +-{lim:.3g})"
    lo, hi, note = plot.colour_limits(v)
    return Normalize(lo, hi), note


def boundary_segments(polygons):
    """Outline of a set of polygons (edges used by one polygon only): [n, 2, 2]."""
    import numpy as np
    count, first = {}, {}
    pts = np.round(polygons, 12)
    for poly, raw in zip(pts, polygons):
        n = len(poly)
        for i in range(n):
            a, b = tuple(poly[i]), tuple(poly[(i + 1) % n])
            key = (a, b) if a <= b else (b, a)
            count[key] = count.get(key, 0) + 1
            first.setdefault(key, (raw[i], raw[(i + 1) % n]))
    return np.array([first[k] for k, c in count.items() if c == 1])


def solid_slice(snap, plane="z_mid", z=None):
    """(polygons [n, corners, 2], cell index) of the solid cells in the xy plane: 2D all cells; 3D hexahedra
    crossing z (default: z mid of the mesh; "z_lower": the layer on the lowest z), drawn by their lower face."""
    import numpy as np
    grid = snap.grid
    xyz, conn = grid.coordinates, grid.connectivity
    if grid.dim < 3:
        return xyz[conn][:, :, :2], np.arange(len(conn))
    zc = xyz[conn][:, :, 2]
    if z is None:
        z = zc.min() + 1e-9 * (zc.max() - zc.min()) if plane == "z_lower" else 0.5 * (xyz[:, 2].min() + xyz[:, 2].max())
    keep = np.nonzero((zc.min(axis=1) <= z) & (zc.max(axis=1) >= z))[0]
    return xyz[conn[keep, :4]][:, :, :2], keep


def solid_cell_values(snap, name, cells):
    import numpy as np
    if name == "velocity":
        conn = snap.grid.connectivity[cells]
        return np.linalg.norm(snap["velocity"][conn].mean(axis=1), axis=-1)
    return snap[name][cells]


def map_axes(fig, aspect, colorbars=1):
    """An axes for a map of height/width `aspect` at equal scales, as large as the figure allows and centred,
    with `colorbars` colour-bar axes at its right (at least 1.8 in tall): (ax, [cax, ...])."""
    W, H = fig.get_size_inches()
    left, right, bottom, top, per_bar = 0.62, 0.1, 0.42, 0.48, 0.9
    avail_w, avail_h = W - left - right - colorbars * per_bar, H - bottom - top
    w = min(avail_w, avail_h / aspect)
    h = w * aspect
    x0, y0 = left + 0.5 * (avail_w - w), bottom + 0.5 * (avail_h - h)
    ax = fig.add_axes([x0 / W, y0 / H, w / W, h / H])
    hb = min(avail_h, max(h, 1.8))
    yb = bottom + 0.5 * (avail_h - hb)
    caxes = [fig.add_axes([(x0 + w + 0.1 + i * per_bar) / W, yb / H, 0.11 / W, hb / H]) for i in range(colorbars)]
    return ax, caxes


def add_colorbar(fig, cax, mappable, text):
    cb = fig.colorbar(mappable, cax=cax)
    cb.set_label(text, fontsize=7)
    cb.ax.tick_params(labelsize=7)
    cb.ax.yaxis.get_offset_text().set_fontsize(7)
    return cb


def set_title(fig, name, t, extra, reduced="", **kw):
    """Title: scene and time; below it, smaller, what the picture shows and how the run was reduced."""
    info = "; ".join(x for x in (extra, reduced) if x)
    if not kw:  # a constrained layout: one line
        fig.suptitle(f"{name}, t = {fmt_time(t)}" + (f"  ({info})" if info else ""), fontsize=9)
        return
    fig.suptitle(f"{name}, t = {fmt_time(t)}", fontsize=9, **kw)
    if info:
        fig.text(0.5, 0.915, textwrap.fill(info, 115), ha="center", va="top", fontsize=7, color="0.25")


def body_cmap(name):
    import matplotlib
    cmap = matplotlib.colormaps[name].copy()
    cmap.set_bad("0.6")
    return cmap


def draw_fluid_lines(run, snap, opts, cosim, plt, reduced_note):
    """1D fluid run: density, velocity x, pressure against x (cells inside a body left out, the structure
    shaded for a coupled run); a pressure spanning more than 100:1 on a log axis."""
    import numpy as np
    from cosim import plot
    prefix, p, rho, vel = plot.fluid_field_set(snap)
    x = snap.grid.axes[0]
    inside = snap["embedded_category"] > plot.LAST_FLOW_CATEGORY if "embedded_category" in snap else None
    span = structure_span_1d(run, snap.time)
    fig, axes = plt.subplots(1, 3, figsize=FIGSIZE, sharex=True, layout="constrained")
    for ax, (v, name) in zip(axes, [(rho, f"{prefix}_density"), (vel[:, 0], f"{prefix}_velocity_x"),
                                    (p, f"{prefix}_pressure")]):
        v = np.array(v, float)
        if inside is not None:
            v[inside] = np.nan
        ax.plot(x, v, lw=1.0, color="C0")
        if span is not None:
            ax.axvspan(*span, color="0.75", lw=0, label="piston")
        ax.set_title(label(name, cosim.unit(name)), fontsize=8)
        ax.set_xlabel("x [m]")
        ax.grid(alpha=0.3)
        finite = v[np.isfinite(v)]
        if name.endswith("pressure") and finite.min() > 0 and finite.max() > 100 * finite.min():
            ax.set_yscale("log")
        else:
            ax.ticklabel_format(axis="y", style="sci", scilimits=(-3, 4))
            ax.yaxis.get_offset_text().set_fontsize(7)
    if span is not None:
        axes[0].legend(fontsize=7, loc="best")
    set_title(fig, run.name, snap.time, f"{snap.grid.cells[0]} cells" + (f"; {reduced_note}" if reduced_note else ""))
    return fig


def structure_span_1d(run, t):
    """(left, right) of a 1D coupled run's structure at time t: its initial extent (solid.mesh) moved by the
    interface centre's displacement (coupler/interface_history.csv)."""
    import numpy as np
    if run.kind != "coupled" or "interface_history" not in run.histories:
        return None
    lower, upper = setting(run, "solid.mesh.lower"), setting(run, "solid.mesh.upper")
    if not lower or not upper:
        return None
    h = run.histories["interface_history"]
    shift = float(np.interp(t, h["time"], h["centre_x"])) - float(h["centre_x"][0])
    return float(lower[0]) + shift, float(upper[0]) + shift


def fluid_plane(snap):
    """(plane function taking a cell array to its 2D xy plane, z of the plane or None)."""
    grid = snap.grid
    if grid.dim == 3:
        k = grid.cells[2] // 2
        return (lambda a: a[k]), float(grid.origin[2] + (k + 0.5) * grid.spacing[2])
    return (lambda a: a), None


def draw_fluid_map(run, snap, opts, cosim, plt, reduced_note):
    """2D / 3D fluid run: one field as a pcolormesh (3D: z mid-plane), cells inside a body grey, the coupled
    structure (solid snapshot nearest in time) on top: its cells filled like the fluid field ("fill"), grey
    ("outline") or coloured by a solid field with a second colour bar."""
    import numpy as np
    from matplotlib.collections import LineCollection, PolyCollection
    from cosim import plot
    grid = snap.grid
    plane, z_mid = fluid_plane(snap)
    values, text = fluid_field(run, snap, opts.get("field", "pressure"), cosim)
    values = plane(values)
    mask = None
    if "embedded_category" in snap:
        mask = plane(snap["embedded_category"]) > plot.LAST_FLOW_CATEGORY
    img = np.ma.masked_where(mask, values) if mask is not None else np.ma.asarray(values)
    norm, note = norm_for(img, opts)
    edges = [grid.origin[d] + np.arange(grid.cells[d] + 1) * grid.spacing[d] for d in range(2)]
    aspect = (edges[1][-1] - edges[1][0]) / (edges[0][-1] - edges[0][0])
    solid_mode = opts.get("solid", "outline")
    solid = run.solid.at(snap.time) if run.kind == "coupled" and run.solid is not None and len(run.solid) else None
    own_field = solid is not None and solid_mode not in ("fill", "outline")
    fig = plt.figure(figsize=FIGSIZE)
    ax, caxes = map_axes(fig, aspect, 2 if own_field else 1)
    cmap = body_cmap(opts.get("cmap", "RdBu_r" if opts.get("symmetric") else "viridis"))
    mesh = ax.pcolormesh(edges[0], edges[1], img, cmap=cmap, norm=norm, shading="flat", rasterized=True)
    add_colorbar(fig, caxes[0], mesh, text + note)
    if solid is not None:
        polys, cells = solid_slice(solid, z=z_mid)
        outline = boundary_segments(polys)
        if solid_mode == "fill":
            name = {"density": "density", "pressure": "pressure", "speed": "velocity"}.get(
                opts.get("field", "pressure"), "pressure")
            ax.add_collection(PolyCollection(polys, array=solid_cell_values(solid, name, cells), cmap=cmap,
                                             norm=norm, edgecolors="face", linewidths=0.3, antialiased=False))
        elif solid_mode == "outline":
            ax.add_collection(PolyCollection(polys, facecolors="0.72", edgecolors="0.45", linewidths=0.3))
        else:
            pc = PolyCollection(polys, array=solid_cell_values(solid, solid_mode, cells), cmap="inferno",
                                edgecolors="face", linewidths=0.3, antialiased=False)
            ax.add_collection(pc)
            add_colorbar(fig, caxes[1], pc, label(f"solid {solid_mode}", cosim.unit(solid_mode)))
        edge = "w" if solid_mode == "fill" else "k"  # white around cells coloured like the (dark) fluid field
        ax.add_collection(LineCollection(outline, colors=edge, linewidths=1.0))
        ax.plot([], [], "-", color=edge if edge == "k" else "0.5", lw=1.5,
                label=f"structure (solid mesh at t = {fmt_time(solid.time)})")
        ax.legend(fontsize=6, loc="lower left", framealpha=0.8)
    elif mask is not None and mask.any():
        ax.plot([], [], "s", color="0.6", ms=5, label="body (embedded_category)")
        ax.legend(fontsize=6, loc="lower left", framealpha=0.8)
    ax.set_xlim(edges[0][0], edges[0][-1])
    ax.set_ylim(edges[1][0], edges[1][-1])
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]", labelpad=1)
    ax.set_ylabel("y [m]", labelpad=1)
    where = f"z = {z_mid:.3g} m mid-plane" if z_mid is not None else ""
    cells = " x ".join(str(c) for c in grid.cells) + " cells" if "fluid " not in reduced_note else ""
    set_title(fig, run.name, snap.time, ", ".join(x for x in (where, cells) if x), reduced_note, y=0.985)
    return fig


def setting(run, key, default=None):
    """A scene value with the run's overrides: from the run's scene.yaml (cosim run), else (solid_solver run
    alone, which writes no scene copy) from the scene file given to draw() with the overrides applied."""
    if run.scene is not None:
        return run.setting(key, default)
    from cosim.scene import lookup
    if key in CURRENT["overrides"]:
        return CURRENT["overrides"][key]
    return lookup(CURRENT["scene"], key, default)


def block_names(run):
    blocks = setting(run, "solid.blocks") or []
    return [str(b.get("name", i)) for i, b in enumerate(blocks)]


def draw_solid_map(run, snap, opts, cosim, plt, reduced_note):
    """Solid-only run: the deformed mesh (3D: one layer of cells) coloured by a cell field; blocks named in
    blocks_apart coloured by their own field, with a second colour bar."""
    import numpy as np
    from matplotlib.collections import LineCollection, PolyCollection
    polys, cells = solid_slice(snap, plane=opts.get("plane", "z_mid"))
    field = opts.get("solid_field", "pressure")
    values = solid_cell_values(snap, field, cells)
    names = block_names(run)
    block = snap["block"][cells].astype(int) if "block" in snap else np.zeros(len(cells), int)
    apart = {b: f for b, f in (opts.get("blocks_apart") or {}).items() if b in names}
    sel_apart = np.zeros(len(cells), bool)
    for bname in apart:
        sel_apart |= block == names.index(bname)
    norm, note = norm_for(np.ma.masked_where(sel_apart, values), opts)
    lo, hi = polys.reshape(-1, 2).min(axis=0), polys.reshape(-1, 2).max(axis=0)
    fig = plt.figure(figsize=FIGSIZE)
    ax, caxes = map_axes(fig, (hi[1] - lo[1]) / (hi[0] - lo[0]), 1 + len(apart))
    pc = PolyCollection(polys[~sel_apart], array=values[~sel_apart], cmap="viridis", norm=norm,
                        edgecolors="face", linewidths=0.3, antialiased=False)
    ax.add_collection(pc)
    add_colorbar(fig, caxes[0], pc, label(field, cosim.unit(field)) + note)
    for cax, (bname, bfield) in zip(caxes[1:], apart.items()):
        sel = block == names.index(bname)
        pb = PolyCollection(polys[sel], array=solid_cell_values(snap, bfield, cells[sel]), cmap="inferno",
                            edgecolors="face", linewidths=0.3, antialiased=False)
        ax.add_collection(pb)
        ax.add_collection(LineCollection(boundary_segments(polys[sel]), colors="k", linewidths=0.7))
        add_colorbar(fig, cax, pb, label(f"{bname} {bfield}", cosim.unit(bfield)))
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]", labelpad=1)
    ax.set_ylabel("y [m]", labelpad=1)
    where = ""
    if snap.grid.dim == 3:
        where = "layer on the z = 0 symmetry plane" if opts.get("plane") == "z_lower" else "layer at mid z"
    info = f"{snap.grid.num_cells} {snap.grid.cell_type or 'element'}s"
    set_title(fig, run.name, snap.time, ", ".join(x for x in (where, info) if x), reduced_note, y=0.985)
    return fig


def draw_solid_spacetime(run, opts, cosim, plt, reduced_note):
    """Solid-only 1D strip: the cells' pressure against the nodes' x (on the strip's y = min line) and time,
    over all snapshots; rigid blocks grey, their ends black lines (the piston's path)."""
    import numpy as np
    series = run.solid
    first = series[0]
    xyz = first.grid.coordinates
    y0 = xyz[:, 1].min()
    bottom = np.nonzero(np.abs(xyz[:, 1] - y0) < 1e-9 * max(1.0, np.ptp(xyz[:, 0])))[0]
    bottom = bottom[np.argsort(xyz[bottom, 0])]
    conn = first.grid.connectivity
    node_pos = {n: i for i, n in enumerate(bottom)}
    order = np.full(len(bottom) - 1, -1)  # the cell on each bottom edge (nodes bottom[i], bottom[i + 1])
    for c, nodes in enumerate(conn):
        idx = sorted(node_pos[n] for n in nodes if n in node_pos)
        if len(idx) == 2 and idx[1] == idx[0] + 1:
            order[idx[0]] = c
    times, xs, ps = [], [], []
    for snap in series:
        times.append(snap.time)
        xs.append(snap.grid.coordinates[bottom, 0])
        ps.append(snap["pressure"][order])
    t, x, p = np.array(times), np.array(xs), np.array(ps)
    t_edges = np.concatenate([[t[0]], 0.5 * (t[1:] + t[:-1]), [t[-1]]])
    x_edges = np.concatenate([x[:1], 0.5 * (x[1:] + x[:-1]), x[-1:]])
    names = block_names(run)
    rigid = [bool(b.get("rigid")) for b in (setting(run, "solid.blocks") or [])]
    block = first["block"][order].astype(int)
    is_rigid = np.array([rigid[b] if b < len(rigid) else False for b in block])
    img = np.ma.masked_where(np.broadcast_to(is_rigid, p.shape), p)
    norm, note = norm_for(img, opts)
    fig, ax = plt.subplots(figsize=FIGSIZE, layout="constrained")
    T = np.repeat(t_edges[:, None], x_edges.shape[1], axis=1)
    mesh = ax.pcolormesh(x_edges, T, img, cmap=body_cmap("viridis"), norm=norm, shading="flat", rasterized=True)
    cb = fig.colorbar(mesh, ax=ax, fraction=0.05, pad=0.02)
    cb.set_label(label("pressure", cosim.unit("pressure")) + note, fontsize=7)
    cb.ax.tick_params(labelsize=7)
    for b in sorted(set(block[is_rigid])):
        cells_b = np.nonzero(block == b)[0]
        for k, node in enumerate((cells_b.min(), cells_b.max() + 1)):
            ax.plot(x[:, node], t, color="k", lw=0.9, label=f"{names[b]} faces (rigid block, grey)" if not k else None)
    if is_rigid.any():
        ax.legend(fontsize=7, loc="upper right", framealpha=0.85)
    ax.set_xlabel("x [m] (node positions)")
    ax.set_ylabel("time [s]")
    ax.set_xlim(x.min(), x.max())
    ax.set_ylim(t[0], t[-1])
    info = f"{len(order)} elements, {len(t)} snapshots"
    fig.suptitle(f"{run.name}, t = 0 .. {fmt_time(t[-1])}  ({', '.join(x for x in (info, reduced_note) if x)})",
                 fontsize=9)  # one line: the time axis is the picture's
    return fig


def pick_snapshot(run, series, opts):
    """The snapshot drawn: opts time ("max_displacement": that of the largest interface displacement of
    interface_history.csv), else the last one."""
    import numpy as np
    when = opts.get("time")
    if when == "max_displacement" and "interface_history" in run.histories:
        h = run.histories["interface_history"]
        d = np.abs(h["centre_x"] - h["centre_x"][0])
        when = float(h["time"][int(np.argmax(d))])
    if isinstance(when, (int, float)):
        return series.at(when)
    return series[-1]


def draw(run, stem, out_png, reduced_note, cosim, scene, overrides):
    import matplotlib.pyplot as plt
    CURRENT.update(scene=scene, overrides=overrides)
    opts = PICTURES.get(stem, {})
    if run.kind in ("coupled", "fluid") and run.fluid is not None and len(run.fluid):
        snap = pick_snapshot(run, run.fluid, opts)
        if snap.grid.dim == 1:
            fig = draw_fluid_lines(run, snap, opts, cosim, plt, reduced_note)
        else:
            fig = draw_fluid_map(run, snap, opts, cosim, plt, reduced_note)
    elif run.solid is not None and len(run.solid):
        if opts.get("spacetime"):
            fig = draw_solid_spacetime(run, opts, cosim, plt, reduced_note)
        else:
            fig = draw_solid_map(run, pick_snapshot(run, run.solid, opts), opts, cosim, plt, reduced_note)
    else:
        raise RuntimeError(f"{run.directory}: no fluid or solid snapshots to draw ({run!r})")
    fig.savefig(out_png, dpi=DPI, pil_kwargs={"optimize": True})
    plt.close(fig)


# ----------------------------------------------------------------------------------------------- main
def fmt_overrides(overrides, fmt):
    return ", ".join(f"{k}={fmt(v)}" for k, v in overrides.items())


def short_reduction(overrides, scene):
    """Title note of the overrides, from the scene's values: 'reduced: fluid cells 640x320 -> 320x160, ...'."""
    from cosim.scene import lookup

    def text(v):
        return "x".join(str(x) for x in v) if isinstance(v, list) else f"{v:g}" if isinstance(v, float) else str(v)
    parts = []
    for key, value in overrides.items():
        head, tail = key.split(".", 1)[0], key.rsplit(".", 1)[-1]
        name = {"cells": head, "end": "end"}.get(tail, f"{head} {tail}")
        unit = " s" if tail == "end" else ""
        parts.append(f"{name} {text(lookup(scene, key, '?'))} -> {text(value)}{unit}")
    return "reduced: " + ", ".join(parts)


def print_table(rows, fmt):
    headers = ["scene", "settings changed (why)", "run [s]", "plot [s]", "picture"]
    lines = []
    for r in rows:
        changed = "-"
        if r["overrides"]:
            changed = fmt_overrides(r["overrides"], fmt) + f" ({r['why']})"
        if r["note"]:
            changed = (changed + "; " if changed != "-" else "") + r["note"]
        lines.append([r["stem"], changed, f"{r['run_s']:.1f}" if r["run_s"] is not None else "-",
                      f"{r['plot_s']:.1f}" if r["plot_s"] is not None else "-", r["picture"]])
    print("| " + " | ".join(headers) + " |")
    print("|" + "|".join("---" for _ in headers) + "|")
    for ln in lines:
        print("| " + " | ".join(ln) + " |")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("--build", default="build", help="build directory (bin/, python/), default build")
    ap.add_argument("--only", nargs="+", metavar="STEM", help="only these scenes (configs/STEM.yaml)")
    ap.add_argument("--work", help="directory of the run directories (default: a temporary one, removed)")
    ap.add_argument("--out", default="docs/img/scenes", help="where the PNGs go, default docs/img/scenes")
    ap.add_argument("--timeout", type=float, default=300.0, help="seconds a run may take (default 300)")
    args = ap.parse_args(argv)

    build = Path(args.build) if Path(args.build).is_absolute() else ROOT / args.build
    out_dir = Path(args.out) if Path(args.out).is_absolute() else ROOT / args.out
    bin_dir = build / "bin"
    cosim = import_cosim(build)
    from cosim.scene import format_value, load_scene
    setup_matplotlib()

    scenes = sorted((ROOT / "configs").glob("*.yaml"))
    if args.only:
        wanted = set(args.only)
        unknown = wanted - {p.stem for p in scenes}
        if unknown:
            ap.error(f"no configs/STEM.yaml for: {', '.join(sorted(unknown))}")
        scenes = [p for p in scenes if p.stem in wanted]
    out_dir.mkdir(parents=True, exist_ok=True)
    temporary = args.work is None
    work = Path(tempfile.mkdtemp(prefix="cosim_gallery_")) if temporary else Path(args.work).resolve()
    if ROOT in work.parents or work == ROOT:
        ap.error(f"--work {work} is inside the repository; choose a directory outside it (e.g. under /tmp)")
    work.mkdir(parents=True, exist_ok=True)
    print(f"{len(scenes)} scene(s); runs in {work}; pictures in {out_dir}", flush=True)

    rows, failed, total0 = [], 0, time.monotonic()
    for scene_path in scenes:
        stem = scene_path.stem
        overrides, why = REDUCED.get(stem, ({}, ""))
        row = {"stem": stem, "overrides": overrides, "why": why, "note": "", "run_s": None, "plot_s": None,
               "picture": "-"}
        rows.append(row)
        run_dir = work / stem
        print(f"{stem}: running" + (f" with {fmt_overrides(overrides, format_value)}" if overrides else ""),
              flush=True)
        try:
            fresh_run_dir(run_dir, cosim)
            t0 = time.monotonic()
            try:
                run, note = run_scene(cosim, scene_path, run_dir, overrides, bin_dir, args.timeout)
            finally:
                row["run_s"] = time.monotonic() - t0
            row["note"] = note
        except (cosim.RunFailed, RuntimeError, subprocess.TimeoutExpired, cosim.RunDirError) as e:
            text = f"exit {e.returncode}: {e.reason}" if isinstance(e, cosim.RunFailed) else str(e)
            row["note"] = "RUN FAILED: " + text.replace("\n", " / ")
            print(f"{stem}: run failed: {text}", flush=True)
            failed += 1
            continue
        png = out_dir / f"{stem}.png"
        t1 = time.monotonic()
        try:
            scene = load_scene(scene_path)
            draw(run, stem, png, short_reduction(overrides, scene) if overrides else "", cosim, scene, overrides)
            row["picture"] = f"{png.relative_to(ROOT) if ROOT in png.parents else png} ({png.stat().st_size / 1024:.0f} KB)"
        except Exception as e:  # noqa: BLE001: a drawing error is reported in the table, the others go on
            row["note"] = (row["note"] + "; " if row["note"] else "") + f"PLOT FAILED: {type(e).__name__}: {e}"
            traceback.print_exc()
            failed += 1
        row["plot_s"] = time.monotonic() - t1
        print(f"{stem}: run {row['run_s']:.1f} s, plot {row['plot_s']:.1f} s -> {row['picture']}", flush=True)

    print()
    print("Reduced scenes (--set overrides, why):")
    for stem, (ov, why) in REDUCED.items():
        print(f"  {stem}: {fmt_overrides(ov, format_value)}  -- {why}")
    print()
    print_table(rows, format_value)
    total_kb = sum(p.stat().st_size for p in out_dir.glob("*.png")) / 1024
    print(f"\ntotal wall time {time.monotonic() - total0:.0f} s; {len(list(out_dir.glob('*.png')))} PNG(s) in "
          f"{out_dir}, {total_kb:.0f} KB")
    if temporary:
        shutil.rmtree(work, ignore_errors=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
