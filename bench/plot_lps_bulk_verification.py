#!/usr/bin/python3
"""Plots of the LPS bulk-node verification (Figs. 11-13 of Scabbia,
Zaccariotto, Galvanetto 2022), from the CSV file written by
perideal-lps-bulk-verification.

  /usr/bin/python3 bench/plot_lps_bulk_verification.py [--input-dir DIR]
      [--output-dir DIR]

reads DIR/lps_bulk_verification.csv (default DIR:
results/lps_bulk_verification) and writes
  fig11_lps.png  relative errors of the neighbourhood volume and of the
                 weighted volume (Fig. 11 b, d)
  fig12.png      relative errors of C1111 and C1122 (Fig. 12 b, d)
  fig13.png      relative errors of the force density b1, b2, b3 (Fig. 13)
against the m-ratio, log y, one curve per algorithm, next to the CSV file or
into --output-dir.

Values that are exactly 0 (the exact neighbourhood volume at many m) cannot
be shown on a log axis: they are drawn at FLOOR and counted in the title.
Non-finite values are left out and counted in the title.
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

# Colours as in bench/plot_partial_volumes.py.
STYLE = {
    "approximate": ("tab:red", "approximate (Algorithm 1)"),
    "quasi-analytical": ("tab:blue", "quasi-analytical N=4 (Algorithm 4)"),
    "exact": ("black", "exact"),
}


def read_groups(path):
    """{algorithm: ([m], {column: [value]})} in file order."""
    groups = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            m, columns = groups.setdefault(row["algorithm"], ([], {}))
            m.append(float(row["m"]))
            for key, value in row.items():
                if key.startswith("err_"):
                    columns.setdefault(key, []).append(float(value))
    return groups


def panel(ax, groups, column, ylabel, title):
    notes = []
    for algorithm, (m, columns) in groups.items():
        colour, text = STYLE.get(algorithm, ("gray", algorithm))
        shown, zeros, bad = [], 0, 0
        for v in columns[column]:
            if not math.isfinite(v):
                bad += 1
                shown.append(float("nan"))
            elif v == 0:
                zeros += 1
                shown.append(FLOOR)
            else:
                shown.append(v)
        if zeros:
            notes.append("%s: %d values exactly 0, drawn at %g"
                         % (algorithm, zeros, FLOOR))
        if bad:
            notes.append("%s: %d non-finite values not drawn"
                         % (algorithm, bad))
        ax.plot(m, shown, color=colour, linewidth=1, label=text)
    ax.set_yscale("log")
    ax.set_xlabel(r"$\bar m$")
    ax.set_ylabel(ylabel)
    ax.set_title("\n".join([title] + notes), fontsize=9)
    ax.grid(True, which="major", alpha=0.3)


def figure(groups, panels, suptitle, png_path, ncols):
    nrows = (len(panels) + ncols - 1) // ncols
    fig, axes = plt.subplots(nrows, ncols, figsize=(6 * ncols, 4.6 * nrows),
                             squeeze=False)
    for ax, (column, ylabel, title) in zip(axes.flat, panels):
        panel(ax, groups, column, ylabel, title)
    for ax in list(axes.flat)[len(panels):]:
        ax.set_visible(False)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=9)
    fig.suptitle(suptitle, fontsize=11)
    fig.tight_layout(rect=(0, 0.06 if nrows == 1 else 0.04, 1, 1))
    fig.savefig(png_path, dpi=120)
    plt.close(fig)
    print("wrote", png_path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--input-dir", default="results/lps_bulk_verification")
    ap.add_argument("--output-dir", default=None,
                    help="where the PNGs go (default: the input directory)")
    args = ap.parse_args()
    csv_path = os.path.join(args.input_dir, "lps_bulk_verification.csv")
    if not os.path.isfile(csv_path):
        print("plot_lps_bulk_verification.py: error: missing input "
              + csv_path, file=sys.stderr)
        return 1
    groups = read_groups(csv_path)
    out = args.output_dir or args.input_dir
    os.makedirs(out, exist_ok=True)
    setting = (r"LPS, Gaussian influence, $E$ = 1 GPa, $\nu$ = 0.2, "
               r"bulk node of a uniform grid")

    figure(groups,
           [("err_volume", r"$\epsilon_V$ (Eq. 34)",
             "(b) Relative error of the neighbourhood volume"),
            ("err_weighted_volume", r"$\epsilon_m$ (Eq. 37)",
             "(d) Relative error of the weighted volume")],
           "Geometrical quantities (Fig. 11 b, d), " + setting,
           os.path.join(out, "fig11_lps.png"), 2)
    figure(groups,
           [("err_C1111", r"$\epsilon_{1111}$ (Eq. 44)",
             r"(b) Relative error of $C_{1111}$ vs. $K + 4\mu/3$"),
            ("err_C1122", r"$\epsilon_{1122}$ (Eq. 44)",
             r"(d) Relative error of $C_{1122}$ vs. $K - 2\mu/3$")],
           "Elasticity coefficients (Fig. 12 b, d), " + setting,
           os.path.join(out, "fig12.png"), 2)
    figure(groups,
           [("err_b%d" % p, r"$\epsilon_{b_%d}$ (Eq. 47)" % p,
             "(%s) Relative error of $b_%d$"
             % ("abc"[p - 1], p)) for p in (1, 2, 3)],
           "Force density of the quadratic manufactured field (Fig. 13), "
           + setting,
           os.path.join(out, "fig13.png"), 3)
    return 0


if __name__ == "__main__":
    sys.exit(main())
