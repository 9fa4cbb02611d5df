#!/usr/bin/python3
"""Plots of bench/diffusion/run_nonlocal_convergence.sh.

Usage: plot_nonlocal_convergence.py CSV OUTPUT_DIR

error_vs_spacing.png: left, m-convergence at fixed delta (relative l2 error
against the PD solution over dx = delta/m, the prediction of the discrete
symbol dashed); right, delta-convergence at fixed m (against the PD and
the classical solution, with |exp((K|k|^2 - lambda) T) - 1|, the distance
of the two solutions, dotted).
error_vs_wall_time.png: every run's error over its wall time.
Also prints the tables (observed orders between neighbouring rows).
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for key in ("m", "dim", "q", "nodes", "steps"):
            r[key] = int(r[key])
        for key in ("delta", "dx", "relative_l2_error", "max_error",
                    "predicted_error", "pd_classical_gap", "wall_s",
                    "lambda_pd", "lambda_classical", "lambda_h",
                    "long_wave_ratio", "end_time"):
            r[key] = float(r[key])
    return rows


def order(e0, e1, x0, x1):
    return math.log(e0 / e1) / math.log(x0 / x1) if e0 > 0 and e1 > 0 else float("nan")


def tables(rows):
    for study in dict.fromkeys(r["study"] for r in rows):
        sub = [r for r in rows if r["study"] == study]
        print("\n%s (%dD, q = %d, %s influence)" % (
            study, sub[0]["dim"], sub[0]["q"], sub[0]["omega"]))
        print("%3s %8s %9s %7s %10s %11s %11s %6s %10s %10s %11s %8s" % (
            "m", "delta", "dx", "nodes", "reference", "error", "predicted",
            "order", "lam_h/lam", "long-wave", "|PD-cl.|", "wall s"))
        previous = {}
        for r in sub:
            key = (r["reference"], r["m"] if study.startswith("delta") else None)
            x = r["delta"] if study.startswith("delta") else r["dx"]
            p = previous.get(key)
            o = order(p[0], r["relative_l2_error"], p[1], x) if p else float("nan")
            previous[key] = (r["relative_l2_error"], x)
            print("%3d %8.5f %9.6f %7d %10s %11.4e %11.4e %6.2f %10.6f %10.6f %11.4e %8.3f" % (
                r["m"], r["delta"], r["dx"], r["nodes"], r["reference"],
                r["relative_l2_error"], r["predicted_error"], o,
                r["lambda_h"] / r["lambda_pd"], r["long_wave_ratio"],
                r["pd_classical_gap"], r["wall_s"]))


def main():
    path, out = sys.argv[1], sys.argv[2]
    rows = read(path)
    tables(rows)

    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 5))
    colours = iter(plt.rcParams["axes.prop_cycle"].by_key()["color"])
    for study in dict.fromkeys(r["study"] for r in rows):
        if not study.startswith("m_"):
            continue
        sub = sorted((r for r in rows if r["study"] == study),
                     key=lambda r: r["dx"])
        c = next(colours)
        label = "%s: %dD q=%d %s, $\\delta$=%g" % (
            study, sub[0]["dim"], sub[0]["q"], sub[0]["omega"], sub[0]["delta"])
        left.loglog([r["dx"] for r in sub], [r["relative_l2_error"] for r in sub],
                    "o-", color=c, label=label)
        left.loglog([r["dx"] for r in sub], [r["predicted_error"] for r in sub],
                    "x--", color=c, label=study + ": discrete symbol")
        for r in sub:
            left.annotate("m=%d" % r["m"], (r["dx"], r["relative_l2_error"]),
                          textcoords="offset points", xytext=(4, -10), fontsize=7)
        x0, e0 = sub[-1]["dx"], sub[-1]["relative_l2_error"]
        left.loglog([x0, x0 / 4], [e0, e0 / 16], ":", color="grey")
    left.set_xlabel("dx = $\\delta$ / m (fixed $\\delta$)")
    left.set_ylabel("relative $l_2$ error against the PD solution")
    left.set_title("m-convergence (dotted: slope 2)")
    left.legend(fontsize=7)

    markers = {"pd": "o-", "classical": "s-"}
    for study in dict.fromkeys(r["study"] for r in rows):
        if not study.startswith("delta"):
            continue
        for m in sorted({r["m"] for r in rows if r["study"] == study}):
            c = next(colours)
            sub = sorted((r for r in rows if r["study"] == study and r["m"] == m),
                         key=lambda r: r["delta"])
            for ref in ("pd", "classical"):
                s = [r for r in sub if r["reference"] == ref]
                if not s:
                    continue
                right.loglog([r["delta"] for r in s],
                             [r["relative_l2_error"] for r in s], markers[ref],
                             color=c, label="%s m=%d vs %s" % (study, m, ref))
                right.loglog([r["delta"] for r in s],
                             [r["predicted_error"] for r in s], "x--", color=c,
                             alpha=0.5)
            # the delta -> 0 limit at fixed m of the error against the
            # classical solution: K is effectively long_wave_ratio K
            r = sub[0]
            floor = abs(math.expm1((1 - r["long_wave_ratio"])
                                   * r["lambda_classical"] * r["end_time"]))
            right.axhline(floor, color=c, lw=0.8, ls="-.")
        gap = sorted((r for r in rows if r["study"] == study
                      and r["reference"] == "pd"), key=lambda r: r["delta"])
        gap = list({r["delta"]: r for r in gap}.values())
        right.loglog([r["delta"] for r in gap],
                     [r["pd_classical_gap"] for r in gap], ":", color="k",
                     label="%s: |PD - classical| (exact, ~$\\delta^2$)" % study)
    right.set_xlabel("$\\delta$ (fixed m)")
    right.set_ylabel("relative $l_2$ error")
    right.set_title("$\\delta$-convergence (x--: discrete symbol; -.: limit "
                    "$\\delta \\to 0$ vs classical at fixed m)", fontsize=9)
    right.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "error_vs_spacing.png"), dpi=120)

    fig, ax = plt.subplots(figsize=(7, 5))
    for study in dict.fromkeys(r["study"] for r in rows):
        for ref in ("pd", "classical"):
            sub = sorted((r for r in rows if r["study"] == study
                          and r["reference"] == ref), key=lambda r: r["wall_s"])
            for m in sorted({r["m"] for r in sub}) if study.startswith("delta") else [None]:
                s = [r for r in sub if m is None or r["m"] == m]
                if s:
                    ax.loglog([r["wall_s"] for r in s],
                              [r["relative_l2_error"] for r in s], markers[ref],
                              label="%s%s vs %s" % (
                                  study, "" if m is None else " m=%d" % m, ref))
    ax.set_xlabel("wall time (s, one process, one thread)")
    ax.set_ylabel("relative $l_2$ error")
    ax.set_title("error against wall time")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "error_vs_wall_time.png"), dpi=120)


if __name__ == "__main__":
    main()
