#!/usr/bin/env bash
# Memory per node of explicit dynamics with fracture, and the largest 3D
# problem that fits in a memory budget: a unit-spaced cube of N^3 nodes,
# bond-based PMB with a critical stretch, finite kinematics, m = 3 (exact
# partial volumes), a few steps, no VTU output. Peak memory is deal.II's
# VmHWM summed over the processes (the run's last line). The bytes per node
# of the largest sizes, extrapolated linearly, give the largest N for the
# budget, which is then run to check it.
#
# Usage: bench/dynamics/run_memory.sh [BUILD_DIR] [BUDGET_GB] [SIZES...]
# Writes results/dynamics/memory.csv.
set -eu
. "$(cd "$(dirname "$0")" && pwd)/log_fields.sh"
build=$(cd "${1:-build}" && pwd)
budget=${2:-16}
shift 2 || true
sizes=${*:-40 60 80 100 120}
perideal="$build/bin/perideal"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out="$(pwd)/results/dynamics"; mkdir -p "$out"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
csv="$out/memory.csv"
echo "N,nodes,bonds,steps,setup_seconds,seconds_per_step,peak_memory_mb,kb_per_node,bytes_per_bond" > "$csv"
run() {
  local N=$1
  cat > "$work/cube.prm" <<PRM
set Dimension = 3
set Problem type = explicit dynamics
subsection Geometry
  set Lower corner = 0, 0, 0
  set Upper corner = $N, $N, $N
  set Subdivisions = $N, $N, $N
end
subsection Horizon
  set m-ratio = 3
end
subsection Material model
  set Model = bond-based
  subsection bond-based
    set Young's modulus = 1
    set Density = 1
    set Critical stretch = 0.01
  end
end
subsection explicit dynamics
  set End time = 1.5
  set Energy every steps = 1
  set Progress interval = 0
  subsection Initial velocity
    set Variable names = x,y,z,t
    set Function expression = 1e-3*sin(x); 0; 0
  end
end
subsection Output
  set Write VTU = false
  set Directory = out
end
PRM
  ( cd "$work" && "$perideal" --threads 2 cube.prm ) > "$work/log" 2>&1 || { tail "$work/log"; exit 1; }
  local nodes bonds steps loop total mem
  nodes=$(log_field "$work/log" nodes)
  bonds=$(log_field "$work/log" bonds)
  steps=$(log_field "$work/log" steps)
  loop=$(log_field "$work/log" loop)
  total=$(log_field "$work/log" wall)
  mem=$(log_field "$work/log" memory)
  awk -v N=$N -v n=$nodes -v b=$bonds -v s=$steps -v l=$loop -v t=$total -v m=$mem 'BEGIN {
    printf "%d,%d,%d,%d,%.4g,%.4g,%.6g,%.4g,%.4g\n", N, n, b, s, t - l, l / s, m, m * 1024 / n, m * 1048576 / b }' | tee -a "$csv"
}
for N in $sizes; do run $N; done
# The largest cube for the budget from the last two sizes (memory linear
# in N^3 beyond a fixed part).
N=$(awk -F, -v B=$budget 'NR > 1 { n[NR] = $2; m[NR] = $7; k = NR }
  END { slope = (m[k] - m[k-1]) / (n[k] - n[k-1]); base = m[k] - slope * n[k];
        printf "%d", ((B * 1024 - base) / slope) ^ (1 / 3) }' "$csv")
echo "predicted largest cube for $budget GB: $N^3"
run $N
