#!/usr/bin/env python3
"""Plots of the whole-body manufactured-solution study
(bench/run_manufactured_convergence.sh):

  error_vs_time.png  relative L2 error against wall time, one line per study
  error_vs_h.png     relative L2 error against the grid spacing h

Usage: plot_manufactured_convergence.py SUMMARY.csv OUTPUT_DIR
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    summary, out = sys.argv[1], sys.argv[2]
    studies = {}
    with open(summary) as f:
        for row in csv.DictReader(f):
            if row["field"] != "quadratic":
                continue
            studies.setdefault(row["study"], []).append(row)

    labels = {
        "fixed_m_2d": "2D, fixed m",
        "fixed_delta_2d": "2D, fixed horizon",
        "fixed_m_3d": "3D, fixed m",
        "fixed_delta_3d": "3D, fixed horizon",
    }
    for x_key, x_label, name in [
        ("time_total", "wall time of the run [s]", "error_vs_time.png"),
        ("h", "grid spacing h", "error_vs_h.png"),
    ]:
        fig, ax = plt.subplots(figsize=(6.4, 4.6))
        for study, rows in sorted(studies.items()):
            x = [float(r[x_key]) for r in rows]
            y = [float(r["l2_error"]) for r in rows]
            ax.loglog(x, y, "o-", label=labels.get(study, study))
            for r, xi, yi in zip(rows, x, y):
                ax.annotate(f"m={float(r['m_ratio']):.3g}", (xi, yi),
                            textcoords="offset points", xytext=(3, 3),
                            fontsize=6)
        ax.set_xlabel(x_label)
        ax.set_ylabel("relative L2 error of u")
        ax.set_title("LPS, quadratic manufactured field, exact weights")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(f"{out}/{name}", dpi=150)
        print(f"wrote {out}/{name}")


if __name__ == "__main__":
    main()
