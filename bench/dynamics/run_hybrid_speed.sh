#!/usr/bin/env bash
# The hybrid quadrature scheme against the all-standard one on fracture
# runs (issue 23, target: hybrid adaptive >= 3x faster where the damage
# zone covers <= 10 % of the nodes, with the crack within 5 %): the 2D
# branching plate (examples/step-4 against examples/step-6, m = 4) and a 3D
# pre-cracked block (hybrid_block_3d.prm, m = 3). Per run: steps, seconds
# in the time loop and in the switch (TimerOutput), broken bonds and
# standard nodes at the end, node scans against a scan at every step.
# Schemes: 'hybrid' as examples/step-6 runs it, with the order-2 lattice
# row stabilised ('Quadrature/collocation/Stabilisation = all orders',
# doc/collocation.md Sect. 7.3); 'hybrid_paper_row' with the paper's row
# ('automatic'), whose larger spectral radius halves the time step in 2D.
#
# Usage: bench/dynamics/run_hybrid_speed.sh [BUILD_DIR] [--quick]
# Writes results/dynamics/hybrid_speed.csv and hybrid_speed.png. --quick:
# coarse grids and short runs (ctest bench/hybrid_speed_quick: fails unless
# every run completes, the hybrid breaks bonds within 10 % of the
# all-standard run and no switch comes late).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/log_fields.sh"
build=$(cd "${1:-build}" && pwd)
quick=${2:-}
perideal="$build/bin/perideal"
examples="$here/../../examples"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out="$(pwd)/results/dynamics"; mkdir -p "$out"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT

if [ "$quick" = "--quick" ]; then
  edits2d="s/Subdivisions = 400, 160/Subdivisions = 100, 40/; s/Length = 0.001/Length = 0.003/; s/End time           = 46e-6/End time           = 20e-6/"
  edits3d="s/Subdivisions = 80, 40, 24/Subdivisions = 40, 20, 12/; s/End time             = 40e-6/End time             = 10e-6/"
else
  edits2d=""; edits3d=""
fi
hybrid3d='subsection Quadrature
  set Scheme = hybrid
  subsection collocation
    set Stabilisation = all orders
  end
  subsection hybrid
    set Critical stretch fraction = 0.6
  end
end'

# run NAME PRM: one run in its own directory, one output at most.
run() {
  mkdir -p "$work/$1"
  sed -e 's/set Output interval *=.*/set Output interval = 1/' "$2" > "$work/$1/input.prm"
  (cd "$work/$1" && "$perideal" input.prm > log 2>&1) ||
    { tail -5 "$work/$1/log"; echo "FAIL: the run $1 failed"; exit 1; }
}
sed -e "$edits2d" "$examples/step-4/step-4.prm" > "$work/step-4.prm"
sed -e "$edits2d" "$examples/step-6/step-6.prm" > "$work/step-6.prm"
sed -e "$edits3d" "$here/hybrid_block_3d.prm" > "$work/block-standard.prm"
{ cat "$work/block-standard.prm"; echo "$hybrid3d"; } > "$work/block-hybrid.prm"
paper_row='s/set Stabilisation = all orders/set Stabilisation = automatic/'
grep -q "set Stabilisation = all orders" "$work/step-6.prm" ||
  { echo "FAIL: examples/step-6 no longer sets 'Stabilisation = all orders'"; exit 1; }
sed -e "$paper_row" "$work/step-6.prm" > "$work/step-6-paper.prm"
sed -e "$paper_row" "$work/block-hybrid.prm" > "$work/block-hybrid-paper.prm"
run plate2d_standard "$work/step-4.prm"
run plate2d_hybrid "$work/step-6.prm"
run plate2d_hybrid_paper_row "$work/step-6-paper.prm"
run block3d_standard "$work/block-standard.prm"
run block3d_hybrid "$work/block-hybrid.prm"
run block3d_hybrid_paper_row "$work/block-hybrid-paper.prm"

csv="$out/hybrid_speed.csv"
echo "case,scheme,nodes,steps,loop_seconds,switch_seconds,broken_bonds,standard_nodes,node_scan_percent,late_switches" > "$csv"
for name in plate2d_standard plate2d_hybrid plate2d_hybrid_paper_row block3d_standard block3d_hybrid block3d_hybrid_paper_row; do
  log="$work/$name/log"
  switch=$(sed -n 's/^| hybrid switch *| *[0-9]* | *\([0-9.e+-]*\)s.*/\1/p' "$log")
  broken=$(grep -E '^\[ *[0-9.]+ s\] step ' "$log" | tail -1 | sed -E 's/.*broken bonds ([0-9]+).*/\1/')
  nodes=$(log_field "$log" nodes)
  summary=$(grep -m1 '^ *hybrid: ' "$log" || true)
  if [ -n "$summary" ]; then
    standard=$(echo "$summary" | sed -E 's/.*hybrid: ([0-9]+) of.*/\1/')
    scans=$(echo "$summary" | sed -E 's/.*node scans \(([0-9.e+-]+) %.*/\1/')
    late=$(echo "$summary" | sed -E 's/.* ([0-9]+) late switches.*/\1/')
  else
    standard=$nodes; scans=""; late=0
  fi
  echo "${name%%_*},${name#*_},$nodes,$(log_field "$log" steps),$(log_field "$log" loop),${switch:-0},$broken,$standard,$scans,$late" >> "$csv"
done
# The table on the terminal (awk: 'column' is not on a minimal Debian).
awk -F, '{ for (k = 1; k <= NF; ++k) { c[NR, k] = $k; if (length($k) > w[k]) w[k] = length($k) }
           if (NF > n) n = NF }
         END { for (r = 1; r <= NR; ++r) { line = ""
                 for (k = 1; k <= n; ++k) line = line sprintf("%-*s  ", w[k], c[r, k])
                 print line } }' "$csv"
/usr/bin/python3 "$here/plot_hybrid_speed.py" "$csv" "$out/hybrid_speed.png"

# The quick variant's checks: every run completed (above), the hybrid
# breaks bonds within 10 % of the all-standard run, no late switch.
awk -F, 'NR > 1 { b[$1 "," $2] = $7; late += $10 }
  END { bad = late > 0
        for (c in b) { split(c, k, ","); if (k[2] ~ /^hybrid/) {
          s = b[k[1] ",standard"]; d = (b[c] - s) / s; if (d < 0) d = -d
          if (!(s > 0 && d <= 0.10)) { print "FAIL: " k[1] ": broken bonds " b[c] " against " s; bad = 1 } } }
        exit bad }' "$csv"
echo "wrote $csv and $out/hybrid_speed.png"
