#!/usr/bin/python3
"""Plots of bench/diffusion/run_manufactured.sh (the paper's Example 2).

Usage: plot_manufactured.py RESULTS_DIR

Reads RESULTS_DIR/manufactured.csv and the histories
manufactured_<case>.csv; writes
  manufactured_error_time.png  relative l2 error and largest nodal error
                               against time, per scheme (dx = 1/39; the
                               grid study's runs dashed),
  manufactured_error_wall.png  final relative l2 error and the largest
                               nodal error over time against the wall
                               time of the run (the largest relative
                               error is that at the zero of C, t = pi/5),
  manufactured_error_dx.png    relative error at the end of the grid study
                               (forward Euler, t = end) against dx.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    runs = read_csv(os.path.join(out, "manufactured.csv"))
    grid = [r for r in runs if r["case"].startswith("dx")]
    schemes = [r for r in runs if not r["case"].startswith("dx")]

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    for r in schemes + grid:
        h = read_csv(os.path.join(out, "manufactured_%s.csv" % r["case"]))
        t = np.array([float(row["time"]) for row in h])
        keep = t > 0
        label = "%s, dt = %s, dx = 1/%.0f" % (
            r["scheme"], r["dt"], 1 / float(r["dx"]))
        for ax, column in zip(axes, ["relative_l2_error", "max_error"]):
            e = np.array([float(row[column]) for row in h])
            ax.semilogy(t[keep], e[keep], "--" if r in grid else "-",
                        marker="." if len(t) < 40 else None, label=label)
    for ax, ylabel in zip(axes, ["relative l2 error (free nodes, Eq. 66)",
                                 "largest nodal error |C_h - C|"]):
        ax.axvline(np.pi / 5, color="gray", lw=0.8, ls=":")
        ax.set_xlabel("t (dotted: C = 0 at t = pi/5)")
        ax.set_ylabel(ylabel)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_title("Example 2 (m = 4): relative l2 error against time")
    axes[1].set_title("largest nodal error against time")
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "manufactured_error_time.png"), dpi=150)

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    for r in schemes:
        w = float(r["wall_seconds"])
        label = "%s, dt = %s" % (r["scheme"], r["dt"])
        axes[0].loglog(w, float(r["final_error"]), "o", label=label)
        axes[1].loglog(w, float(r["max_nodal_error_over_time"]), "^",
                       label=label)
    end = schemes[0]["end_time"] if schemes else "?"
    axes[0].set_ylabel("relative l2 error at t = %s" % end)
    axes[1].set_ylabel("largest nodal error over 0 < t <= %s" % end)
    for ax in axes:
        ax.set_xlabel("wall time of the run [s]")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_title("Example 2, dx = 1/39, m = 4: error against wall time")
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "manufactured_error_wall.png"), dpi=150)

    if grid:
        fig, ax = plt.subplots(figsize=(6, 4.5))
        dx = np.array([float(r["dx"]) for r in grid])
        ef = np.array([float(r["final_error"]) for r in grid])
        em = np.array([float(r["max_error_over_time"]) for r in grid])
        ax.loglog(dx, ef, "o-", label="at t = %s" % grid[0]["end_time"])
        ax.loglog(dx, em, "^--", label="largest over time")
        ax.loglog(dx, ef[0] * (dx / dx[0]) ** 2, ":", color="gray",
                  label="slope 2")
        m = float(grid[0]["m"])
        ax.axhline(1 / (np.pi * m * m), color="k", lw=0.8, ls="-.",
                   label="1/(pi m^2): operator on quadratics, fixed m")
        ax.set_xlabel("dx (delta = 4 dx)")
        ax.set_ylabel("relative l2 error")
        ax.set_title("Example 2: forward Euler, dt = 1e-5, m = 4")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "manufactured_error_dx.png"), dpi=150)


if __name__ == "__main__":
    main()
