#!/usr/bin/env bash
# Winkler's L-shaped concrete panel with brittle bonds (issue 24): where the
# crack starts and runs, and the peak load against the experiment, as the
# grid (and with it delta = 3h) is refined.
#
#   bash bench/l_panel/run_l_panel.sh [--quick] [--output-dir DIR]
#
# The input is bench/l_panel/l_panel.prm (500 x 500 mm, 250 x 250 mm
# cut-out, 100 mm thick; E = 25.85 GPa, nu = 0.18, G0 = 89 J/m^2; LPS, plane
# stress, m = 3), with N cells per 500 mm (h = 0.5/N m): the mesh from
# make_l_panel_mesh.py, the load point kept two nodes wide. The experiment
# (Winkler 2001, test series A, as digitised in the public benchmark
# PSAAPGroupLinder/lShapedPanelBenchmark) peaks at 7.22 kN at a load-point
# displacement of 0.21 mm. Writes DIR/l_panel.csv (cells, h, delta, nodes,
# the load at the first broken bond and the peak load in kN for the 100 mm
# thickness, the peak over the experiment's, the crack's height half-way
# across the vertical arm (x = 0.125 m) and where it ends at 1 mm, the load
# there, wall time, steps, iterations), DIR/crack_path_N.csv, DIR/logs/ and
# with matplotlib DIR/load_displacement.png and DIR/crack_path.png. DIR
# defaults to results/l_panel. SIZES overrides N (default 50 100 200;
# --quick: 50). Fails unless at every N the crack starts within one cell of
# the re-entrant corner and runs at least half-way across the vertical arm.
set -euo pipefail
cd "$(dirname "$0")/../.."

source bench/driver_study.sh
driver_study_setup results/l_panel "$@"
here=bench/l_panel
if [ $quick -eq 1 ]; then sizes="${SIZES:-50}"; else sizes="${SIZES:-50 100 200}"; fi

csv="$out/l_panel.csv"
echo "cells,h,delta,nodes,load_first_break_kN,load_peak_kN,peak_over_experiment,crack_y_mid_arm,crack_end_x,load_at_1mm_kN,wall_seconds,steps,iterations" > "$csv"
status=0
for n in $sizes; do
  name="l_panel_$n"; dir="$out/logs/$name"
  mkdir -p "$dir"
  /usr/bin/python3 "$here/make_l_panel_mesh.py" 0.5 "$n" "$dir/l_panel.inp" > /dev/null
  # The boxes scaled to h: the load point (two nodes at x = 0.47), the held
  # bottom row, the no-fail regions about them.
  awk -v n="$n" '
    function box(x0, y0, x1, y1) { return sprintf("%.10g, %.10g, %.10g, %.10g", x0, y0, x1, y1) }
    BEGIN { h = 0.5 / n; load = box(0.47 - h, 0.25, 0.47 + h, 0.25 + h) }
    /set Mesh file =/ { print "  set Mesh file = " dir "/l_panel.inp"; next }
    /set Dirichlet boxes =/ { print "  set Dirichlet boxes = " load "; " box(0, 0, 0.25, h); next }
    /set Reaction boxes =/ { print "  set Reaction boxes = " load; next }
    /set No-fail boxes =/ { print "  set No-fail boxes = " box(0.47 - 4 * h, 0.25, 0.5, 0.25 + 4 * h) "; " box(0, 0, 0.25, 4 * h); next }
    /set Directory = output/ { print "  set Directory = " dir; next }
    { print }' dir="$dir" "$here/l_panel.prm" > "$out/logs/$name.prm"
  printf 'N = %4s (h = %s mm): ' "$n" "$(awk -v n="$n" 'BEGIN { print 500 / n }')"
  "$perideal" "$out/logs/$name.prm" > "$out/logs/$name.log" 2>&1 || { tail -20 "$out/logs/$name.log"; exit 1; }
  /usr/bin/python3 "$here/crack_path.py" "$dir" > "$out/crack_path_$n.csv"
  wall=$(sed -n 's/^total wall time \([0-9.e+-]*\) s.*/\1/p' "$out/logs/$name.log")
  awk -F, -v n="$n" -v wall="$wall" -v path="$out/crack_path_$n.csv" -v csv="$csv" '
    BEGIN { h = 0.5 / n; first_x = -1; mid = "nan"
            while ((getline line < path) > 0) { if (line ~ /^x/) continue
              split(line, p, ","); if (first_x < 0) { first_x = p[1]; first_y = p[2] }; last_x = p[1]; last_y = p[2]
              d = p[1] - 0.125; if (d < 0) d = -d; if (d <= h / 2 + 1e-12 && mid == "nan") mid = p[2] } }
    NR > 1 { f = $4 * 0.1 / 1000; if (f < 0) f = -f; if (f > peak) peak = f; it += $6; steps++; end = f
             if (!found && $5 > 0) { found = 1; first = f } }
    END { printf "%d,%.6g,%.6g,%d,%.4f,%.4f,%.4f,%s,%s,%.4f,%s,%d,%d\n", n, h, 3 * h, 3 * n * n / 4, first, peak, peak / 7.22, mid, last_x, end, wall, steps, it >> csv
          ok = first_x >= 0.25 - h && first_y >= 0.25 - h && first_y <= 0.25 + h && last_x < 0.125
          printf "first break %.3f kN, peak %.3f kN (experiment 7.22 kN, ratio %.2f), %.3f kN at 1 mm; crack from (%s, %s) to (%s, %s); %s s\n", first, peak, peak / 7.22, end, first_x, first_y, last_x, last_y, wall
          exit !ok }' "$dir/load_displacement.csv" \
    || { echo "FAIL: at N = $n the crack does not start at the corner and cross half the arm"; status=1; }
done
plot_if_possible "$here/plot_l_panel.py" "$csv" "$out"
exit $status
