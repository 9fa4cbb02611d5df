#!/usr/bin/env python3
"""A hollow cylinder as a mesh of axis-aligned cubes (AVS UCD, .inp).

Usage: make_cylinder_mesh.py R_INNER R_OUTER HEIGHT H OUTPUT.inp

Keeps the cubes of side H of the lattice [-R_OUTER, R_OUTER]^2 x [0, HEIGHT]
whose centre lies at a distance in [R_INNER, R_OUTER] from the axis (x = y =
0): PD nodes at the cell centres, the way a lattice code (LAMMPS) builds a
cylinder. Vertices are shared, so the mesh is conforming; deal.II's GridIn
reads it ('Geometry/Mesh = file'), with boundary id 0 on every face.
"""
import math
import sys

r_in, r_out, height, h = map(float, sys.argv[1:5])
path = sys.argv[5]
n = int(round(2 * r_out / h))
nz = int(round(height / h))
vertex_ids = {}
vertices = []
cells = []


def vertex(i, j, k):
    key = (i, j, k)
    if key not in vertex_ids:
        vertex_ids[key] = len(vertices) + 1
        vertices.append((-r_out + i * h, -r_out + j * h, k * h))
    return vertex_ids[key]


for k in range(nz):
    for j in range(n):
        for i in range(n):
            x = -r_out + (i + 0.5) * h
            y = -r_out + (j + 0.5) * h
            r = math.hypot(x, y)
            if r < r_in or r > r_out:
                continue
            # UCD hexahedron: the bottom face counterclockwise, then the top.
            cells.append([vertex(i, j, k), vertex(i + 1, j, k),
                          vertex(i + 1, j + 1, k), vertex(i, j + 1, k),
                          vertex(i, j, k + 1), vertex(i + 1, j, k + 1),
                          vertex(i + 1, j + 1, k + 1), vertex(i, j + 1, k + 1)])
with open(path, "w") as f:
    f.write(f"{len(vertices)} {len(cells)} 0 0 0\n")
    for v, (x, y, z) in enumerate(vertices, 1):
        f.write(f"{v} {x:.17g} {y:.17g} {z:.17g}\n")
    for c, ids in enumerate(cells, 1):
        f.write(f"{c} 0 hex " + " ".join(map(str, ids)) + "\n")
print(f"{len(cells)} cells, {len(vertices)} vertices -> {path}")
