#!/usr/bin/env bash
# Study 6 of issue 23: corrosion with the hybrid quadrature against the
# all-standard scheme, on the pit of examples/step-5 (SS304 in NaCl, a pit
# grows under diffusion control from an 8 um opening in a passive film).
# Cases, each on the example's grid (1 um cells, m = 3) and on a grid
# REFINE times finer at the same horizon (m = 3 REFINE):
#   standard          every node standard (exact partial areas);
#   hybrid_adaptive   C2 collocation rows (stabilised: 'Stabilisation =
#                     all orders', as examples/step-6), the nodes an
#                     interface reaches standard for good (the default
#                     'adaptive');
#   hybrid_fixed      the same rows, a node at an interface standard only
#                     while its neighbourhood holds two phases ('fixed'
#                     without a region);
#   hybrid_adaptive_paper_row (full run only) the paper's C2 row, whose
#                     larger Gershgorin bound halves the time step.
# Metal and passive film conduct nothing (their bulk costs nothing in any
# scheme); the rows replace the partial-volume stencil in the electrolyte
# away from the interface.
#
# Usage: bench/diffusion/run_corrosion_hybrid.sh BUILD_DIR [--quick]
#   --quick: the example's grid only, to t = 4 s (the ctest variant);
#   otherwise both grids to END_TIME (default 20 s; the example runs 40).
#   THREADS=N (default 1): threads per run; REFINE=N (default 2): the
#   finer grid; LEVELS="1 2 3" (default "1 REFINE"): all refinements run.
# Writes results/diffusion/corrosion_hybrid.csv (one row per run: case,
# refinement, nodes, steps, time step, wall and loop seconds, the final pit
# depth, pit volume and converted nodes, their differences to the standard
# run on the same grid (largest over the history rows, against the two
# standard rows around each row's time, for the depth and the volume; the
# volumes relative to the standard's final one), the final and largest
# fraction of standard nodes),
# corrosion_hybrid_<case>_r<k>.csv (each history), and
# corrosion_hybrid_history.png, corrosion_hybrid_speed.png
# (plot_corrosion_hybrid.py).
# Checks (non-zero exit): every run finishes; every hybrid run's pit depth
# is within one cell of the standard run's at the same time (of the
# interval the two standard rows around it span), and its final pit volume
# within 5 % of the standard one.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/../dynamics/log_fields.sh"
build=$(cd "${1:?usage: run_corrosion_hybrid.sh BUILD_DIR [--quick]}" && pwd)
quick=${2:-}
threads=${THREADS:-1}
refine=${REFINE:-2}
perideal="$build/bin/perideal"
[ -x "$perideal" ] || { echo "no $perideal: build the target perideal first"; exit 1; }
example="$here/../../examples/step-5/step-5.prm"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out="$(pwd)/results/diffusion"
mkdir -p "$out"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT

cases="standard hybrid_adaptive hybrid_fixed"
if [ "$quick" = "--quick" ]; then levels="1"; end=4
else levels=${LEVELS:-"1 $refine"}; end=${END_TIME:-20}; cases="$cases hybrid_adaptive_paper_row"; fi
summary="$out/corrosion_hybrid.csv"
echo "case,refinement,n_nodes,steps,time_step,wall_seconds,loop_seconds,pit_depth,pit_volume,converted_nodes,max_depth_difference,max_volume_difference,final_volume_difference,final_standard_fraction,max_standard_fraction" > "$summary"
for r in $levels; do
  for name in $cases; do
    case_dir="$work/${name}_r$r"
    mkdir -p "$case_dir"
    # The example's input, refined at the same horizon, without output
    # series (the history is the comparison), to the end time.
    sed -e "s/set Subdivisions = 100, 60/set Subdivisions = $((100 * r)), $((60 * r))/" \
        -e "s/set m-ratio = 3/set m-ratio = $((3 * r))/" \
        -e "s/set End time      = 40/set End time      = $end/" \
        -e "s/set Output interval     = 2/set Output interval     = $end/" \
        -e "s/set History every steps = 2000/set History every steps = $((500 * r * r))/" \
        -e "s/set Progress interval   = 5/set Progress interval   = 30/" \
        "$example" > "$case_dir/input.prm"
    # The stabilised order-2 row ('all orders', as examples/step-6): the
    # paper's row has twice the Gershgorin bound (half the time step).
    stabilised='  subsection collocation\n    set Stabilisation = all orders\n  end\n'
    case $name in
      hybrid_adaptive)
        printf "subsection Quadrature\n  set Scheme = hybrid\n$stabilised""end\n" >> "$case_dir/input.prm" ;;
      hybrid_fixed)
        printf "subsection Quadrature\n  set Scheme = hybrid\n$stabilised""  subsection hybrid\n    set Configuration = fixed\n  end\nend\n" >> "$case_dir/input.prm" ;;
      hybrid_adaptive_paper_row)
        printf 'subsection Quadrature\n  set Scheme = hybrid\nend\n' >> "$case_dir/input.prm" ;;
    esac
    ( cd "$case_dir" && "$perideal" --threads "$threads" input.prm < /dev/null ) > "$case_dir/log" 2>&1 \
      || { tail -20 "$case_dir/log"; echo "FAILED: $name (refinement $r)"; exit 1; }
    cp "$case_dir/output/history.csv" "$out/corrosion_hybrid_${name}_r$r.csv"
    cp "$case_dir/log" "$out/corrosion_hybrid_${name}_r$r.log"
    nodes=$(sed -n 's/.*diffusion: \([0-9]*\) nodes.*/\1/p' "$case_dir/log")
    steps=$(sed -n 's/.*time step [0-9.e+-]* (\([0-9]*\) steps.*/\1/p' "$case_dir/log")
    dt=$(sed -n 's/.*time step \([0-9.e+-]*\) (.*/\1/p' "$case_dir/log")
    wall=$(log_field "$case_dir/log" wall)
    loop=$(log_field "$case_dir/log" loop)
    reference="$out/corrosion_hybrid_standard_r$r.csv"
    # Against the standard run at the same times. The runs take different
    # time steps, so their history rows fall at different times: a row of
    # this run at time t is compared with the two standard rows that
    # bracket t, and its difference is its distance to the interval they
    # span (zero if it lies between them). Volume differences are relative
    # to the standard run's final pit volume. Both runs end with a row at
    # the end time.
    line=$(awk -F, -v nodes="$nodes" '
      function distance(x, a, b) { if (a > b) { z = a; a = b; b = z }
                                   return x < a ? a - x : (x > b ? x - b : 0) }
      FNR == 1 { for (k = 1; k <= NF; ++k) c[FILENAME, $k] = k; next }
      FILENAME == ARGV[1] { n0++; t0[n0] = $c[ARGV[1], "time"]; d0[n0] = $c[ARGV[1], "pit_depth"]; v0[n0] = $c[ARGV[1], "pit_volume"]; next }
      { t = $c[ARGV[2], "time"]; depth = $c[ARGV[2], "pit_depth"]; volume = $c[ARGV[2], "pit_volume"]; n = $c[ARGV[2], "converted_nodes"]
        while (q < n0 && t0[q + 1] <= t * (1 + 1e-12)) q++
        if (q > 0) { p = q < n0 && t0[q] < t * (1 - 1e-12) ? q + 1 : q
                     x = distance(depth, d0[q], d0[p]); if (x > md) md = x
                     y = distance(volume, v0[q], v0[p]); if (y > mv) mv = y
                     fv = volume - v0[q] }
        s = (c[ARGV[2], "standard_nodes"] ? $c[ARGV[2], "standard_nodes"] : nodes) / nodes; if (s > ms) ms = s }
      END { printf "%.6e,%.6e,%d,%.6e,%.6e,%.6e,%.4f,%.4f", depth, volume, n, md, mv / v0[n0], fv / v0[n0], s, ms }' \
      "$reference" "$case_dir/output/history.csv")
    echo "$name,$r,$nodes,$steps,$dt,$wall,$loop,$line" >> "$summary"
    echo "$name (refinement $r): $nodes nodes, $steps steps, $wall s (loop $loop s); depth, volume, converted, max depth diff, max volume diff, final volume diff, final and largest standard fraction: $line"
  done
done

# Every hybrid run within a cell of the standard pit depth at every row,
# and its final pit volume within 5 %.
status=0
awk -F, 'NR > 1 && $1 != "standard" { cell = 1e-6 / $2
    if ($11 > cell * (1 + 1e-9) || ($13 < 0 ? -$13 : $13) > 0.05) {
      printf "FAILED: %s (refinement %s): pit depth differs by up to %s (cell %s), final volume by %s\n", $1, $2, $11, cell, $13; bad = 1 } }
  END { exit bad }' "$summary" || status=1
if /usr/bin/python3 -c 'import matplotlib' 2> /dev/null; then
  /usr/bin/python3 "$here/plot_corrosion_hybrid.py" "$out"
else
  echo "matplotlib not importable by /usr/bin/python3: no plots"
fi
exit $status
