"""Plots of bench/run_boundary_treatment.sh.

Usage: python3 bench/plot_boundary_treatment.py DIR
Per case, DIR/<case>_error_slices.png: the normalized displacement error
(paper Eq. 38) of the body nodes on the mid-plane slice (3D: the layer of
nodes nearest z = 0; 2D: the plate), one panel per treatment, each with its
own colour scale. DIR/convergence.png: error against h (fixed horizon) and
against the horizon (fixed m). DIR/error_vs_time.png: error against run time.
"""
import csv
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1]
main = list(csv.DictReader(open(f"{out}/boundary_treatment.csv")))
cost = list(csv.DictReader(open(f"{out}/cost.csv")))


def slice_of(path):
    rows = [r for r in csv.DictReader(open(path)) if r["kind"] == "body"]
    if "z" in rows[0]:
        z0 = min(abs(float(r["z"])) for r in rows)
        rows = [r for r in rows if abs(abs(float(r["z"])) - z0) < 1e-9
                and float(r["z"]) <= 0]
    return ([float(r["x"]) for r in rows], [float(r["y"]) for r in rows],
            [float(r["normalized_error"]) for r in rows])


for case in sorted({r["case"] for r in main}):
    tags = [r["tag"] for r in cost if r["case"] == case
            and not r["tag"].startswith(("h_", "delta_"))]
    tags = [t for t in tags if os.path.exists(f"{out}/nodes/{case}_{t}.csv")]
    if not tags:
        continue
    fig, axes = plt.subplots(1, len(tags), figsize=(4.2 * len(tags), 3.4),
                             squeeze=False)
    for ax, tag in zip(axes[0], tags):
        x, y, e = slice_of(f"{out}/nodes/{case}_{tag}.csv")
        sc = ax.scatter(x, y, c=[100 * v for v in e], marker="s", s=18,
                        cmap="viridis")
        fig.colorbar(sc, ax=ax, label="error (%)")
        ax.set_title(f"{tag}: max {100 * max(e):.3g} %")
        ax.set_aspect("equal")
        ax.set_xlabel("x")
        ax.set_ylabel("y")
    fig.suptitle(f"{case}: normalized displacement error (Eq. 38), "
                 "mid-plane")
    fig.tight_layout()
    fig.savefig(f"{out}/{case}_error_slices.png", dpi=120)
    plt.close(fig)

if os.path.exists(f"{out}/convergence.csv"):
    conv = list(csv.DictReader(open(f"{out}/convergence.csv")))
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, study, var, label in (
            (axes[0], "fixed_horizon", "h", "h (horizon 0.25)"),
            (axes[1], "fixed_m", "horizon", "horizon (m = 3)")):
        for treatment, style in (("none", "o-"), ("surface nodes", "s-")):
            rows = sorted((float(r[var]), float(r["max_error"]))
                          for r in conv if r["study"] == study
                          and r["treatment"] == treatment)
            if rows:
                ax.loglog(*zip(*rows), style, label=treatment)
        ax.set_xlabel(label)
        ax.set_ylabel("max normalized error (Eq. 38)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle("manufactured_3d: convergence with and without treatment")
    fig.tight_layout()
    fig.savefig(f"{out}/convergence.png", dpi=120)
    plt.close(fig)

fig, ax = plt.subplots(figsize=(6, 4.5))
for treatment, marker in (("none", "o"), ("surface nodes", "s"),
                          ("fictitious layer", "^")):
    rows = [r for r in cost if r["treatment"] == treatment]
    if rows:
        ax.loglog([float(r["seconds"]) for r in rows],
                  [float(r["max_error"]) for r in rows], marker,
                  linestyle="none", label=treatment)
ax.set_xlabel("wall time of the run (s)")
ax.set_ylabel("max normalized error (Eq. 38)")
ax.grid(True, which="both", alpha=0.3)
ax.legend()
fig.tight_layout()
fig.savefig(f"{out}/error_vs_time.png", dpi=120)
plt.close(fig)
print("plots written to", out)
