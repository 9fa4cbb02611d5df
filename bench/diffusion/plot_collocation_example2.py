#!/usr/bin/python3
"""Plots of bench/diffusion/run_collocation_example2.sh (the paper's
Example 2 with the collocation scheme).

Usage: plot_collocation_example2.py RESULTS_DIR

Reads RESULTS_DIR/collocation_example2.csv and the histories
collocation_example2_<case>.csv; writes
  collocation_example2_error_time.png  relative l2 error (Eq. 66) and the
                                       largest nodal error against time,
                                       per scheme, uniform nodes solid,
                                       perturbed dashed;
  collocation_example2_error_wall.png  the largest nodal error over the
                                       run against its wall time.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


COLOURS = {"standard": "tab:blue", "Proposed-A": "tab:orange",
           "Proposed-B": "tab:green"}


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    runs = read_csv(os.path.join(out, "collocation_example2.csv"))

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    for r in runs:
        hist = read_csv(os.path.join(out, "collocation_example2_%s.csv"
                                     % r["case"]))
        t = [float(h["time"]) for h in hist if float(h["time"]) > 0]
        rel = [float(h["relative_l2_error"]) for h in hist
               if float(h["time"]) > 0]
        nod = [float(h["max_error"]) for h in hist if float(h["time"]) > 0]
        style = "-" if r["nodes"] == "uniform" else "--"
        label = "%s, %s" % (r["scheme"], r["nodes"])
        colour = COLOURS.get(r["scheme"], "k")
        axes[0].semilogy(t, rel, style, color=colour, label=label)
        axes[1].semilogy(t, nod, style, color=colour, label=label)
    axes[0].set_ylabel("relative l2 error (Eq. 66)")
    axes[1].set_ylabel("largest nodal error |C_h - C|")
    for ax in axes:
        ax.set_xlabel("t")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("Example 2: dx = 1/39, delta = 4 dx, forward Euler, "
                 "dt = 1e-5")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "collocation_example2_error_time.png"),
                dpi=150)

    fig, ax = plt.subplots(figsize=(6, 4.5))
    for r in runs:
        marker = "o" if r["nodes"] == "uniform" else "s"
        ax.loglog(float(r["wall_seconds"]),
                  float(r["max_nodal_error_over_time"]), marker,
                  color=COLOURS.get(r["scheme"], "k"),
                  label="%s, %s" % (r["scheme"], r["nodes"]))
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("largest nodal error over the run")
    ax.set_title("Example 2: error against wall time")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "collocation_example2_error_wall.png"),
                dpi=150)


if __name__ == "__main__":
    main()
