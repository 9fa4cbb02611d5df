#!/usr/bin/env python3
"""Plot of bench/dynamics/run_setup_scaling.sh: each set-up phase and the
whole set-up against the number of nodes (left), and the set-up in units of
one step, against the target of 15 steps (right).

Usage: plot_setup_scaling.py CSV PNG"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
models = sorted({r["model"] for r in rows})
phases = [("mesh_s", "mesh"), ("nodes_s", "nodes and ghost exchange"),
          ("neighbours_s", "neighbour search and weights"),
          ("operator_s", "operator setup"), ("setup_s", "whole set-up")]

fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
for model, line in zip(models, ["-", "--"]):
    sel = sorted((r for r in rows if r["model"] == model),
                 key=lambda r: int(r["nodes"]))
    n = [int(r["nodes"]) for r in sel]
    for (key, label), color in zip(phases, "bgrmk"):
        axes[0].loglog(n, [max(float(r[key]), 1e-3) for r in sel], line,
                       color=color, marker="o", label=f"{model}: {label}")
    axes[1].semilogx(n, [float(r["setup_s"]) / float(r["seconds_per_step"])
                         for r in sel], line, color="k", marker="o",
                     label=f"{model}")
axes[0].axhline(180, color="gray", ls=":", label="3 minutes")
axes[0].set_xlabel("nodes")
axes[0].set_ylabel("wall time [s]")
axes[0].legend(fontsize=6)
axes[0].set_title("set-up phases (1 process)")
axes[1].axhline(15, color="gray", ls=":", label="target: 15 steps")
axes[1].set_xlabel("nodes")
axes[1].set_ylabel("set-up / time of one step")
axes[1].legend(fontsize=8)
axes[1].set_title("set-up in steps")
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)
