#!/usr/bin/env python3
"""Plots of Example 1 of the hybrid-collocation paper (Fig. 9), from the CSV
files of perideal-collocation-example1 (bench/run_collocation_example1.sh):

  example1_fig9.png           left: relative l2 error (Eq. 66) against
                              m = delta / h at delta = 6 (PD body force,
                              Eq. 69); right: against delta at m = 12
                              (local body force, Eq. 71); log axes, the
                              paper's four schemes (standard, Proposed-A/B/C)
                              and, dashed grey, the full-volume standard
                              scheme (standard-FV) as a reference
  example1_error_vs_time.png  error against the wall time of a run (row,
                              assembly and banded LU solve), both studies

Usage: plot_collocation_example1.py [--input-dir DIR] [--output-dir DIR]
(defaults: the current directory for both; the output directory defaults to
the input directory when only that is given).
"""
import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCHEMES = ["standard", "Proposed-A", "Proposed-B", "Proposed-C", "standard-FV"]
STYLE = {
    "standard": dict(color="k", marker="s", linestyle="-"),
    "Proposed-A": dict(color="tab:blue", marker="o", linestyle="-"),
    "Proposed-B": dict(color="tab:orange", marker="^", linestyle="-"),
    "Proposed-C": dict(color="tab:green", marker="D", linestyle="-"),
    "standard-FV": dict(color="0.6", marker="x", linestyle="--"),
}
# Round-off errors of 0 would vanish from a log plot.
FLOOR = 1e-17


def read(path):
    series = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            series.setdefault(row["scheme"], []).append(row)
    return series


def label(scheme):
    return scheme + (" (full volumes, reference)" if scheme == "standard-FV" else "")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--input-dir", default=".")
    parser.add_argument("--output-dir", default=None)
    args = parser.parse_args()
    out = args.output_dir or args.input_dir
    os.makedirs(out, exist_ok=True)
    m_study = read(os.path.join(args.input_dir, "example1_m_convergence.csv"))
    d_study = read(os.path.join(args.input_dir, "example1_delta_convergence.csv"))

    fig, (left, right) = plt.subplots(1, 2, figsize=(11.0, 5.0))
    for scheme in SCHEMES:
        rows = m_study.get(scheme, [])
        if rows:
            left.loglog(
                [float(r["m"]) for r in rows],
                [max(float(r["error"]), FLOOR) for r in rows],
                markersize=4,
                label=label(scheme),
                **STYLE[scheme],
            )
        rows = d_study.get(scheme, [])
        if rows:
            right.loglog(
                [float(r["delta"]) for r in rows],
                [max(float(r["error"]), FLOOR) for r in rows],
                markersize=4,
                label=label(scheme),
                **STYLE[scheme],
            )
    left.set_xlabel(r"$m = \delta / \Delta x$")
    left.set_title(r"m-convergence, $\delta = 6$ (PD force, Eq. 69)")
    right.set_xlabel(r"horizon $\delta$")
    right.set_title(r"$\delta$-convergence, $m = 12$ (local force, Eq. 71)")
    for ax in (left, right):
        ax.set_ylabel(r"relative $l_2$ error (Eq. 66)")
        ax.grid(True, which="both", alpha=0.3)
    handles, labels = left.get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=5, fontsize=8)
    fig.suptitle("Example 1: 1D bond-based PD, u = sin(x/10), Omega = (-100, 100)")
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    fig.savefig(os.path.join(out, "example1_fig9.png"), dpi=150)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(7.5, 6.0))
    for study, series, marker_fill in [
        (r"m-study ($\delta$ = 6)", m_study, "full"),
        (r"$\delta$-study (m = 12)", d_study, "none"),
    ]:
        for scheme in SCHEMES:
            rows = series.get(scheme, [])
            if not rows:
                continue
            style = dict(STYLE[scheme])
            style["linestyle"] = "none"
            ax.loglog(
                [float(r["wall_time_s"]) for r in rows],
                [max(float(r["error"]), FLOOR) for r in rows],
                markersize=5,
                fillstyle=marker_fill,
                label=f"{study}, {scheme}",
                **style,
            )
    ax.set_xlabel("wall time of a run (row, assembly, banded LU) [s]")
    ax.set_ylabel(r"relative $l_2$ error (Eq. 66)")
    ax.set_title("Example 1: error against cost")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6, ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.12))
    fig.tight_layout()
    fig.savefig(os.path.join(out, "example1_error_vs_time.png"), dpi=150)
    plt.close(fig)
    print(
        f"wrote {out}/example1_fig9.png and {out}/example1_error_vs_time.png"
    )


if __name__ == "__main__":
    main()
