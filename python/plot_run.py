#!/usr/bin/python3
"""PNG plots of a cosim run directory (coupled `cosim run` output, or a fluid-only run).

Usage:
    /usr/bin/python3 python/plot_run.py RUN_DIR [--out DIR] [--reference CONFORMING_RUN_DIR] [--show-ghosts]

RUN_DIR is what `cosim run SCENE --out RUN_DIR` writes (scene.yaml, fluid/, and for a coupled run
coupler/ and solid/); a bare fluid_solver output directory (fluid_NNNNNN.h5 in it) works too.
Writes into --out (default RUN_DIR/plots/):

  motion.png     coupled: structure displacement (interface centre_x - its initial value) and velocity
                 against time; for a piston scene (name "piston...", rigid block "piston") also the
                 two-chamber adiabatic ODE
                   m x'' = A [pL0 (VL0/(VL0 + A x))^g - pR0 (VR0/(VR0 - A x))^g],  x(0) = x'(0) = 0,
                 the same ODE with the gas inertia (m + m_gas/3, dashed) and, with --reference, the
                 conforming all-Lagrangian run of `solid_solver configs/solid_piston_1d.yaml --out DIR`
                 (position = mean x of the piston block's nodes in each solid snapshot).
  interface.png  coupled: area-mean interface pressure and the interface force (ODE force for a piston).
  fields.png     last fluid snapshot: pressure, density, velocity magnitude (2D images; the cells inside a body,
                 embedded_category solid-cut, ghost and solid, masked grey, with --show-ghosts only the solid
                 ones; the embedded interface faces of the matching fluid_interface CSV as red points;
                 3D: the mid-plane z slice; 1D: line plots, velocity x).
  timing.png     coupled: wall time per cycle, stacked solid / fluid / coupler / comm (coupler/timing.csv).

For a piston scene the maximum deviations of the run from each reference are printed as % of the ODE's
peak-to-peak amplitude. Exit status 2 when RUN_DIR (or the reference directory) is not a run directory.
"""
import argparse
import csv
import glob
import json
import math
import os
import sys

import h5py
import matplotlib
import numpy as np
import yaml

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SOLID_CATEGORY = 4  # embedded_category: 0 fluid, 1 fluid cut, 2 solid cut, 3 ghost, 4 solid
LAST_FLOW_CATEGORY = 1  # categories above it are inside a body (their values are ghost states)
DPI = 110


class RunError(Exception):
    """A missing or malformed input file; the message names it."""


# ----------------------------------------------------------------------------------------------- reading


def find_run(run_dir):
    """Paths of the parts of a run directory; RunError if it is not one."""
    if not os.path.isdir(run_dir):
        raise RunError(f"{run_dir}: no such directory")
    fluid = os.path.join(run_dir, "fluid")
    if not glob.glob(os.path.join(fluid, "fluid_*.h5")) and glob.glob(os.path.join(run_dir, "fluid_*.h5")):
        fluid = run_dir  # a bare fluid_solver output directory
    history = os.path.join(run_dir, "coupler", "interface_history.csv")
    run = {
        "dir": run_dir,
        "scene": os.path.join(run_dir, "scene.yaml"),
        "fluid": fluid if glob.glob(os.path.join(fluid, "fluid_*.h5")) else None,
        "history": history if os.path.isfile(history) else None,
        "timing": os.path.join(run_dir, "coupler", "timing.csv"),
        "coupler_summary": os.path.join(run_dir, "coupler", "coupler_summary.json"),
    }
    if run["fluid"] is None and run["history"] is None:
        raise RunError(f"{run_dir}: not a run directory (neither {os.path.join(fluid, 'fluid_*.h5')} "
                       f"nor {history} exists)")
    return run


def load_yaml(path):
    try:
        with open(path) as f:
            return yaml.safe_load(f) or {}
    except OSError as e:
        raise RunError(f"{path}: {e.strerror}") from e
    except yaml.YAMLError as e:
        raise RunError(f"{path}: not valid YAML ({e})") from e


def read_csv_columns(path):
    """{column: float array} of a CSV file with a header line."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise RunError(f"{path}: {e.strerror}") from e
    if len(rows) < 2:
        raise RunError(f"{path}: no data rows")
    if len(rows[-1]) != len(rows[0]) and len(rows) < 3:
        raise RunError(f"{path}: no complete data row")
    try:
        width = len(rows[0])  # a run still in progress may have a partly written last line
        data = np.array([[float(v) for v in r] for r in rows[1:] if len(r) == width], dtype=float)
    except ValueError as e:
        raise RunError(f"{path}: {e}") from e
    return {name: data[:, i] for i, name in enumerate(rows[0])}


def snapshot_files(directory, prefix):
    return sorted(glob.glob(os.path.join(directory, f"{prefix}_[0-9]*.h5")))


def read_uniform_snapshot(path):
    """Grid and cell fields of a cosim-snapshot-1 file on a uniform grid."""
    try:
        with h5py.File(path, "r") as f:
            g = f["grid"].attrs
            grid = {"dim": int(g["dim"]), "cells": [int(c) for c in g["cells"]],
                    "origin": np.array(g["origin"], float), "spacing": np.array(g["spacing"], float)}
            fields = {k: f["cell"][k][()] for k in f["cell"].keys()}
            return grid, fields, float(f.attrs["time"])
    except (OSError, KeyError) as e:
        raise RunError(f"{path}: not a readable uniform-grid snapshot ({e})") from e


# -------------------------------------------------------------------------------------- piston reference


def state_at(initial, point, dim):
    """Initial fluid state (dict with p, rho) at a point: background, overridden by the last region containing it."""
    def contains(region):
        if "box" in region:
            lo, hi = region["box"]["lower"], region["box"]["upper"]
            return all(lo[d] <= point[d] <= hi[d] for d in range(dim))
        if "sphere" in region:
            c, r = region["sphere"]["center"], region["sphere"]["radius"]
            return sum((point[d] - c[d]) ** 2 for d in range(dim)) <= r * r
        if "half_space" in region:
            a, n = region["half_space"]["point"], region["half_space"]["normal"]
            return sum((point[d] - a[d]) * n[d] for d in range(dim)) >= 0
        return False
    state = initial.get("state", {})
    for region in initial.get("regions", []) or []:
        if contains(region):
            state = region["state"]
    phases = state.get("phases")
    first = phases[0] if phases else {}
    return {"p": first.get("p", state.get("p")), "rho": first.get("rho", state.get("rho"))}


def piston_box(solid):
    """(lower, upper) of the solid block named 'piston' on a box mesh."""
    mesh = solid["mesh"]
    if mesh.get("type", "box") != "box":
        raise KeyError("solid.mesh.type is not box")
    names = [b["name"] for b in solid["blocks"]]
    if "piston" not in names:
        raise KeyError("no solid block named 'piston'")
    lo, hi = list(map(float, mesh["lower"])), list(map(float, mesh["upper"]))
    for r in mesh.get("regions", []) or []:
        if r["block"] == "piston":
            lo = [max(a, float(b)) for a, b in zip(lo, r["lower"])]
            hi = [min(a, float(b)) for a, b in zip(hi, r["upper"])]
    return lo, hi


def piston_parameters(scene):
    """Parameters of the two-chamber ODE from a coupled piston scene (all read from scene.yaml)."""
    fluid, solid = scene["fluid"], scene["solid"]
    flo, fhi = fluid["mesh"]["lower"], fluid["mesh"]["upper"]
    dim = len(flo)
    area = 1.0
    for d in range(1, dim):
        area *= fhi[d] - flo[d]
    plo, phi = piston_box(solid)
    volume = 1.0
    for d in range(len(plo)):
        volume *= phi[d] - plo[d]
    block = next(b for b in solid["blocks"] if b["name"] == "piston")
    if not block.get("rigid", False):
        raise ValueError("solid block 'piston' is not rigid: the two-chamber ODE is for a rigid piston")
    density = block["density"]
    gamma = fluid["phases"][0]["eos"]["gamma"]
    mid = [0.5 * (flo[d] + fhi[d]) for d in range(dim)]
    left = state_at(fluid["initial"], [0.5 * (flo[0] + plo[0])] + mid[1:], dim)
    right = state_at(fluid["initial"], [0.5 * (phi[0] + fhi[0])] + mid[1:], dim)
    par = {"A": area, "m": density * volume, "gamma": float(gamma),
           "pL": float(left["p"]), "pR": float(right["p"]),
           "VL": area * (plo[0] - flo[0]), "VR": area * (fhi[0] - phi[0])}
    if left["rho"] is not None and right["rho"] is not None:
        par["m_gas"] = float(left["rho"]) * par["VL"] + float(right["rho"]) * par["VR"]
    return par


def solve_piston_ode(par, extra_mass, t_end):
    """RK4 of the two-chamber ODE from rest; returns t, x, v."""
    A, g, m = par["A"], par["gamma"], par["m"] + extra_mass
    pL, pR, VL, VR = par["pL"], par["pR"], par["VL"], par["VR"]

    def accel(x):
        return A * (pL * (VL / (VL + A * x)) ** g - pR * (VR / (VR - A * x)) ** g) / m

    omega = math.sqrt(g * A * A * (pL / VL + pR / VR) / m)  # small-amplitude estimate, sets the step
    n = max(1000, int(math.ceil(t_end / (2 * math.pi / omega / 4000))))
    dt = t_end / n
    x, v = np.zeros(n + 1), np.zeros(n + 1)
    for i in range(n):
        x0, v0 = x[i], v[i]
        k1x, k1v = v0, accel(x0)
        k2x, k2v = v0 + 0.5 * dt * k1v, accel(x0 + 0.5 * dt * k1x)
        k3x, k3v = v0 + 0.5 * dt * k2v, accel(x0 + 0.5 * dt * k2x)
        k4x, k4v = v0 + dt * k3v, accel(x0 + dt * k3x)
        x[i + 1] = x0 + dt / 6 * (k1x + 2 * k2x + 2 * k3x + k4x)
        v[i + 1] = v0 + dt / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
    return np.linspace(0.0, t_end, n + 1), x, v


def ode_force(par, x):
    """Net gas force on the piston at displacement x (positive to the right)."""
    A, g = par["A"], par["gamma"]
    return A * (par["pL"] * (par["VL"] / (par["VL"] + A * x)) ** g - par["pR"] * (par["VR"] / (par["VR"] - A * x)) ** g)


def reference_trajectory(ref_dir):
    """t, x, v of the rigid block 'piston' in a conforming solid_solver run (node means of its cells)."""
    files = snapshot_files(ref_dir, "solid")
    summary_path = os.path.join(ref_dir, "summary.json")
    if not files or not os.path.isfile(summary_path):
        raise RunError(f"{ref_dir}: not a solid_solver run directory (no solid_*.h5 or summary.json)")
    with open(summary_path) as f:
        bodies = [b for b in json.load(f).get("rigid_bodies", []) if b.get("block") == "piston"]
    if not bodies:
        raise RunError(f"{summary_path}: no rigid body 'piston'")
    final_x = bodies[0]["centre_of_mass"][0]
    # The snapshots store block indices, the summary block names: the piston is the block whose final node
    # centre is nearest the summary's final piston centre of mass.
    with h5py.File(files[-1], "r") as f:
        block, conn, xyz = f["cell/block"][()], f["grid/connectivity"][()], f["grid/coordinates"][()]
    nodes_of = {b: np.unique(conn[block == b]) for b in np.unique(block)}
    piston = min(nodes_of, key=lambda b: abs(xyz[nodes_of[b], 0].mean() - final_x))
    nodes = nodes_of[piston]
    t, x, v = [], [], []
    for path in files:
        with h5py.File(path, "r") as f:
            t.append(float(f.attrs["time"]))
            x.append(f["grid/coordinates"][()][nodes, 0].mean())
            v.append(f["node/velocity"][()][nodes, 0].mean())
    t, x, v = map(np.array, (t, x, v))
    order = np.argsort(t)
    return t[order], x[order] - x[order][0], v[order]


def max_deviation(t, x, t_ref, x_ref):
    """Largest |x - x_ref| over the common time range, x_ref interpolated to the times t."""
    keep = (t >= t_ref[0]) & (t <= t_ref[-1])
    return float(np.max(np.abs(x[keep] - np.interp(t[keep], t_ref, x_ref))))


# ---------------------------------------------------------------------------------------------- plotting


def save(fig, out_dir, name):
    path = os.path.join(out_dir, name)
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    print(f"wrote {path}")


def plot_motion(hist, refs, title, out_dir):
    """Displacement and velocity of the structure against time, with the reference curves in refs."""
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
    save(fig, out_dir, "motion.png")


def plot_interface(hist, par, title, out_dir):
    """Area-mean interface pressure and the interface force against time."""
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
    save(fig, out_dir, "interface.png")


def field_set(fields):
    """(label prefix, pressure, density, velocity) arrays: mixture fields if present, else the first phase."""
    if "mixture_pressure" in fields:
        prefix = "mixture"
    else:
        phases = sorted(k[:-len("_pressure")] for k in fields if k.endswith("_pressure"))
        if not phases:
            raise RunError("fluid snapshot has no *_pressure field")
        prefix = phases[0]
    return prefix, fields[f"{prefix}_pressure"], fields[f"{prefix}_density"], fields[f"{prefix}_velocity"]


def plot_fields_1d(grid, fields, t, path_label, out_dir):
    prefix, p, rho, vel = field_set(fields)
    x = grid["origin"][0] + (np.arange(grid["cells"][0]) + 0.5) * grid["spacing"][0]
    rows = [(p, "pressure [Pa]"), (rho, "density [kg/m^3]"), (vel[:, 0], "velocity x [m/s]")]
    fig, axes = plt.subplots(3, 1, figsize=(8, 7), sharex=True)
    for ax, (v, label) in zip(axes, rows):
        ax.plot(x, v, lw=1.3)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].set_title(f"{prefix} at t = {t:.4g} s ({path_label})")
    axes[-1].set_xlabel("x [m]")
    save(fig, out_dir, "fields.png")


def interface_points(csv_path, dim, z_mid, dz):
    """(x, y) of the embedded interface faces of a fluid_interface CSV (3D: those near the z mid-plane)."""
    if not csv_path or not os.path.isfile(csv_path):
        return None
    cols = read_csv_columns(csv_path) if os.path.getsize(csv_path) > 0 else {}
    if "cx" not in cols:
        return None
    keep = np.ones(len(cols["cx"]), bool) if dim < 3 else np.abs(cols["cz"] - z_mid) <= 0.5 * dz
    return cols["cx"][keep], cols["cy"][keep]


def colour_limits(values):
    """(vmin, vmax, note): a field uniform to round-off gets a +-1% range instead of a colour bar of noise."""
    lo, hi = float(np.ma.min(values)), float(np.ma.max(values))
    ref = max(abs(lo), abs(hi))
    if hi - lo > 1e-9 * ref:
        return lo, hi, ""
    centre, half = 0.5 * (lo + hi), 0.01 * ref if ref > 0 else 1.0
    return centre - half, centre + half, f" (uniform, max - min = {hi - lo:.2g})"


def plot_fields_2d(grid, fields, t, path_label, csv_path, out_dir, mask_ghosts):
    prefix, p, rho, vel = field_set(fields)
    dim = grid["dim"]
    k_mid = grid["cells"][2] // 2 if dim == 3 else 0
    plane = (lambda a: a[k_mid]) if dim == 3 else (lambda a: a)
    speed = np.linalg.norm(vel, axis=-1)
    mask = None
    if "embedded_category" in fields:
        category = plane(fields["embedded_category"])
        mask = category > LAST_FLOW_CATEGORY if mask_ghosts else category == SOLID_CATEGORY
    o, h, n = grid["origin"], grid["spacing"], grid["cells"]
    extent = [o[0], o[0] + n[0] * h[0], o[1], o[1] + n[1] * h[1]]
    z_mid = o[2] + (k_mid + 0.5) * h[2]
    points = interface_points(csv_path, dim, z_mid, h[2])
    width, height = extent[1] - extent[0], extent[3] - extent[2]
    wide = width > 1.5 * height
    panels = [(p, "pressure [Pa]", "viridis"), (rho, "density [kg/m^3]", "cividis"),
              (speed, "velocity magnitude [m/s]", "magma")]
    if wide:
        fig, axes = plt.subplots(3, 1, figsize=(10, min(12, 0.6 + 3 * (1.0 + 8.5 * height / width))))
    else:
        fig, axes = plt.subplots(1, 3, figsize=(15, min(6, 1.2 + 3.9 * height / width)))
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
    fig.suptitle(f"{prefix} at t = {t:.4g} s ({path_label}{where}{masked})", fontsize=11)
    if points is not None and len(points[0]):
        axes[0].legend(fontsize=8, loc="upper right")
    save(fig, out_dir, "fields.png")


def plot_fields(fluid_dir, out_dir, mask_ghosts=True):
    files = snapshot_files(fluid_dir, "fluid")
    grid, fields, t = read_uniform_snapshot(files[-1])
    name = os.path.basename(files[-1])
    csv_path = os.path.join(fluid_dir, name.replace("fluid_", "fluid_interface_").replace(".h5", ".csv"))
    if grid["dim"] == 1:
        plot_fields_1d(grid, fields, t, name, out_dir)
    else:
        plot_fields_2d(grid, fields, t, name, csv_path, out_dir, mask_ghosts)


def plot_timing(timing_path, summary_path, out_dir, max_bins=600):
    """Stacked wall time per cycle (solid, fluid, coupler, comm); cycles averaged in bins when there are many.
    In the pipelined cycle the solid works while the fluid does: the longer of the two is stacked, the solid
    drawn as a line."""
    summary = {}
    if os.path.isfile(summary_path):
        with open(summary_path) as f:
            summary = json.load(f)
    overlapped = summary.get("scheme") == "pipelined"
    cols = read_csv_columns(timing_path)
    cycle = cols["cycle"]
    solid = cols["solid"] * 1e3
    if overlapped:
        parts = ["solver (max of solid, fluid)", "coupler", "comm"]
        values = [np.maximum(cols["solid"], cols["fluid"]) * 1e3, cols["coupler"] * 1e3, cols["comm"] * 1e3]
    else:
        parts = ["solid", "fluid", "coupler", "comm"]
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
    save(fig, out_dir, "timing.png")


# -------------------------------------------------------------------------------------------------- main


def piston_references(scene, hist, reference_dir):
    """ODE curves (and the conforming run) for a piston scene; prints the deviations of the run."""
    try:
        par = piston_parameters(scene)
    except (KeyError, TypeError, IndexError, ValueError, StopIteration) as e:
        print(f"piston ODE skipped: {e}" if isinstance(e, ValueError) else
              f"piston ODE skipped: scene.yaml lacks what it needs ({e!r})")
        return None, []
    t_end = float(hist["time"][-1])
    try:  # the whole scheduled run, so that the amplitude is the ODE's even for a run still in progress
        t_end = max(t_end, float(scene["coupling"]["time"]["end"]))
    except (KeyError, TypeError, ValueError):
        pass
    t, x, v = solve_piston_ode(par, 0.0, t_end)
    amp = float(x.max() - x.min())
    print(f"piston ODE: A = {par['A']:.4g} m^2, m = {par['m']:.4g} kg, gamma = {par['gamma']:.4g}, "
          f"pL0 = {par['pL']:.4g} Pa, pR0 = {par['pR']:.4g} Pa, VL0 = {par['VL']:.4g} m^3, VR0 = {par['VR']:.4g} m^3; "
          f"turning points {x.min():.4f} .. {x.max():.4f} m (peak-to-peak {amp:.4f} m)")
    refs = [{"t": t, "x": x, "v": v, "label": "two-chamber ODE", "style": {"color": "k", "lw": 1.0}}]
    if "m_gas" in par:
        tg, xg, vg = solve_piston_ode(par, par["m_gas"] / 3.0, t_end)
        refs.append({"t": tg, "x": xg, "v": vg, "label": f"ODE with gas inertia (m + {par['m_gas'] / 3:.3g} kg)",
                     "style": {"color": "k", "lw": 1.0, "ls": "--"}})
    if reference_dir:
        tr, xr, vr = reference_trajectory(reference_dir)
        refs.append({"t": tr, "x": xr, "v": vr, "label": "conforming all-Lagrangian run",
                     "style": {"color": "C3", "ls": "none", "marker": "o", "ms": 3}})
    run_x = hist["centre_x"] - hist["centre_x"][0]
    for r in refs:
        dev = max_deviation(hist["time"], run_x, r["t"], r["x"])
        print(f"max deviation of the coupled run from the {r['label']}: {dev:.4g} m = {100 * dev / amp:.2f}% "
              f"of the ODE peak-to-peak amplitude")
    if reference_dir and "m_gas" in par:
        dev = max_deviation(refs[-1]["t"], refs[-1]["x"], refs[1]["t"], refs[1]["x"])
        print(f"(for comparison: conforming run vs ODE with gas inertia: {100 * dev / amp:.2f}%)")
    return par, refs


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("run_dir", metavar="RUN_DIR")
    ap.add_argument("--out", metavar="DIR", help="output directory (default RUN_DIR/plots)")
    ap.add_argument("--reference", metavar="CONFORMING_RUN_DIR",
                    help="output of `solid_solver configs/solid_piston_1d.yaml --out DIR` (piston scenes)")
    ap.add_argument("--show-ghosts", action="store_true",
                    help="mask only the embedded_category == solid cells (show ghost and solid-cut cell values)")
    args = ap.parse_args(argv)
    try:
        run = find_run(args.run_dir)
        out_dir = args.out or os.path.join(args.run_dir, "plots")
        os.makedirs(out_dir, exist_ok=True)
        scene = load_yaml(run["scene"]) if os.path.isfile(run["scene"]) else {}
        name = str(scene.get("name", os.path.basename(os.path.abspath(args.run_dir))))
        if run["history"]:
            hist = read_csv_columns(run["history"])
            par, refs = None, []
            if name.startswith("piston"):
                par, refs = piston_references(scene, hist, args.reference)
            elif args.reference:
                print(f"--reference ignored: scene '{name}' is not a piston scene")
            plot_motion(hist, refs, f"{name}: structure (interface centre) motion", out_dir)
            plot_interface(hist, par, f"{name}: interface pressure and force", out_dir)
        elif args.reference:
            print("--reference ignored: not a coupled run (no coupler/interface_history.csv)")
        if run["fluid"]:
            plot_fields(run["fluid"], out_dir, mask_ghosts=not args.show_ghosts)
        if os.path.isfile(run["timing"]):
            plot_timing(run["timing"], run["coupler_summary"], out_dir)
    except RunError as e:
        print(f"plot_run.py: error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
