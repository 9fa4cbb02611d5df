#!/usr/bin/env python3
"""The crack path of an L-panel run: for each node column of the vertical
arm's upper part (x < SIDE/2, y > SIDE/2 - h), the height of the node with
the largest damage, where that damage is at least 0.3 (a node one of whose
sides is cut loses about half of its bonds' volume; 0.3 keeps the crack and
leaves the scattered broken bonds around it out).

    crack_path.py RUN_DIR [SIDE]

Prints 'x,y' rows (m) of the last record of RUN_DIR/solution.pvd, from the
corner to the left edge as far as the crack goes.
"""
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                ".."))
from pd_vtu import read_pvtu  # noqa: E402

run = sys.argv[1]
side = float(sys.argv[2]) if len(sys.argv) > 2 else 0.5
root = ET.parse(os.path.join(run, "solution.pvd")).getroot()
last = root.find("Collection").findall("DataSet")[-1].get("file")
x, fields = read_pvtu(os.path.join(run, last))
damage = fields["damage"]
columns = np.unique(np.round(x[:, 0], 9))
h = columns[1] - columns[0]
print("x,y")
for cx in sorted(columns[columns < side / 2], reverse=True):
    sel = (np.abs(x[:, 0] - cx) < h / 4) & (x[:, 1] > side / 2 - h)
    if not np.any(sel):
        continue
    k = np.argmax(damage[sel])
    if damage[sel][k] < 0.3:
        break
    print(f"{cx:.6g},{x[sel][k, 1]:.6g}")
