#!/usr/bin/env python3
"""Plot of the 3D LPS cost study (bench/run_lps_scaling.sh): wall time of
each phase, and peak memory, against the number of nodes, for 1 and 2 MPI
processes.

Usage: plot_lps_scaling.py SCALING.csv OUTPUT_DIR
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PHASES = [
    ("time_neighbors", "neighbour search + weights"),
    ("time_operator", "operator setup"),
    ("time_assembly", "assembly"),
    ("time_solve", "solve"),
    ("time_total", "total"),
]


def main():
    path, out = sys.argv[1], sys.argv[2]
    rows = list(csv.DictReader(open(path)))
    fig, (ax, ax_mem) = plt.subplots(1, 2, figsize=(11, 4.6))
    for ranks, style in [("1", "-"), ("2", "--")]:
        subset = [r for r in rows if r["n_ranks"] == ranks]
        if not subset:
            continue
        n = [int(r["n_nodes"]) for r in subset]
        for i, (key, label) in enumerate(PHASES):
            ax.loglog(n, [max(float(r[key]), 1e-4) for r in subset],
                      style, marker="o", color=f"C{i}",
                      label=f"{label}, {ranks} proc.")
        ax_mem.loglog(n, [float(r["peak_memory_mb"]) for r in subset], style,
                      marker="o", color="k",
                      label=f"peak memory, {ranks} proc. (sum)")
        ax_mem.loglog(n, [int(r["nnz"]) * 12 / 2**20 for r in subset], style,
                      marker="s", color="C5",
                      label=f"matrix values+indices (12 B/nnz), {ranks} proc.")
    n_all = sorted({int(r["n_nodes"]) for r in rows})
    if len(n_all) > 1:
        ref = [float(rows[0]["time_total"]) * x / n_all[0] for x in n_all]
        ax.loglog(n_all, ref, ":", color="gray", label="O(N)")
    ax.set_xlabel("number of PD nodes N")
    ax.set_ylabel("wall time [s]")
    ax.set_title("3D LPS, m = 3, exact weights, CG + Jacobi")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6, ncol=2)
    ax_mem.set_xlabel("number of PD nodes N")
    ax_mem.set_ylabel("MB")
    ax_mem.grid(True, which="both", alpha=0.3)
    ax_mem.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(f"{out}/time_vs_size.png", dpi=150)
    print(f"wrote {out}/time_vs_size.png")


if __name__ == "__main__":
    main()
