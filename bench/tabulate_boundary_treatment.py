"""Tables of bench/run_boundary_treatment.sh from the driver's summary.csv.

Usage: python3 bench/tabulate_boundary_treatment.py DIR
Writes DIR/boundary_treatment.csv (case,treatment,N,max_error,l2_error,
n_nodes,seconds), DIR/cost.csv and DIR/convergence.csv.
"""
import csv
import sys

out = sys.argv[1]
summary = list(csv.DictReader(open(f"{out}/summary.csv")))
runs = [line.strip().split(",") for line in open(f"{out}/runs.csv")]
assert len(runs) == len(summary), "one summary line per run expected"

main, cost, convergence = [], [], []
for (case, tag, nx, m, seconds), s in zip(runs, summary):
    row = dict(case=case, treatment=s["treatment"], N=s["taylor_order"],
               max_error=s["max_normalized_error"], l2_error=s["l2_error"],
               n_nodes=s["n_nodes"], seconds=f"{float(seconds):.3f}")
    extra = dict(tag=tag, n_unknowns=s["n_unknowns"],
                 n_surface_nodes=s["n_surface_nodes"],
                 n_fictitious_nodes=s["n_fictitious_nodes"], nnz=s["nnz"],
                 time_setup=s["time_operator"], time_assembly=s["time_assembly"],
                 time_solve=s["time_solve"], peak_memory_mb=s["peak_memory_mb"])
    if tag.startswith("h_") or tag.startswith("delta_"):
        convergence.append(dict(study="fixed_horizon" if tag.startswith("h_")
                                else "fixed_m", h=s["h"], horizon=s["horizon"],
                                m_ratio=s["m_ratio"], **row, **extra))
    else:
        main.append(row)
    cost.append(dict(**row, **extra))


def write(name, rows):
    if not rows:
        return
    with open(f"{out}/{name}", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


write("boundary_treatment.csv", main)
write("cost.csv", cost)
write("convergence.csv", convergence)
for r in main:
    print(f"{r['case']:28s} {r['treatment']:17s} N={r['N']} "
          f"max {float(r['max_error']):.3e} L2 {float(r['l2_error']):.3e} "
          f"{r['n_nodes']:>6s} nodes {r['seconds']:>8s} s")
