#!/usr/bin/env python3
"""Strong-scaling estimate of the explicit loop (issue 25, item 3).

Reads results/dynamics/partition_volume.csv (run_partition_volume.sh: owned
and ghost nodes and exchange partners of the cube's p4est partition on P
processes) and estimates the time of one step on P processes:

  t_compute   = t_node * owned_max            (the slowest process)
  t_redundant = LPS only: the dilatations of the ghosts within a horizon,
                theta_share * t_node * ghosts_max * f_theta, f_theta the
                horizon's share of the two-horizon ghost layer's depth
  t_exchange  = alpha * neighbours_max + 8 * 3 * ghosts_max / bandwidth
                (+ one message per neighbour for broken bonds)
  t_reduce    = alpha * log2(P)               (the finite check)
  t_step      = t_compute + t_redundant + t_exchange + t_reduce
  overlapped  = t_compute + t_redundant + max(0, t_exchange - t_interior)
                + t_reduce, t_interior = t_compute times the share of
                owned nodes farther than a horizon from the subdomain's
                surface (the subdomain taken as a cube: ((s - 2m) / s)^3,
                s = owned^(1/3), m the horizon in cells)

and the parallel efficiency t_node * N^3 / (P * t_step). Processes beyond
the measured ones follow the surface law ghosts ~ (N^3 / P)^(2/3) fitted at
the largest measured P. t_node comes from a measured single-process run
(arguments); alpha and the bandwidth are stated network parameters, not
measurements of a cluster.

Usage: plot_strong_scaling.py CSV OUT_PREFIX --pmb-node-step S --lps-node-step S
       [--alpha 2e-6] [--bandwidth 1e10] [--max-processes 4096]
"""
import argparse
import csv
import math
import os

parser = argparse.ArgumentParser()
parser.add_argument("csv")
parser.add_argument("out")
parser.add_argument("--pmb-node-step", type=float, required=True,
                    help="seconds per node per step, PMB, one process")
parser.add_argument("--lps-node-step", type=float, required=True,
                    help="seconds per node per step, LPS, one process")
parser.add_argument("--theta-share", type=float, default=0.4,
                    help="share of an LPS step in the dilatation pass")
parser.add_argument("--alpha", type=float, default=2e-6,
                    help="latency per message, s")
parser.add_argument("--bandwidth", type=float, default=1e10,
                    help="bytes per second per process")
parser.add_argument("--max-processes", type=int, default=4096)
args = parser.parse_args()

rows = list(csv.DictReader(open(args.csv)))
out_rows = []
for two in ("0", "1"):
    measured = sorted((r for r in rows if r["two_horizons"] == two),
                      key=lambda r: int(r["processes"]))
    if not measured:
        continue
    n = int(measured[0]["n"])
    m = float(measured[0]["m"])
    total = n ** 3
    t_node = args.lps_node_step if two == "1" else args.pmb_node_step
    last = measured[-1]
    p_last = int(last["processes"])
    c_ghost = float(last["ghosts_max"]) / (total / p_last) ** (2 / 3)
    neighbours_last = float(last["neighbours_max"])
    points = [(int(r["processes"]), float(r["owned_max"]),
               float(r["ghosts_max"]), float(r["neighbours_max"]), "measured")
              for r in measured]
    p = p_last * 2
    while p <= args.max_processes:
        owned = total / p
        points.append((p, owned, c_ghost * owned ** (2 / 3),
                       neighbours_last, "surface law"))
        p *= 2
    # The horizon's share of the ghost layer's depth (2 (delta + d), d the
    # cell diameter sqrt(3) h) for the redundant LPS dilatations.
    f_theta = m / (2 * (m + math.sqrt(3))) if two == "1" else 0.0
    for p, owned, ghosts, neighbours, source in points:
        t_compute = t_node * owned
        t_redundant = args.theta_share * t_node * ghosts * f_theta
        if p == 1:
            t_exchange = t_reduce = 0.0
        else:
            t_exchange = (2 * args.alpha * neighbours +
                          8 * 3 * ghosts / args.bandwidth)
            t_reduce = args.alpha * math.log2(p)
        # Owned nodes farther than a horizon from the subdomain's surface,
        # the subdomain taken as a cube of side owned^(1/3) cells.
        side = owned ** (1 / 3)
        interior = max(0.0, (side - 2 * m) / side) ** 3
        t_step = t_compute + t_redundant + t_exchange + t_reduce
        t_overlap = (t_compute + t_redundant +
                     max(0.0, t_exchange - interior * t_compute) + t_reduce)
        ideal = t_node * total / p
        out_rows.append({
            "model": "LPS" if two == "1" else "PMB", "processes": p,
            "source": source, "nodes_per_process": round(owned),
            "ghosts_per_process": round(ghosts),
            "neighbours": round(neighbours, 1),
            "t_compute_s": t_compute, "t_redundant_s": t_redundant,
            "t_exchange_s": t_exchange, "t_reduce_s": t_reduce,
            "t_step_s": t_step, "t_step_overlapped_s": t_overlap,
            "efficiency": ideal / t_step,
            "efficiency_overlapped": ideal / t_overlap})

# Under a temporary name, then renamed: a kill leaves the old file whole.
with open(args.out + ".csv.tmp", "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=list(out_rows[0].keys()))
    writer.writeheader()
    writer.writerows(out_rows)
os.replace(args.out + ".csv.tmp", args.out + ".csv")
print("wrote", args.out + ".csv")

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
for model, colour in (("PMB", "tab:blue"), ("LPS", "tab:red")):
    rs = [r for r in out_rows if r["model"] == model]
    if not rs:
        continue
    ps = [r["processes"] for r in rs]
    left.loglog(ps, [r["t_step_s"] for r in rs], "o-", color=colour,
                label=model + " estimate")
    left.loglog(ps, [r["t_compute_s"] for r in rs], ":", color=colour,
                label=model + " compute only")
    right.semilogx(ps, [r["efficiency"] for r in rs], "o-", color=colour,
                   label=model)
    right.semilogx(ps, [r["efficiency_overlapped"] for r in rs], "--",
                   color=colour, label=model + ", exchange overlapped")
n = int(rows[0]["n"])
left.set_xlabel("processes")
left.set_ylabel("time per step [s]")
p_measured = max(int(r["processes"]) for r in rows)
left.set_title(f"{n}^3 nodes, delta = 3 h: partitions measured to "
               f"P = {p_measured}, surface law beyond")
left.legend(fontsize=8)
right.set_xlabel("processes")
right.set_ylabel("parallel efficiency")
right.set_ylim(0, 1.05)
right.set_title(f"alpha = {args.alpha:g} s, {args.bandwidth / 1e9:g} GB/s")
right.legend(fontsize=8)
fig.tight_layout()
fig.savefig(args.out + ".tmp.png", dpi=120)
os.replace(args.out + ".tmp.png", args.out + ".png")
print("wrote", args.out + ".png")
