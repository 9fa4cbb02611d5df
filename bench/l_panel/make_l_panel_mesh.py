#!/usr/bin/env python3
"""Winkler's L-shaped panel as a 2D mesh of square cells (AVS UCD, .inp).

Usage: make_l_panel_mesh.py SIDE N OUTPUT.inp

The square [0, SIDE]^2 without its lower right quarter [SIDE/2, SIDE] x
[0, SIDE/2], cut into N x N square cells of side SIDE / N (N even) of which
the 3N^2/4 outside the cut-out are kept: PD nodes at the cell centres. The
re-entrant corner is at (SIDE/2, SIDE/2). Vertices are shared, so the mesh
is conforming; deal.II's GridIn reads it ('Geometry/Mesh = file'), with
boundary id 0 on every face.
"""
import sys

side, n = float(sys.argv[1]), int(sys.argv[2])
path = sys.argv[3]
if n % 2:
    sys.exit("N must be even, so that the corner is a vertex")
h = side / n
vertex_ids = {}
vertices = []
cells = []


def vertex(i, j):
    key = (i, j)
    if key not in vertex_ids:
        vertex_ids[key] = len(vertices) + 1
        vertices.append((i * h, j * h))
    return vertex_ids[key]


for j in range(n):
    for i in range(n):
        if i >= n // 2 and j < n // 2:
            continue
        # UCD quadrilateral, counterclockwise.
        cells.append([vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1),
                      vertex(i, j + 1)])
with open(path, "w") as f:
    f.write(f"{len(vertices)} {len(cells)} 0 0 0\n")
    for v, (x, y) in enumerate(vertices, 1):
        f.write(f"{v} {x:.17g} {y:.17g} 0\n")
    for c, ids in enumerate(cells, 1):
        f.write(f"{c} 0 quad " + " ".join(map(str, ids)) + "\n")
print(f"{len(cells)} cells, {len(vertices)} vertices -> {path}")
