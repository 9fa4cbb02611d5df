"""Plots of bench/run_three_point_bending.sh: the load-displacement curves
(load point's reaction against its prescribed displacement, LEFM's peak
load as a line), the gap of the peak load to LEFM against wall time, and
wall time against the number of nodes, per solver."""
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
    m = r.get("m", "3")
    name = f"{r['model']}_{r['solver']}_{r['cells']}" + ("" if m == "3" else f"_m{m}")
    prm = open(f"{out}/logs/{name}.prm").read()
    rate = float(re.search(r"-([0-9.eE+-]+)\*t", prm).group(1))
    data = list(csv.DictReader(open(f"{out}/logs/{name}/load_displacement.csv")))
    ax.plot([0] + [1e6 * rate * float(d["time"]) for d in data],
            [0] + [abs(float(d["reaction_y"])) for d in data],
            "-" if r["solver"] == "newton" else "--",
            label=f"{r['model']}, {r['solver']}, W/h = {r['cells']}, m = {m}")
ax.axhline(float(rows[0]["load_lefm"]), color="grey", ls=":", lw=1,
           label="LEFM peak load")
ax.set_xlabel("load-point displacement [µm]")
ax.set_ylabel("load per unit thickness [N/m]")
ax.set_title("Notched beam in three-point bending")
ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(f"{out}/load_displacement.png", dpi=150)

series = {}
for r in rows:
    series.setdefault((r["model"], r["solver"], r.get("m", "3")), []).append(r)
fig, ax = plt.subplots(figsize=(6, 4.5))
for (model, solver, m), rs in series.items():
    ax.plot([float(r["wall_seconds"]) for r in rs],
            [abs(float(r["gap_peak_percent"])) for r in rs], "o-",
            label=f"{model}, {solver}, m = {m}")
    for r in rs:
        ax.annotate(f"W/h = {r['cells']}", (float(r["wall_seconds"]),
                    abs(float(r["gap_peak_percent"]))), fontsize=7)
ax.axhline(5, color="grey", ls="--", lw=0.8)
ax.set_xscale("log")
ax.set_xlabel("wall time [s] (1 process)")
ax.set_ylabel("|peak load / LEFM - 1| [%]")
ax.set_title("Three-point bending: gap to LEFM")
ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(f"{out}/error_vs_time.png", dpi=150)

fig, ax = plt.subplots(figsize=(6, 4.5))
for (model, solver, m), rs in series.items():
    ax.loglog([int(r["nodes"]) for r in rs],
              [float(r["wall_seconds"]) for r in rs], "o-",
              label=f"{model}, {solver}, m = {m}")
ax.set_xlabel("nodes")
ax.set_ylabel("wall time [s]")
ax.set_title("Three-point bending: time against size")
ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(f"{out}/time_vs_size.png", dpi=150)
