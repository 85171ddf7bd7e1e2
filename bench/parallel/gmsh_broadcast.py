#!/usr/bin/python3
"""A Gmsh mesh read once and broadcast: what rank 0's read and the broadcast of the parsed mesh cost.

Writes the steel panel of configs/shock_panel_2d_gmsh.yaml at NX x NY quadrangles (scripts/make_panel_mesh.py) into
a temporary folder, then runs build/bin/solid_solver on it for one step (no snapshots) alone and on 2 and 3 ranks
(mpirun), and prints from each run's summary.json: rank 0's read (open and parse), the packed mesh's bytes, the
packing, the broadcast (rank 0's time in it) and the unpacking (the slowest rank's), and the state's bytes per element
that every rank still holds.

Usage: /usr/bin/python3 bench/parallel/gmsh_broadcast.py [NX NY]   (default 200 1000: 200,000 elements)
"""
import json
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = os.path.join(ROOT, "build", "bin", "solid_solver")
MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe", "--bind-to", "none"]

SCENE = """name: panel_gmsh_broadcast
solid:
  mesh: {type: gmsh, file: panel.msh}
  blocks:
    - name: panel
      material: steel
      strength: {shear_modulus: 7.77e10, yield_stress: 7.92e8}
  boundaries:
    - {set: clamp_bottom, type: fixed}
    - {set: clamp_top, type: fixed}
  time: {end: 1.0e-3, max_steps: 1}
  output: {snapshots: false}
"""


def main():
    nx, ny = (int(sys.argv[1]), int(sys.argv[2])) if len(sys.argv) > 2 else (200, 1000)
    with tempfile.TemporaryDirectory() as tmp:
        mesh = os.path.join(tmp, "panel.msh")
        t0 = time.time()
        subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "make_panel_mesh.py"), str(nx), str(ny), mesh],
                       check=True, stdout=subprocess.DEVNULL)
        made = time.time() - t0
        scene = os.path.join(tmp, "scene.yaml")
        with open(scene, "w") as fh:
            fh.write(SCENE)
        print(f"mesh: {nx} x {ny} = {nx * ny:,} quadrangles, {(nx + 1) * (ny + 1):,} nodes, "
              f"{os.path.getsize(mesh) / 1e6:.1f} MB of text, written in {made:.1f} s\n")
        print("| ranks | rank 0 reads | packed mesh | pack | broadcast | unpack | run wall | state per element |")
        print("|---|---|---|---|---|---|---|---|")
        for ranks in (1, 2, 3):
            out = os.path.join(tmp, f"out{ranks}")
            cmd = ([] if ranks == 1 else MPIRUN + ["-np", str(ranks)]) + [BIN, scene, "--out", out, "--quiet",
                                                                          "--threads", "1"]
            t0 = time.time()
            subprocess.run(cmd, check=True)
            wall = time.time() - t0
            with open(os.path.join(out, "summary.json")) as fh:
                s = json.load(fh)
            m = s["parallel"].get("mesh")
            if m is None:
                row = ["(itself)", "-", "-", "-", "-"]
            else:
                assert m["read_by_ranks"] == [0], m
                row = [f"{m['read_seconds']:.2f} s", f"{m['bytes'] / 1e6:.1f} MB ({m['bytes'] / s['elements']:.0f} B "
                       "per element)", f"{m['pack_seconds']:.3f} s", f"{m['broadcast_seconds']:.3f} s",
                       f"{m['unpack_seconds']:.3f} s"]
            print(f"| {ranks} | " + " | ".join(row) + f" | {wall:.1f} s | {s['bytes_per_element']:.0f} B |")


if __name__ == "__main__":
    main()
