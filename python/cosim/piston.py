"""The rigid piston between two gas chambers (paper 9.3, docs/methods.md §8.2): its two-chamber adiabatic ODE
from a piston scene, and its trajectory in a conforming solid_solver run.

    m x'' = A [pL0 (VL0/(VL0 + A x))^g - pR0 (VR0/(VR0 - A x))^g],  x(0) = x'(0) = 0
"""
import math

import numpy as np

from .errors import RunDirError


def state_at(initial, point, dim):
    """Initial fluid state {p, rho} at a point: the background, overridden by the last region holding it."""
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


def parameters(scene):
    """{A, m, gamma, pL, pR, VL, VR[, m_gas]} of the ODE, read from a coupled piston scene (parsed)."""
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
    gamma = fluid["phases"][0]["eos"]["gamma"]
    mid = [0.5 * (flo[d] + fhi[d]) for d in range(dim)]
    left = state_at(fluid["initial"], [0.5 * (flo[0] + plo[0])] + mid[1:], dim)
    right = state_at(fluid["initial"], [0.5 * (phi[0] + fhi[0])] + mid[1:], dim)
    par = {"A": area, "m": block["density"] * volume, "gamma": float(gamma),
           "pL": float(left["p"]), "pR": float(right["p"]),
           "VL": area * (plo[0] - flo[0]), "VR": area * (fhi[0] - phi[0])}
    if left["rho"] is not None and right["rho"] is not None:
        par["m_gas"] = float(left["rho"]) * par["VL"] + float(right["rho"]) * par["VR"]
    return par


def small_amplitude_period(par, extra_mass=0.0):
    """2 pi / omega of the linearised ODE [s]."""
    omega = math.sqrt(par["gamma"] * par["A"] ** 2 * (par["pL"] / par["VL"] + par["pR"] / par["VR"])
                      / (par["m"] + extra_mass))
    return 2 * math.pi / omega


def solve(par, extra_mass, t_end):
    """RK4 of the ODE from rest with the mass m + extra_mass; returns the arrays t, x, v."""
    A, g, m = par["A"], par["gamma"], par["m"] + extra_mass
    pL, pR, VL, VR = par["pL"], par["pR"], par["VL"], par["VR"]

    def accel(x):
        return A * (pL * (VL / (VL + A * x)) ** g - pR * (VR / (VR - A * x)) ** g) / m

    n = max(1000, int(math.ceil(t_end / (small_amplitude_period(par, extra_mass) / 4000))))
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


def force(par, x):
    """Net gas force on the piston at displacement x [N] (positive to the right)."""
    A, g = par["A"], par["gamma"]
    return A * (par["pL"] * (par["VL"] / (par["VL"] + A * x)) ** g - par["pR"] * (par["VR"] / (par["VR"] - A * x)) ** g)


def conforming_trajectory(run):
    """t, x - x(0), v of the rigid block 'piston' in a conforming solid_solver run (a Run): the mean of its nodes
    in each solid snapshot."""
    summary = run.summaries.get("solid")
    if run.solid is None or not len(run.solid) or summary is None:
        raise RunDirError(f"{run.directory}: not a solid_solver run directory (no solid snapshots or summary.json)")
    bodies = [b for b in summary.get("rigid_bodies", []) if b.get("block") == "piston"]
    if not bodies:
        raise RunDirError(f"{run.directory}/summary.json: no rigid body 'piston'")
    final_x = bodies[0]["centre_of_mass"][0]
    # The snapshots store block indices, the summary block names: the piston is the block whose final node
    # centre is nearest the summary's final piston centre of mass.
    last = run.solid[-1]
    block, conn, xyz = last["block"], last.grid.connectivity, last.grid.coordinates
    nodes_of = {b: np.unique(conn[block == b]) for b in np.unique(block)}
    nodes = nodes_of[min(nodes_of, key=lambda b: abs(xyz[nodes_of[b], 0].mean() - final_x))]
    t, x, v = [], [], []
    for snap in run.solid:
        t.append(snap.time)
        x.append(snap.grid.coordinates[nodes, 0].mean())
        v.append(snap["velocity"][nodes, 0].mean())
    t, x, v = map(np.array, (t, x, v))
    order = np.argsort(t)
    return t[order], x[order] - x[order][0], v[order]


def max_deviation(t, x, t_ref, x_ref):
    """Largest |x - x_ref| over the common time range, x_ref interpolated to the times t."""
    keep = (t >= t_ref[0]) & (t <= t_ref[-1])
    return float(np.max(np.abs(x[keep] - np.interp(t[keep], t_ref, x_ref))))
