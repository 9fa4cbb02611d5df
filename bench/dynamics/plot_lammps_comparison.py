#!/usr/bin/env python3
"""Plots of bench/dynamics/run_lammps_comparison.sh: time per step against
the number of nodes (both codes), bonds per second per core, and the probe
displacement histories of the two codes (each model and variant, largest
size)."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

out = sys.argv[1]
rows = list(csv.DictReader(open(f"{out}/lammps_comparison.csv")))
models = sorted({r["model"] for r in rows})

fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
for (code, ranks, threads), (color, line) in {
    ("lammps", "1", "1"): ("k", "-"),
    ("perideal", "1", "1"): ("b", "-"),
    ("perideal", "1", "2"): ("b", "--"),
    ("perideal", "2", "1"): ("g", "-."),
}.items():
    for model, marker in zip(models, "osD^"):
        for variant, fill in (("elastic", None), ("failure", "none")):
            sel = [r for r in rows if r["code"] == code and r["model"] == model
                   and r["ranks"] == ranks and r["threads"] == threads
                   and r["variant"] == variant]
            if not sel:
                continue
            n = [int(r["nodes"]) for r in sel]
            style = color + line + marker
            label = f"{code} {model} {ranks}p x {threads}t, {variant}"
            axes[0].loglog(n, [float(r["seconds_per_step"]) for r in sel],
                           style, mfc=fill, label=label)
            axes[1].semilogx(n, [float(r["bonds_per_second_per_core"]) / 1e6
                                 for r in sel], style, mfc=fill, label=label)
axes[0].set_xlabel("nodes")
axes[0].set_ylabel("wall time per step [s]")
axes[1].set_xlabel("nodes")
axes[1].set_ylabel("M bonds / s / core")
axes[0].legend(fontsize=6, ncol=2)
axes[0].grid(True, which="both", alpha=0.3)
axes[1].grid(True, alpha=0.3)
fig.suptitle("Explicit dynamics, 3D, m = 3 (" + ", ".join(models)
             + "): PeriDEAL and LAMMPS (PERI)")
fig.tight_layout()
fig.savefig(f"{out}/lammps_comparison.png", dpi=120)

sizes = sorted({int(r["N"]) for r in rows})
for model, variant in ((m, v) for m in models for v in ("elastic", "failure")):
    try:
        probe = list(csv.DictReader(
            open(f"{out}/probe_{model}_{sizes[-1]}_{variant}.csv")))
    except FileNotFoundError:
        continue
    fig, ax = plt.subplots(figsize=(6, 4))
    t = [float(r["time"]) * 1e6 for r in probe]
    for c, color in zip("xyz", "rgb"):
        ax.plot(t, [float(r[f"lammps_u{c}"]) for r in probe], color + "-",
                label=f"LAMMPS u_{c}")
        ax.plot(t, [float(r[f"perideal_u{c}"]) for r in probe], color + "o",
                mfc="none", label=f"PeriDEAL u_{c}")
    ax.set_xlabel("time [us]")
    ax.set_ylabel("probe displacement [m]")
    ax.set_title(f"probe node, {model}, N = {sizes[-1]}, {variant}")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(f"{out}/probe_{model}_{variant}.png", dpi=120)
