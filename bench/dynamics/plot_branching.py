#!/usr/bin/env python3
"""Crack-tip history of the branching runs (run_branching.sh).

From the tip columns of each run's energy file (origin of the tracking:
the left end of the pre-crack, so that the tip is the crack front):
- initiation: the first time the tip has advanced one horizon beyond the
  notch tip (x = 0);
- branching: the first time the front spread (largest distance of a front
  node from the line origin-tip) exceeds two horizons (a single crack's
  damage band is about one horizon wide); position: the tip's x then;
- mean speed: least-squares slope of tip x against time between initiation
  and branching, as a fraction of the Rayleigh speed c_R of the model (2D
  plane stress, E = 72 GPa, nu = 1/3, rho = 2440: c_R from the Rayleigh
  equation with the plane-stress c_p and c_s) and of 3102 m/s (the value
  quoted in the literature, from the 3D formula with nu = 1/3);
- peak speed before branching: the tip's x differenced over about 2 us;
- branch half-angle: from the branching point to the last tip position.
Runs with the hybrid quadrature (column scheme) are drawn dashed.
Writes branching.csv and branching.png.
"""
import csv
import math
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

E, nu, rho = 72e9, 1.0 / 3.0, 2440.0
mu = E / (2 * (1 + nu))
cs = math.sqrt(mu / rho)
cp = math.sqrt(E / ((1 - nu * nu) * rho))  # plane stress


def rayleigh(cp, cs):
    k = (cs / cp) ** 2
    f = lambda x: (2 - x * x) ** 2 - 4 * math.sqrt(1 - k * x * x) * math.sqrt(1 - x * x)
    a, b = 0.5, 0.999999
    for _ in range(200):
        c = 0.5 * (a + b)
        if f(a) * f(c) <= 0:
            b = c
        else:
            a = c
    return 0.5 * (a + b) * cs


cR = rayleigh(cp, cs)
out = sys.argv[1]
runs = list(csv.DictReader(open(f"{out}/branching_runs.csv")))
rows = []
fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
for run in runs:
    data = list(csv.DictReader(open(f"{out}/{run['case']}.csv")))
    delta = float(run["delta"])
    t = np.array([float(r["time"]) for r in data])
    x = np.array([float(r["tip_x"]) for r in data])
    y = np.array([float(r["tip_y"]) for r in data])
    spread = np.array([float(r["front_spread"]) for r in data])
    moved = np.nonzero(x >= delta)[0]
    t_init = t[moved[0]] if len(moved) else float("nan")
    branched = np.nonzero(spread > 2 * delta)[0]
    if len(branched):
        kb = branched[0]
        t_branch, x_branch = t[kb], x[kb]
        half_angle = math.degrees(math.atan2(abs(y[-1]), x[-1] - x_branch))
    else:
        kb = len(t) - 1
        t_branch, x_branch, half_angle = float("nan"), float("nan"), float("nan")
    sel = (t >= t_init) & (t <= t[kb])
    speed = np.polyfit(t[sel], x[sel], 1)[0] if sel.sum() >= 3 else float("nan")
    # Speed: the tip's x differenced over about 2 microseconds.
    w = max(1, int(round(2e-6 / max(t[1] - t[0], 1e-12))))
    v = (x[2 * w:] - x[:-2 * w]) / (t[2 * w:] - t[:-2 * w])
    tv = t[w:-w]
    before = tv < t[kb]
    peak = v[before].max() if before.any() else float("nan")
    scheme = run.get("scheme", "standard")
    rows.append(dict(case=run["case"], delta_mm=delta * 1e3, m=run["m"],
                     traction_MPa=float(run["traction"]) / 1e6,
                     scheme=scheme,
                     standard_nodes_final=run.get("standard_nodes_final", "all"),
                     nodes=run["nodes"], steps=run["steps"],
                     wall_seconds=run["wall_seconds"],
                     peak_memory_mb=run["peak_memory_mb"],
                     initiation_us=f"{t_init * 1e6:.2f}",
                     branching_us=f"{t_branch * 1e6:.2f}",
                     branching_x_mm_from_left=f"{(x_branch + 0.05) * 1e3:.1f}",
                     mean_speed_m_s=f"{speed:.0f}",
                     speed_over_cR_model=f"{speed / cR:.3f}",
                     speed_over_3102=f"{speed / 3102:.3f}",
                     peak_speed_before_branching_m_s=f"{peak:.0f}",
                     peak_over_cR_model=f"{peak / cR:.3f}",
                     branch_half_angle_deg=f"{half_angle:.1f}",
                     final_tip_mm=f"({(x[-1] + 0.05) * 1e3:.1f}, {y[-1] * 1e3:.1f})"))
    label = (f"delta={delta*1e3:g} mm m={run['m']} "
             f"{float(run['traction'])/1e6:g} MPa {scheme}")
    style = "--" if scheme == "hybrid" else "-"
    axes[0].plot(t * 1e6, (x + 0.05) * 1e3, style, label=label)
    axes[1].plot(tv * 1e6, v / cR, style, label=label)
    axes[2].plot(float(run["wall_seconds"]), t_branch * 1e6,
                 "s" if scheme == "hybrid" else "o", label=label)
with open(f"{out}/branching.csv", "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
    w.writeheader()
    w.writerows(rows)
axes[0].set_xlabel("t (us)")
axes[0].set_ylabel("crack tip x from the left edge (mm)")
axes[0].legend(fontsize=6)
axes[1].set_xlabel("t (us)")
axes[1].set_ylabel(f"tip speed / c_R (c_R = {cR:.0f} m/s)")
axes[1].set_ylim(-0.1, 1.0)
axes[2].set_xscale("log")
axes[2].set_xlabel("wall time (s)")
axes[2].set_ylabel("branching time (us)")
fig.tight_layout()
fig.savefig(f"{out}/branching.png", dpi=120)
print(f"c_R (2D plane stress model) = {cR:.1f} m/s, c_s = {cs:.1f}, c_p = {cp:.1f}")
for r in rows:
    print(", ".join(f"{k}={v}" for k, v in r.items()))
