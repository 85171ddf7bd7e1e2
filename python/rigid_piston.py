#!/usr/bin/python3
"""A rigid-piston solid in Python speaking the cosim coupling protocol (a swappable replacement of solid_solver).

    rigid_piston.py SCENE --out DIR --coupler ENDPOINT --token T [--set k=v ...]
                    [--mass KG] [--area M2] [--left X] [--right X] [--v0 M/S] [--dim 2|3]

One face pair: the left face (normal -x) and the right face (normal +x) of a rigid slab [left, right] with
cross-section `area`. Newton's law under the interface pressures of the previous cycle (paper section 8, step 1):
F = (p_left - p_right) * area, v += dt F / m, x += dt v (symplectic Euler). Defaults come from the scene's solid:
section when it describes a box mesh with a rigid block named "piston" (solid_solver format), else from the flags.
Writes DIR/piston.csv (t, x, v, F) at every OutputRequest.
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cosim_client import Client, CouplingError, scene_hash  # noqa: E402


def defaults_from_scene(path):
    """(mass, area, left, right) from a solid_solver box scene with a rigid block 'piston', or None."""
    try:
        import yaml
        s = yaml.safe_load(open(path))["solid"]
        mesh, blocks = s["mesh"], {b["name"]: b for b in s["blocks"]}
        lo, hi = mesh["lower"], mesh["upper"]
        left, right = lo[0], hi[0]
        for r in mesh.get("regions", []):
            if r["block"] == "piston":
                left, right = max(lo[0], r["lower"][0]), min(hi[0], r["upper"][0])
        area = 1.0
        for d in range(1, len(lo)):
            area *= hi[d] - lo[d]
        return blocks["piston"]["density"] * (right - left) * area, area, left, right
    except Exception:
        return None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--out", default=".")
    ap.add_argument("--coupler", required=True)
    ap.add_argument("--token", default="")
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--mass", type=float)
    ap.add_argument("--area", type=float)
    ap.add_argument("--left", type=float)
    ap.add_argument("--right", type=float)
    ap.add_argument("--v0", type=float, default=0.0)
    ap.add_argument("--dim", type=int, default=2, choices=(2, 3))
    ap.add_argument("--dt", type=float, default=1.0, help="largest step proposed [s]")
    a = ap.parse_args()
    d = defaults_from_scene(a.scene) or (1.0, 1.0, -0.5, 0.5)
    m, area = a.mass or d[0], a.area or d[1]
    left = a.left if a.left is not None else d[2]
    right = a.right if a.right is not None else d[3]
    x, v, force = 0.0, a.v0, 0.0
    p = [0.0, 0.0]  # interface pressure on the left and right face [Pa]
    os.makedirs(a.out, exist_ok=True)
    out = open(os.path.join(a.out, "piston.csv"), "w")
    out.write("time,x,v,force\n")
    tag = "[rigid_piston] "
    try:
        c = Client(a.coupler, a.token, "solid", scene_hash(a.scene, a.set), program="rigid_piston.py")
    except CouplingError as e:
        print(tag + "error: %s" % e, file=sys.stderr)
        return 5
    try:
        while True:
            kind, value = c.next()
            if kind == "stop":
                print(tag + "stop: " + value, file=sys.stderr)
                break
            if kind == "output":
                out.write("%.12g,%.12g,%.12g,%.12g\n" % (c.output_time, x, v, force))
                out.flush()
                continue
            dt = value
            force = (p[0] - p[1]) * area
            v += dt * force / m
            x += dt * v
            zero = [0.0] * (a.dim - 1)
            ymid = [0.0] * (a.dim - 1)
            c.send_faces({
                "dim": a.dim,
                "centre": [left + x] + ymid + [right + x] + ymid,
                "normal": [-1.0] + zero + [1.0] + zero,
                "area": [area, area],
                "velocity": [v] + zero + [v] + zero,
                "normal_stress": [0.0, 0.0],
                "impedance": [math.inf, math.inf],
            })
            st = c.receive_states()
            p = list(st.face_pressure)
            c.propose_dt(a.dt)
    except CouplingError as e:
        print(tag + "error: %s" % e, file=sys.stderr)
        c.report_error(str(e))
        return 5
    finally:
        c.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
