#!/usr/bin/env python3
"""The energy, at the critical stretch, of the bonds that cross a straight
crack line on the 2D lattice, against the continuum value that gives s0
from G0 (bond-based PMB, constant micromodulus; doc/explicit-dynamics.md).

    /usr/bin/python3 bench/dynamics/crossing_bond_energy.py [M]

Cells of side 1, nodes at their centres, the crack on the line x = 0
between two node columns, horizon M (default 3). Per unit length of the
line, a bond's energy at s0 is proportional to |xi| times the partial
volume of the far node's cell inside the near node's horizon ("exact
partial volumes": the area of cell ∩ disc, here by a 400 x 400 midpoint
rule per cell, 1e-5 accurate). The continuum counterpart is the integral of
|xi| over the pairs that cross, delta^4 / 2. Prints both and their ratio
(1.028 at M = 3).
"""
import sys

import numpy as np

d = float(sys.argv[1]) if len(sys.argv) > 1 else 3.0
n = 400
g = (np.arange(n) + 0.5) / n - 0.5
X, Y = np.meshgrid(g, g)
k_max = int(np.ceil(d)) + 1
total = 0.0
# One node per unit length of the line: the row y = 0, columns x < 0; its
# partners are every node with x > 0.
for k in range(1, k_max + 1):
    xi = -(k - 0.5)
    for m in range(1, k_max + 1):
        for l in range(-k_max, k_max + 1):
            xj, yj = m - 0.5, float(l)
            inside = (((xj + X) - xi) ** 2 + (yj + Y) ** 2 <= d * d).mean()
            if inside > 0:
                total += np.hypot(xj - xi, yj) * inside
continuum = d ** 4 / 2
print(f"lattice {total:.6g}, continuum {continuum:.6g}, "
      f"ratio {total / continuum:.4f}")
