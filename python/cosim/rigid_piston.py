"""A rigid-piston solid in Python speaking the cosim coupling protocol (a swappable replacement of solid_solver).

    python3 -m cosim.rigid_piston SCENE --out DIR --coupler ENDPOINT --token T [--set k=v ...]
        [--mass KG] [--area M2] [--left X] [--right X] [--v0 M/S] [--dim 1|2|3] [--dt S] [--restart SET]
    (or python/rigid_piston.py, <build>/python/rigid_piston.py with the same arguments)

The closed boundary of a rigid slab [left, right] x (transverse box) moving along x: 4 segments (2D) or 6 quads
(3D) with their vertices, so a real fluid_solver can embed it. Newton's law under the interface pressures of
the previous cycle (paper section 8, step 1): F = -sum p A n_x, v += dt F / m, x += dt v (symplectic Euler, as
solid_solver's leapfrog). Under coupling.mode robin the states carry the fluid's impedance Z per face and the
pressure on a face is p + Z (v' n_x - v_sent n_x) at the new velocity, taken implicitly as solid_solver does
(docs/methods.md §4.4): (m + theta dt K) v' = m v + dt (F + b - (1 - theta) K v), K = sum Z A n_x^2,
b = sum Z A n_x v_sent n_x, theta = max(1/2, 1 - m / (dt K)). Defaults come from the scene's solid: section when it describes a box mesh with a
rigid block named "piston" (solid_solver format), else from the flags (--area: 2D height x 1 m).
Writes DIR/piston.csv (t, x, v, F) at every OutputRequest; at a CheckpointRequest its state as SET/solid.json,
which --restart SET resumes from.
"""
import argparse
import json
import math
import os
import sys

from .checkpoint import CorruptCheckpoint, read_verified_part
from .client import Client, CouplingError, scene_hash
from .scene import load_scene


PART = "solid.json"  # this solver's part of a checkpoint set


def defaults_from_scene(path):
    """(mass, area, left, right) from a solid_solver box scene with a rigid block 'piston', or None."""
    try:
        s = load_scene(path)["solid"]
        mesh, blocks = s["mesh"], {b["name"]: b for b in s["blocks"]}
        lo, hi = mesh["lower"], mesh["upper"]
        left, right = lo[0], hi[0]
        for r in mesh.get("regions", []):
            if r["block"] == "piston":
                left, right = max(lo[0], r["lower"][0]), min(hi[0], r["upper"][0])
        area = 1.0
        for d in range(1, len(lo)):
            area *= hi[d] - lo[d]
        return blocks["piston"]["density"] * (right - left) * area, area, left, right, lo[1:], hi[1:]
    except Exception:
        return None


def box_faces(dim, x0, x1, lower, upper, v, cross_section=1.0):
    """The closed boundary of the slab [x0, x1] x [lower, upper] (2D: 4 segments, 3D: 6 quads), outward normals,
    vertices and the rigid velocity (v, 0, 0); impedance +inf (rigid), no stress."""
    if dim == 1:  # two points; their "area" is the cross-section (1 m^2 unless --area)
        verts, faces, normals = [(x0,), (x1,)], [(0,), (1,)], [(-1,), (1,)]
    elif dim == 2:
        (y0,), (y1,) = lower, upper
        verts = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
        faces = [(3, 0), (1, 2), (0, 1), (2, 3)]  # -x, +x, -y, +y
        normals = [(-1, 0), (1, 0), (0, -1), (0, 1)]
    else:
        (y0, z0), (y1, z1) = lower, upper
        verts = [(x, y, z) for z in (z0, z1) for y in (y0, y1) for x in (x0, x1)]  # index = x + 2y + 4z
        faces = [(0, 4, 6, 2), (1, 3, 7, 5), (0, 1, 5, 4), (2, 6, 7, 3), (0, 2, 3, 1), (4, 5, 7, 6)]
        normals = [(-1, 0, 0), (1, 0, 0), (0, -1, 0), (0, 1, 0), (0, 0, -1), (0, 0, 1)]
    centre, area = [], []
    for f, n in zip(faces, normals):
        pts = [verts[i] for i in f]
        centre += [sum(p[d] for p in pts) / len(pts) for d in range(dim)]
        size = 1.0
        for d in range(dim):
            if n[d] == 0:
                size *= max(p[d] for p in pts) - min(p[d] for p in pts)
        area.append(size if dim > 1 else cross_section)
    return {
        "dim": dim, "centre": centre, "normal": [c for n in normals for c in n], "area": area,
        "velocity": ([v] + [0.0] * (dim - 1)) * len(faces),
        "normal_stress": [0.0] * len(faces), "impedance": [math.inf] * len(faces),
        "nodes_per_face": len(faces[0]), "vertex_position": [c for p in verts for c in p],
        "face_vertex": [i for f in faces for i in f],
    }


def main(argv=None):
    """Run the piston as the solid of a coupled run; returns the exit code (0, 2 bad argument, 5 protocol)."""
    ap = argparse.ArgumentParser(prog="rigid_piston.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--out", default=".")
    ap.add_argument("--coupler", required=True)
    ap.add_argument("--token", default=os.environ.get("COSIM_TOKEN", ""),
                    help="the run's token (default: $COSIM_TOKEN, which cosim run sets)")
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--mass", type=float)
    ap.add_argument("--area", type=float)
    ap.add_argument("--left", type=float)
    ap.add_argument("--right", type=float)
    ap.add_argument("--v0", type=float, default=0.0)
    ap.add_argument("--dim", type=int, default=2, choices=(1, 2, 3))
    ap.add_argument("--dt", type=float, default=1.0, help="largest step proposed [s]")
    ap.add_argument("--restart", help="resume from this checkpoint set (its solid.json)")
    a = ap.parse_args(argv)
    d = defaults_from_scene(a.scene) or (1.0, 1.0, -0.5, 0.5, [0.0] * (a.dim - 1), [1.0] * (a.dim - 1))
    m, area = a.mass or d[0], a.area or d[1]
    left = a.left if a.left is not None else d[2]
    right = a.right if a.right is not None else d[3]
    lower, upper = d[4], d[5]
    if len(lower) != a.dim - 1:
        a.dim = len(lower) + 1  # the scene's solid mesh decides
    if a.area and len(lower) == a.dim - 1 and a.dim == 2:
        lower, upper = [0.0], [a.area]  # a given cross-section: height = area (x 1 m)
    faces0 = box_faces(a.dim, left, right, lower, upper, 0.0, area)
    areas = faces0["area"]
    normals = [faces0["normal"][i * a.dim:(i + 1) * a.dim] for i in range(len(areas))]
    x, v, force = 0.0, a.v0, 0.0
    p = [0.0] * len(areas)  # interface pressure per face [Pa]
    z = [0.0] * len(areas)  # the fluid's impedance per face (mode robin) [Pa s/m]
    v_sent = 0.0
    os.makedirs(a.out, exist_ok=True)
    csv_path = os.path.join(a.out, "piston.csv")
    tag = "[rigid_piston] "
    cycle, t0 = 0, 0.0
    if a.restart:  # the state of the set's cycle; piston.csv cut back to where it was then
        try:
            ck = json.loads(read_verified_part(a.restart, PART))
            if ck["cycle"] != json.load(open(os.path.join(a.restart, "manifest.json")))["cycle"]:
                raise ValueError("%s holds cycle %s, not the manifest's" % (PART, ck["cycle"]))
        except (OSError, ValueError, KeyError, CorruptCheckpoint) as e:
            print(tag + "error: --restart %s: %s" % (a.restart, e), file=sys.stderr)
            return 2
        cycle, t0 = ck["cycle"], ck["time"]
        x, v, force, p, z, v_sent = ck["x"], ck["v"], ck["force"], ck["p"], ck["z"], ck["v_sent"]
        out = open(csv_path, "r+")
        out.truncate(ck["csv_bytes"])
        out.seek(ck["csv_bytes"])
    else:
        out = open(csv_path, "w")
        out.write("time,x,v,force\n")
    try:
        c = Client(a.coupler, a.token, "solid", scene_hash(a.scene, a.set), program="rigid_piston.py",
                   restarted_from=cycle, restart_time=t0)
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
            if kind == "checkpoint":  # one file, published whole (floats as repr: exact)
                out.flush()
                state = {"cycle": c.cycle, "time": c.time, "x": x, "v": v, "force": force, "p": p, "z": z,
                         "v_sent": v_sent, "csv_bytes": out.tell()}
                tmp = os.path.join(value, PART + ".tmp")
                with open(tmp, "w") as f:
                    json.dump(state, f)
                    f.flush()
                    os.fsync(f.fileno())
                os.replace(tmp, os.path.join(value, PART))
                c.confirm_checkpoint(PART, os.path.getsize(os.path.join(value, PART)))
                continue
            dt = value
            force = sum(-pf * af * nf[0] for pf, af, nf in zip(p, areas, normals))
            k = sum(zf * af * nf[0] ** 2 for zf, af, nf in zip(z, areas, normals))
            if k > 0 and dt > 0:
                theta = max(0.5, 1.0 - m / (dt * k))
                v_new = (m * v + dt * (force + k * v_sent - (1.0 - theta) * k * v)) / (m + theta * dt * k)
                force += k * (v_sent - ((1.0 - theta) * v + theta * v_new))  # the Robin part, for piston.csv
                v = v_new
            else:
                v += dt * force / m
            x += dt * v
            c.send_faces(box_faces(a.dim, left + x, right + x, lower, upper, v, area))
            c.propose_dt(a.dt)
            st = c.receive_states()
            p = list(st.face_pressure)
            z = list(st.face_impedance) if len(st.face_impedance) == len(p) else [0.0] * len(p)
            v_sent = v
    except CouplingError as e:
        print(tag + "error: %s" % e, file=sys.stderr)
        c.report_error(str(e))
        return 5
    finally:
        c.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
