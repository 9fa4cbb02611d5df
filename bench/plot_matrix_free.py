"""Plots of bench/run_matrix_free.sh: time and peak memory against the
number of nodes (log-log) for the matrix-free solve with the local
elasticity and the Jacobi preconditioner, error against wall time,
iterations against h and against m."""
import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

parser = argparse.ArgumentParser()
parser.add_argument("--output-dir", default=".")
args = parser.parse_args()
os.chdir(args.output_dir)


def read(name):
    with open(name) as f:
        return list(csv.DictReader(f))


def save(fig, name):
    """Under a temporary name, then renamed: a kill leaves the old file whole."""
    fig.savefig(name + ".tmp.png", dpi=120)
    os.replace(name + ".tmp.png", name)


# The preconditioners as the summary names them, and their markers.
PRECONDITIONERS = (("local elasticity", "o"),
                   ("local elasticity (coarsening 2)", "^"),
                   ("Jacobi", "s"))

rows = read("scaling.csv")
fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
for prec, marker in PRECONDITIONERS:
    r = [x for x in rows if x["preconditioner"] == prec]
    n = [int(x["n_nodes"]) for x in r]
    axes[0].loglog(n, [float(x["time_total"]) for x in r], marker, ls="-",
                   label=f"{prec}: total")
    axes[0].loglog(n, [float(x["time_solve"]) for x in r], marker, ls="--",
                   label=f"{prec}: solve")
    axes[1].loglog(n, [float(x["peak_memory_mb"]) for x in r], marker, ls="-",
                   label=prec)
    axes[2].semilogx(n, [int(x["iterations"]) for x in r], marker, ls="-",
                     label=prec)
axes[0].set(xlabel="nodes", ylabel="wall time [s]",
            title="3D LPS, m = 3, CG to 1e-8")
axes[1].set(xlabel="nodes", ylabel="peak memory [MB]")
axes[2].set(xlabel="nodes", ylabel="CG iterations")
for a in axes:
    a.grid(True, which="both", alpha=0.3)
    a.legend()
fig.tight_layout()
save(fig, "scaling.png")

fig, ax = plt.subplots(figsize=(6, 4.5))
for prec, marker in PRECONDITIONERS:
    r = [x for x in rows if x["preconditioner"] == prec]
    ax.loglog([float(x["time_total"]) for x in r],
              [float(x["l2_error"]) for x in r], marker, ls="-", label=prec)
ax.set(xlabel="wall time [s]", ylabel="relative L2 error",
       title="error against wall time")
ax.grid(True, which="both", alpha=0.3)
ax.legend()
fig.tight_layout()
save(fig, "error_vs_time.png")

rows = read("m_sweep.csv")
fig, ax = plt.subplots(figsize=(6, 4.5))
for prec, marker in PRECONDITIONERS:
    r = [x for x in rows if x["preconditioner"] == prec]
    ax.plot([float(x["m_ratio"]) for x in r], [int(x["iterations"]) for x in r],
            marker, ls="-", label=prec)
ax.set(xlabel="m-ratio", ylabel="CG iterations", title="iterations against m")
ax.grid(True, alpha=0.3)
ax.legend()
fig.tight_layout()
save(fig, "m_sweep.png")
