#!/usr/bin/env python3
"""Plots of the collocation-against-standard study
(bench/run_collocation_convergence.sh):

  error_vs_h.png     relative L2 error against the grid spacing h, one line
                     per study, field and scheme
  error_vs_time.png  relative L2 error against the wall time of the run

Usage: plot_collocation_convergence.py CSV OUTPUT_DIR
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    path, out = sys.argv[1], sys.argv[2]
    series = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            key = (row["study"], row["field"], row["scheme"])
            series.setdefault(key, []).append(row)

    for x_key, x_label, name in [
        ("h", "grid spacing h", "error_vs_h.png"),
        ("time_total", "wall time of the run [s]", "error_vs_time.png"),
    ]:
        fig, ax = plt.subplots(figsize=(7.0, 5.0))
        for (study, field, scheme), rows in sorted(series.items()):
            x = [float(r[x_key]) for r in rows]
            # Round-off errors of 0 would vanish from a log plot.
            y = [max(float(r["l2_error"]), 1e-17) for r in rows]
            style = {"collocation": "o-", "collocation_s": "^-"}.get(scheme, "s--")
            ax.loglog(x, y, style, label=f"{study}, {field}, {scheme}")
        ax.set_xlabel(x_label)
        ax.set_ylabel("relative L2 error of u")
        ax.set_title("bond-based, exact weights against collocation C2")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6)
        fig.tight_layout()
        fig.savefig(f"{out}/{name}", dpi=150)
        plt.close(fig)
    print(f"wrote {out}/error_vs_h.png and {out}/error_vs_time.png")


if __name__ == "__main__":
    main()
