#!/usr/bin/python3
"""Writes the steel panel of configs/shock_panel_2d.yaml as a Gmsh 4.1 ASCII mesh (what Gmsh would write for a
transfinite 5 x 25 quad surface): one surface group "panel" and the two clamped short ends as curve groups
"clamp_bottom" (y = 0.25) and "clamp_top" (y = 0.75), plus "front" (x = 0.45) and "back" (x = 0.55).

Usage: scripts/make_panel_mesh.py [NX NY] [OUT]   (default 5 25 configs/meshes/panel_5x25.msh)
"""
import sys

nx = int(sys.argv[1]) if len(sys.argv) > 2 else 5
ny = int(sys.argv[2]) if len(sys.argv) > 2 else 25
out = sys.argv[3] if len(sys.argv) > 3 else f"configs/meshes/panel_{nx}x{ny}.msh"
x0, x1, y0, y1 = 0.45, 0.55, 0.25, 0.75


def node(i, j):
    return 1 + j * (nx + 1) + i


groups = {"clamp_bottom": 11, "clamp_top": 12, "front": 13, "back": 14}
curves = {  # physical tag -> boundary segments (node pairs, counter-clockwise around the panel)
    11: [(node(i, 0), node(i + 1, 0)) for i in range(nx)],
    14: [(node(nx, j), node(nx, j + 1)) for j in range(ny)],
    12: [(node(i + 1, ny), node(i, ny)) for i in range(nx)],
    13: [(node(0, j + 1), node(0, j)) for j in range(ny)],
}
bbox = {11: (x0, y0, x1, y0), 14: (x1, y0, x1, y1), 12: (x0, y1, x1, y1), 13: (x0, y0, x0, y1)}
lines = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$PhysicalNames", str(len(groups) + 1)]
lines += [f'1 {tag} "{name}"' for name, tag in groups.items()] + ['2 21 "panel"', "$EndPhysicalNames"]
lines += ["$Entities", f"0 {len(curves)} 1 0"]
for k, tag in enumerate(curves, start=1):
    a = bbox[tag]
    lines.append(f"{k} {a[0]} {a[1]} 0 {a[2]} {a[3]} 0 1 {tag} 0")
lines += [f"1 {x0} {y0} 0 {x1} {y1} 0 1 21 0", "$EndEntities"]
nn = (nx + 1) * (ny + 1)
lines += ["$Nodes", f"1 {nn} 1 {nn}", f"2 1 0 {nn}"] + [str(n) for n in range(1, nn + 1)]
for j in range(ny + 1):
    for i in range(nx + 1):
        lines.append(f"{x0 + (x1 - x0) * i / nx:.17g} {y0 + (y1 - y0) * j / ny:.17g} 0")
lines.append("$EndNodes")
nb = sum(len(s) for s in curves.values())
ne = nb + nx * ny
lines += ["$Elements", f"{len(curves) + 1} {ne} 1 {ne}"]
tag = 1
for k, (phys, segs) in enumerate(curves.items(), start=1):
    lines.append(f"1 {k} 1 {len(segs)}")
    for a, b in segs:
        lines.append(f"{tag} {a} {b}")
        tag += 1
lines.append(f"2 1 3 {nx * ny}")
for j in range(ny):
    for i in range(nx):
        lines.append(f"{tag} {node(i, j)} {node(i + 1, j)} {node(i + 1, j + 1)} {node(i, j + 1)}")
        tag += 1
lines.append("$EndElements")
with open(out, "w") as fh:
    fh.write("\n".join(lines) + "\n")
print(out)
