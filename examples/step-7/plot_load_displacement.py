"""Plot step-7's load-displacement curve: the reaction of the top grip
against the grip opening (2 x 2e-5 m x t), with broken bonds on a second
axis and the LEFM load as a line.

    python3 plot_load_displacement.py output/load_displacement.csv [LEFM]
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
opening = [2 * 2e-5 * float(r["time"]) * 1e6 for r in rows]  # micrometres
reaction = [float(r["reaction_y"]) / 1e3 for r in rows]  # kN per m
broken = [int(r["broken_bonds"]) for r in rows]

fig, ax = plt.subplots(figsize=(6, 4.2))
ax.plot([0] + opening, [0] + reaction, "o-", ms=3, label="reaction, top grip")
if len(sys.argv) > 2:
    ax.axhline(float(sys.argv[2]) / 1e3, color="grey", ls="--",
               label="LEFM initiation load")
ax.set_xlabel("grip opening [µm]")
ax.set_ylabel("reaction [kN per m of thickness]")
ax2 = ax.twinx()
ax2.plot(opening, broken, "s:", ms=2, color="tab:red", label="broken bonds")
ax2.set_ylabel("broken bonds", color="tab:red")
ax.legend(loc="upper left", fontsize=8)
ax.set_title("step-7: notched glass plate to failure")
fig.tight_layout()
fig.savefig(sys.argv[1].rsplit("/", 1)[0] + "/load_displacement.png", dpi=150)
