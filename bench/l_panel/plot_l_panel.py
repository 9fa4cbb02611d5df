"""Plots of bench/l_panel/run_l_panel.sh: the load against the load-point
displacement for every grid (the experiment's peak, 7.22 kN, as a line),
and the crack paths in the panel."""
import csv
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
out = sys.argv[2]

fig, ax = plt.subplots(figsize=(6, 4.5))
for r in rows:
    name = f"l_panel_{r['cells']}"
    prm = open(f"{out}/logs/{name}.prm").read()
    rate = float(re.search(r"([0-9.eE+-]+)\*t", prm).group(1))
    data = list(csv.DictReader(open(f"{out}/logs/{name}/load_displacement.csv")))
    ax.plot([1e3 * rate * float(d["time"]) for d in data],
            [abs(float(d["reaction_y"])) * 0.1e-3 for d in data], "-",
            label=f"PD, h = {1e3 * float(r['h']):.3g} mm")
ax.axhline(7.22, color="grey", ls=":", lw=1,
           label="experiment's peak (Winkler 2001)")
ax.set_xlabel("load-point displacement [mm]")
ax.set_ylabel("load [kN] (100 mm thick)")
ax.set_title("L-shaped panel, brittle bonds")
ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(f"{out}/load_displacement.png", dpi=150)

fig, ax = plt.subplots(figsize=(5, 5))
outline_x = [0, 0.25, 0.25, 0.5, 0.5, 0, 0]
outline_y = [0, 0, 0.25, 0.25, 0.5, 0.5, 0]
ax.plot(outline_x, outline_y, "k-", lw=0.8)
for r in rows:
    path = list(csv.DictReader(open(f"{out}/crack_path_{r['cells']}.csv")))
    ax.plot([float(p["x"]) for p in path], [float(p["y"]) for p in path],
            "-", label=f"h = {1e3 * float(r['h']):.3g} mm")
ax.set_aspect("equal")
ax.set_xlabel("x [m]")
ax.set_ylabel("y [m]")
ax.set_title("Crack paths (largest damage per column)")
ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(f"{out}/crack_path.png", dpi=150)
