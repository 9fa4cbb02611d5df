#!/usr/bin/env python3
"""Writes the mesh files of the driver tests in UCD (.inp) format:

l_shape.inp      an L-shaped 2D body of equal square cells (h = 0.1): the
                 square [0,2]^2 without [1,2]^2. Boundary lines carry id 0.
skewed_quad.inp  a 2 x 2 mesh whose centre vertex is moved: not Cartesian,
                 for the bad-input test.

Run: python3 tests/driver/make_meshes.py (from the repository root).
"""
import os

here = os.path.dirname(os.path.abspath(__file__))


def write_ucd(path, vertices, cells):
    with open(path, "w") as f:
        f.write("# written by tests/driver/make_meshes.py\n")
        f.write(f"{len(vertices)} {len(cells)} 0 0 0\n")
        for i, (x, y) in enumerate(vertices):
            f.write(f"{i + 1} {x:.17g} {y:.17g} 0\n")
        for i, c in enumerate(cells):
            f.write(f"{i + 1} 0 quad {' '.join(str(v + 1) for v in c)}\n")


def l_shape(n=10):
    h = 1.0 / n
    index = {}
    vertices = []

    def vertex(i, j):
        if (i, j) not in index:
            index[(i, j)] = len(vertices)
            vertices.append((i * h, j * h))
        return index[(i, j)]

    cells = []
    for j in range(2 * n):
        for i in range(2 * n):
            if i >= n and j >= n:
                continue
            cells.append((vertex(i, j), vertex(i + 1, j),
                          vertex(i + 1, j + 1), vertex(i, j + 1)))
    return vertices, cells


def skewed():
    vertices = [(x, y) for y in (0, 1, 2) for x in (0, 1, 2)]
    vertices[4] = (1.2, 0.9)
    cells = [(0, 1, 4, 3), (1, 2, 5, 4), (3, 4, 7, 6), (4, 5, 8, 7)]
    return vertices, cells


write_ucd(os.path.join(here, "l_shape.inp"), *l_shape())
write_ucd(os.path.join(here, "skewed_quad.inp"), *skewed())
