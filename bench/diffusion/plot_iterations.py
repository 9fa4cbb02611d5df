#!/usr/bin/python3
"""Plots of bench/diffusion/run_iterations.sh.

Usage: plot_iterations.py RESULTS_DIR

Reads RESULTS_DIR/iterations.csv; writes
  iterations_h.png     mean CG iterations per solve against 1/h (m = 3),
  iterations_m.png     mean CG iterations per solve against m (h = 1/64),
  iterations_time.png  seconds in the solves (set-up of the preconditioner
                       included) against the number of nodes (m = 3).
Solid: steady state; dashed: backward Euler, dt = 0.1.
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


def series(rows, study, stepping, pre, x, y):
    pts = sorted((float(r[x]), float(r[y])) for r in rows
                 if r["study"] == study and r["stepping"] == stepping
                 and r["preconditioner"] == pre)
    return [p[0] for p in pts], [p[1] for p in pts]


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    rows = read_csv(os.path.join(out, "iterations.csv"))
    for r in rows:
        r["inverse_h"] = str(1 / float(r["h"]))
    styles = {"steady state": "-", "backward Euler": "--"}
    markers = {"jacobi": "o", "local laplacian": "s"}

    def plot(study, x, y, xlabel, ylabel, title, path, loglog):
        fig, ax = plt.subplots(figsize=(6.5, 4.5))
        for stepping, style in styles.items():
            for pre, marker in markers.items():
                xs, ys = series(rows, study, stepping, pre, x, y)
                if not xs:
                    continue
                draw = ax.loglog if loglog else ax.semilogy
                draw(xs, ys, style, marker=marker,
                     label="%s, %s" % (stepping, pre))
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(out, path), dpi=150)

    plot("h", "inverse_h", "mean_iterations", "1/h", "CG iterations per solve",
         "Iterations against 1/h, m = 3 (tolerance 1e-10)",
         "iterations_h.png", True)
    plot("m", "m", "mean_iterations", "m = delta/h", "CG iterations per solve",
         "Iterations against m, h = 1/64", "iterations_m.png", False)
    plot("h", "nodes", "solve_seconds", "nodes",
         "seconds in the solves (set-up included)",
         "Solve time against nodes, m = 3", "iterations_time.png", True)


if __name__ == "__main__":
    main()
