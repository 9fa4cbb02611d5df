#!/usr/bin/python3
"""Plots of the partial-volume benchmark and of Figs. 10 and 11 of Scabbia,
Zaccariotto, Galvanetto (2022), from the CSV files written by
perideal-bench-partial-volumes and perideal-partial-volume-figures.

  /usr/bin/python3 bench/plot_partial_volumes.py [--benchmark-dir DIR]
      [--figures-dir DIR] [--output-dir DIR]

writes
  benchmark.png   max. abs. error of beta vs. time per partial cell (log-log)
  fig10.png       eps_V vs. m for quasi-analytical N = 2..20 and exact,
                  m step 0.5 as in the paper (fig10_fine.png: step 0.05)
  fig11.png       neighbourhood volume, normalised weighted volume and their
                  relative errors for approximate, quasi-analytical N = 4 and
                  N = 20, and exact (m step 0.05)
next to the CSV files they come from, or into --output-dir.

Values that are exactly 0 cannot be shown on a log axis: they are drawn at
FLOOR and marked as such. Non-finite values (inf, nan) are drawn at the top
of the axis with an 'x' and listed in the legend.
"""
import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FLOOR = 1e-17

# One colour and marker per variant, the same in every figure.
STYLE = {
    ("exact", ""): ("black", "o"),
    ("approximate", ""): ("tab:red", "s"),
    ("full", ""): ("tab:brown", "D"),
    ("quasi-analytical", "2"): ("tab:olive", "v"),
    ("quasi-analytical", "4"): ("tab:blue", "^"),
    ("quasi-analytical", "6"): ("tab:cyan", "<"),
    ("quasi-analytical", "8"): ("tab:green", ">"),
    ("quasi-analytical", "12"): ("tab:purple", "p"),
    ("quasi-analytical", "16"): ("tab:pink", "h"),
    ("quasi-analytical", "20"): ("tab:orange", "*"),
}


def label(algorithm, order):
    if algorithm == "quasi-analytical":
        return "quasi-analytical N=%s" % order
    return algorithm


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def group(rows):
    """{(algorithm, taylor_order): [row, ...]} in file order."""
    out = {}
    for r in rows:
        out.setdefault((r["algorithm"], r["taylor_order"]), []).append(r)
    return out


def floored(values):
    """Values for a log axis: 0 -> FLOOR; also the indices of zeros and of
    non-finite values."""
    shown, zeros, bad = [], [], []
    for i, v in enumerate(values):
        if not math.isfinite(v):
            bad.append(i)
            shown.append(float("nan"))
        elif v == 0:
            zeros.append(i)
            shown.append(FLOOR)
        else:
            shown.append(v)
    return shown, zeros, bad


def plot_benchmark(csv_path, png_path):
    rows = read_csv(csv_path)
    fig, ax = plt.subplots(figsize=(8, 6))
    columns = [("max_abs_error_vs_reference", "filled",
                "vs. mpmath reference (%s rows)" % rows[0]["n_reference_rows"]),
               ("max_abs_error_vs_exact_fine_grid", "none",
                "vs. exact kernel, all wedge cells, m step 0.05")]
    for column, fill, _ in columns:
        for r in rows:
            key = (r["algorithm"], r["taylor_order"])
            colour, marker = STYLE.get(key, ("gray", "o"))
            t = float(r["ns_per_partial_cell_in_table"])
            e = float(r[column])
            y = e if e > 0 else FLOOR
            if not math.isfinite(y):
                continue
            ax.plot([t], [y], marker=marker, markersize=10, linestyle="",
                    markerfacecolor=colour if fill == "filled" else "none",
                    markeredgecolor=colour)
            if fill == "filled":
                ax.annotate(label(*key), (t, y), textcoords="offset points",
                            xytext=(8, 4), fontsize=8)
            if e == 0:
                ax.annotate("exactly 0 (drawn at %g)" % FLOOR, (t, y),
                            textcoords="offset points", xytext=(8, -10),
                            fontsize=7, color="gray")
    for column, fill, text in columns:
        ax.plot([], [], marker="o", linestyle="", color="gray",
                markerfacecolor="gray" if fill == "filled" else "none",
                label="max |beta - beta_ref| " + text)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per partial cell [ns] (building the uniform-grid tables, m = 1..10)")
    ax.set_ylabel("max. absolute error of beta")
    ax.set_title("3D partial-volume algorithms: accuracy vs. cost")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(loc="lower left", fontsize=8)
    fig.tight_layout()
    fig.savefig(png_path, dpi=120)
    plt.close(fig)


def plot_fig10(csv_path, png_path, step):
    data = group(read_csv(csv_path))
    fig, ax = plt.subplots(figsize=(10.5, 5.5))
    for key, rows in data.items():
        colour, marker = STYLE.get(key, ("gray", "o"))
        m = [float(r["m"]) for r in rows]
        e, zeros, bad = floored([float(r["rel_error_volume"]) for r in rows])
        text = label(*key)
        if zeros:
            text += " (%d values exactly 0, at %g)" % (len(zeros), FLOOR)
        if bad:
            text += " (non-finite at m = %s)" % ", ".join(
                "%g" % m[i] for i in bad)
        ax.plot(m, e, color=colour, marker=marker if step >= 0.5 else None,
                markersize=5, linewidth=1.0 if step >= 0.5 else 0.8,
                label=text)
    ax.set_yscale("log")
    ax.set_xlabel(r"$\bar m$")
    ax.set_ylabel(r"$\epsilon_V$ (Eq. 34)")
    ax.set_title(r"Relative error of the neighbourhood volume "
                 r"($\Delta\bar m$ = %g)" % step)
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1))
    fig.tight_layout()
    fig.savefig(png_path, dpi=120)
    plt.close(fig)


def plot_fig11(csv_path, png_path):
    data = group(read_csv(csv_path))
    fig, axes = plt.subplots(2, 2, figsize=(12, 9.5))
    panels = [
        (axes[0, 0], "volume", False, r"$V_\mathcal{H}$ (Eq. 35)",
         "(a) Neighbourhood volume"),
        (axes[0, 1], "rel_error_volume", True, r"$\epsilon_V$ (Eq. 34)",
         "(b) Relative error of the neighbourhood volume"),
        (axes[1, 0], "normalised_weighted_volume", False,
         r"$m/m_{an}$ (Eq. 36)", "(c) Normalised weighted volume"),
        (axes[1, 1], "rel_error_weighted_volume", True,
         r"$\epsilon_m$ (Eq. 37)",
         "(d) Relative error of the weighted volume"),
    ]
    for ax, column, log, ylabel, title in panels:
        if column == "volume":
            ms = sorted({float(r["m"]) for rows in data.values()
                         for r in rows})
            ax.plot(ms, [4 / 3 * math.pi * m ** 3 for m in ms], color="gray",
                    linestyle="--", linewidth=1)
        if column == "normalised_weighted_volume":
            ax.axhline(1, color="gray", linestyle="--", linewidth=1)
        notes = []
        for key, rows in data.items():
            colour, marker = STYLE.get(key, ("gray", "o"))
            m = [float(r["m"]) for r in rows]
            values = [float(r[column]) for r in rows]
            if log:
                values, zeros, bad = floored(values)
                if zeros:
                    notes.append("%s: %d values exactly 0, drawn at %g"
                                 % (label(*key), len(zeros), FLOOR))
                if bad:
                    notes.append("%s: %d non-finite values not drawn"
                                 % (label(*key), len(bad)))
            ax.plot(m, values, color=colour, linewidth=1, label=label(*key))
        if log:
            ax.set_yscale("log")
        ax.set_xlabel(r"$\bar m$")
        ax.set_ylabel(ylabel)
        ax.set_title("\n".join([title] + notes), fontsize=9)
        ax.grid(True, which="major", alpha=0.3)
    handles, labels = axes[1, 0].get_legend_handles_labels()
    handles.append(plt.Line2D([], [], color="gray", linestyle="--"))
    labels.append("analytical value")
    fig.legend(handles, labels, loc="lower center", ncol=5, fontsize=9)
    fig.suptitle(r"Geometrical quantities, Gaussian influence function "
                 r"$\omega = \exp(-|\xi|^2/\delta^2)$, "
                 r"$\Delta\bar m$ = 0.05")
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.savefig(png_path, dpi=120)
    plt.close(fig)


def plot_time_vs_m(csv_path, png_path):
    data = group(read_csv(csv_path))
    fig, ax = plt.subplots(figsize=(7.5, 5.5))
    for key, rows in data.items():
        colour, marker = STYLE.get(key, ("gray", "o"))
        m = [float(r["m"]) for r in rows]
        t = [float(r["microseconds_per_table"]) for r in rows]
        ax.plot(m, t, color=colour, marker=marker, label=label(*key))
    rows = list(data.values())[0]
    m = [float(r["m"]) for r in rows]
    n = [float(r["n_partial_cells"]) for r in rows]
    scale = [float(r["microseconds_per_table"]) for r in rows][-1] / n[-1]
    ax.plot(m, [scale * x for x in n], "k:", linewidth=0.8,
            label="proportional to the number of partial cells")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(r"m-ratio $\bar m$")
    ax.set_ylabel("time to build one wedge table [µs]")
    ax.set_title("Cost of the uniform-grid coefficients against size")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png_path, dpi=120)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--benchmark-dir", default="results/partial_volumes")
    ap.add_argument("--figures-dir", default="results/partial_volume_figures")
    ap.add_argument("--output-dir", default=None,
                    help="where the PNGs go (default: next to their CSVs)")
    args = ap.parse_args()

    jobs = [
        (args.benchmark_dir, "partial_volumes.csv", "benchmark.png",
         plot_benchmark),
        (args.benchmark_dir, "table_time_vs_m.csv", "time_vs_m.png",
         plot_time_vs_m),
        (args.figures_dir, "fig10.csv", "fig10.png",
         lambda c, p: plot_fig10(c, p, 0.5)),
        (args.figures_dir, "fig10_fine.csv", "fig10_fine.png",
         lambda c, p: plot_fig10(c, p, 0.05)),
        (args.figures_dir, "fig11.csv", "fig11.png", plot_fig11),
    ]
    missing = []
    for directory, csv_name, png_name, plot in jobs:
        csv_path = os.path.join(directory, csv_name)
        if not os.path.isfile(csv_path):
            missing.append(csv_path)
            continue
        out_dir = args.output_dir or directory
        os.makedirs(out_dir, exist_ok=True)
        png_path = os.path.join(out_dir, png_name)
        plot(csv_path, png_path)
        print("wrote", png_path)
    if missing:
        print("plot_partial_volumes.py: error: missing input " +
              ", ".join(missing), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
