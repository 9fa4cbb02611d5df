#!/usr/bin/python3
"""Bars of hybrid_speed.csv (run_hybrid_speed.sh): seconds in the time loop
of the all-standard and the hybrid runs of each case (hybrid_paper_row:
the paper's order-2 lattice row, not stabilised), the hybrid's switch
share hatched, and the broken bonds of each run on a second panel."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
cases = sorted({r["case"] for r in rows})
fig, (ax_time, ax_broken) = plt.subplots(1, 2, figsize=(10, 4))
schemes = [s for s in ("standard", "hybrid", "hybrid_paper_row") if any(r["scheme"] == s for r in rows)]
width = 0.8 / len(schemes)
for k, scheme in enumerate(schemes):
    loop = []
    switch = []
    broken = []
    for case in cases:
        r = next(r for r in rows if r["case"] == case and r["scheme"] == scheme)
        loop.append(float(r["loop_seconds"]))
        switch.append(float(r["switch_seconds"] or 0))
        broken.append(float(r["broken_bonds"]))
    x = [i + (k - 0.5 * (len(schemes) - 1)) * width for i in range(len(cases))]
    ax_time.bar(x, loop, width, label=scheme)
    if scheme != "standard":
        ax_time.bar(x, switch, width, fill=False, hatch="//", label="of it: switch" if scheme == "hybrid" else None)
    ax_broken.bar(x, broken, width, label=scheme)
for ax, label in ((ax_time, "time loop (s)"), (ax_broken, "broken bonds at the end")):
    ax.set_xticks(range(len(cases)))
    ax.set_xticklabels(cases)
    ax.set_ylabel(label)
    ax.legend()
ax_time.set_title("wall time (1 process, 2 threads)")
ax_broken.set_title("crack: broken bonds")
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)
