#!/usr/bin/env python3
"""Plots of bench/diffusion/run_corrosion_hybrid.sh (study 6 of issue 23).

Usage: plot_corrosion_hybrid.py RESULTS_DIR

Reads corrosion_hybrid.csv and the histories corrosion_hybrid_<case>_r<k>.csv
and writes corrosion_hybrid_history.png (pit depth and the fraction of
standard nodes against time) and corrosion_hybrid_speed.png (wall time
against the final pit-volume difference to the standard run on the same
grid, and wall time against the number of nodes).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main():
    out = sys.argv[1]
    summary = read(os.path.join(out, "corrosion_hybrid.csv"))
    styles = {"standard": "k-", "hybrid_adaptive": "r--", "hybrid_fixed": "b:",
              "hybrid_adaptive_paper_row": "g-."}

    fig, (depth_ax, fraction_ax) = plt.subplots(1, 2, figsize=(11, 4.2))
    for row in summary:
        name, r = row["case"], row["refinement"]
        history = read(os.path.join(out, f"corrosion_hybrid_{name}_r{r}.csv"))
        t = [float(h["time"]) for h in history]
        depth_ax.plot(t, [1e6 * float(h["pit_depth"]) for h in history],
                      styles[name], alpha=1.0 if r == "1" else 0.55,
                      label=f"{name}, h = {1 / float(r):g} um")
        nodes = float(row["n_nodes"])
        fraction = [float(h["standard_nodes"]) / nodes if "standard_nodes" in h
                    else 1.0 for h in history]
        fraction_ax.plot(t, fraction, styles[name],
                         alpha=1.0 if r == "1" else 0.55,
                         label=f"{name}, h = {1 / float(r):g} um")
    depth_ax.set_xlabel("t (s)")
    depth_ax.set_ylabel("pit depth (um)")
    depth_ax.legend(fontsize=7)
    depth_ax.set_title("pit depth")
    fraction_ax.set_xlabel("t (s)")
    fraction_ax.set_ylabel("standard nodes / nodes")
    fraction_ax.set_title("fraction of standard nodes")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "corrosion_hybrid_history.png"), dpi=120)

    fig, (error_ax, size_ax) = plt.subplots(1, 2, figsize=(11, 4.2))
    for row in summary:
        name = row["case"]
        wall = float(row["wall_seconds"])
        error_ax.plot([wall], [100 * abs(float(row["final_volume_difference"]))],
                      styles[name][0] + "o")
        error_ax.annotate(f"{name} r{row['refinement']}", (wall,
                          100 * abs(float(row["final_volume_difference"]))),
                          fontsize=7)
    error_ax.set_xlabel("wall time (s)")
    error_ax.set_ylabel("|pit volume - standard| / standard (%)")
    error_ax.set_title("difference to all-standard against time")
    for name in styles:
        rows = [r for r in summary if r["case"] == name]
        size_ax.loglog([float(r["n_nodes"]) for r in rows],
                       [float(r["wall_seconds"]) for r in rows],
                       styles[name] + "o", label=name)
    size_ax.set_xlabel("nodes")
    size_ax.set_ylabel("wall time (s)")
    size_ax.set_title("time against size")
    size_ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "corrosion_hybrid_speed.png"), dpi=120)


if __name__ == "__main__":
    main()
