"""Plots of bench/run_centre_crack.sh: the gap to LEFM against wall time,
and wall time against the number of nodes, per model and solver; with a
tolerance study (centre_crack_tolerance.csv), the curve's difference from
the tightest Newton run against wall time, per solver."""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt



def finish(fig, ax, xlabel, ylabel, title, name):
    """Labels, the legend where there are series, and the PNG."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(f"{out}/{name}", dpi=150)


rows = list(csv.DictReader(open(sys.argv[1])))
out = sys.argv[2]
series = {}
for r in rows:
    # The a/W study (the tall plate) and the tolerance study are plotted
    # apart.
    if r["height_over_width"] != "1" or "_tol" in r["solver"]:
        continue
    # The refinement at m = 3, and the m study at fixed delta / a (its
    # m = 3 point is the 100^2 run of the refinement).
    series.setdefault((r["model"], r["solver"]), []).append(r)
    if r["solver"] == "newton" and (r["m"] != "3" or r["cells"] == "100"):
        series.setdefault((r["model"], "m study"), []).append(r)

fig, ax = plt.subplots(figsize=(6, 4.5))
for (model, solver), rs in series.items():
    if solver != "m study":
        rs = [r for r in rs if r["m"] == "3"]
    ax.plot([float(r["wall_seconds"]) for r in rs],
            [abs(float(r["gap_percent"])) for r in rs], "o-",
            label=f"{model}, {solver}")
    for r in rs:
        ax.annotate(r["cells"] + "², m = " + r["m"], (float(r["wall_seconds"]),
                    abs(float(r["gap_percent"]))), fontsize=7)
ax.axhline(5, color="grey", ls="--", lw=0.8)
ax.set_xscale("log")
finish(fig, ax, "wall time [s] (1 process)", "|initiation load / LEFM - 1| [%]",
       "Centre-cracked plate: gap to LEFM", "error_vs_time.png")

fig, ax = plt.subplots(figsize=(6, 4.5))
for (model, solver), rs in series.items():
    if solver == "m study":
        continue
    rs = [r for r in rs if r["m"] == "3"]
    ax.loglog([int(r["nodes"]) for r in rs],
              [float(r["wall_seconds"]) for r in rs], "o-",
              label=f"{model}, {solver}")
finish(fig, ax, "nodes", "wall time [s] to complete failure",
       "Centre-cracked plate: time against size", "time_vs_size.png")

tolerance_csv = f"{out}/centre_crack_tolerance.csv"
if os.path.exists(tolerance_csv):
    fig, ax = plt.subplots(figsize=(6, 4.5))
    rows = list(csv.DictReader(open(tolerance_csv)))
    for cells in sorted({r["cells"] for r in rows}, key=int):
        for solver in ("newton", "dynamic_relaxation"):
            rs = [r for r in rows if r["cells"] == cells and r["solver"] == solver
                  and r["same_bonds"] != "stopped"]
            # The curve's difference: the larger of the peak's and the
            # critical load's, floored for the log axis.
            diff = [max(1e-5, abs(float(r["peak_difference_percent"])),
                        abs(float(r["critical_difference_percent"] or 0)))
                    for r in rs]
            ax.plot([float(r["wall_seconds"]) for r in rs], diff, "o-",
                    label=f"{cells}², {solver}")
            for r, d in zip(rs, diff):
                ax.annotate(r["tolerance"], (float(r["wall_seconds"]), d), fontsize=7)
    ax.axhline(1, color="grey", ls="--", lw=0.8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    finish(fig, ax, "wall time [s] to complete failure (1 process)",
           "peak, critical load vs tightest Newton [%]",
           "Centre-cracked plate: solver tolerance, curve against time",
           "tolerance_vs_time.png")
