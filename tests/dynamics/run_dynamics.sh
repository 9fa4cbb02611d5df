#!/usr/bin/env bash
# Usage: run_dynamics.sh PERIDEAL NUMDIFF NPROCS INPUT.prm EXPECTED.output
#
# Runs an explicit-dynamics input on NPROCS MPI processes in a fresh
# directory and checks:
#  - exit code 0, a PVD time series whose every record exists with one VTU
#    piece per process, no temporary file left;
#  - the assertions written in the input as comment lines
#      # check: max_energy_drift <tolerance>
#          max |balance - balance(0)| / max (kinetic + elastic) over all rows
#          (balance = kinetic + elastic - external work: velocity Verlet
#          keeps it constant up to its O(dt^2) oscillation)
#      # check: min_new_broken_bonds <n>
#          bonds broken during the run (beyond the pre-crack) >= n
#      # check: crack_angle <x0> <y0> <min_deg> <max_deg>
#          the tracked crack tip (columns tip_x, tip_y) at the end lies in
#          the direction atan2(tip_y - y0, tip_x - x0) within [min, max]
#          degrees, at least two cells away from (x0, y0) (the larger cell
#          side of the 'Geometry' box: Lower/Upper corner, Subdivisions)
#      # check: tip_speed_below_rayleigh <E> <nu> <rho> <plane stress|plane strain|3d>
#          (closed form) the tracked crack tip (column tip_distance) never
#          runs faster than the Rayleigh speed c_R of the model's long-wave
#          elasticity: its advance between two energy rows over their time
#          interval stays below c_R, the root in (0, c_s) of
#          (2 - c^2/c_s^2)^2 = 4 sqrt(1 - c^2/c_d^2) sqrt(1 - c^2/c_s^2)
#          (bisection), c_s^2 = E / (2 rho (1 + nu)), c_d^2 = E / (rho (1 -
#          nu^2)) in plane stress and E (1 - nu) / (rho (1 + nu) (1 - 2 nu))
#          otherwise;
#      # check: dissipation_per_crack_length <G0> <min_advance> <low> <high>
#          (fracture mechanics) along a single crack (rows whose
#          front_spread is at most one cell), the energy the run has
#          dissipated, external work - kinetic - elastic (the drop of the
#          balance; the broken bonds take their energy with them), over G0
#          times the advance of the tip (tip_distance, less its first value;
#          per unit thickness in 2D) must lie in [low, high] at every row
#          once the tip has advanced min_advance (the first broken bonds
#          ahead of the tip are not yet a crack);
#      # check: lefm_initiation_ramp <a> <b> <E'> <G0> <stress rate> <tolerance>
#          (fracture mechanics) a centre crack of half-length a in a strip
#          of half-width b under a remote stress rate * t, ramped slowly:
#          at the first energy row with more broken bonds than the first
#          row, rate * t must be sigma_c = sqrt(E' G0) / (F sqrt(pi a))
#          within the relative tolerance, F = sqrt(sec(pi a / (2 b)))
#          (Feddersen, as tests/fracture/run_fracture.sh);
#      # check: verlet_energy_order <n_steps> [<every>]
#          (on 1 process) over the first n_steps steps, before any bond
#          breaks beyond the pre-crack (asserted), the balance moves only by
#          velocity Verlet's O(dt^2) term. Velocity Verlet conserves
#          K + W - (dt^2/8) sum_i m_i |a_i|^2 exactly for linear forces,
#          with the work of loads and of prescribed values counted by the
#          trapezoidal rule as the code does, so balance - balance(0) =
#          (dt^2/8)(S_n - S_0), S = sum m |a|^2, plus terms of higher order
#          in dt. The window is run again with the run's step dt and with
#          dt/2, energy rows every <every> (default: the input's 'Energy
#          every steps') and 2 <every> steps, i.e. at the same times; the
#          largest |balance - balance(0)| over the rows must fall by 4
#          within a factor 4/3, [3, 5.33]. Work left out or energies taken
#          at mismatched times, O(1) or O(dt), give a ratio near 1 or 2;
#          the higher-order terms of modes near the stability limit move
#          it above 4. The drift must exceed 1e-9 of the energies (not
#          round-off).
#  - the energy history (energies.csv: energies to 1e-8 relative, broken
#    bonds exactly) against EXPECTED.output, the same file for 1 and 2
#    processes: the partition must not change the answer (a snapshot for
#    regressions and the 1-vs-2-process check; the assertions above are the
#    verification).
set -u
perideal="$1"; numdiff="$2"; nprocs="$3"; input="$4"; expected="$5"
. "$(cd "$(dirname "$0")" && pwd)/../run_checks.sh"
name=$(basename "$input" .prm)
work="$(pwd)/${name}.np${nprocs}"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
cp "$input" input.prm
run_perideal "$perideal" "$nprocs"
rc=$?
[ $rc -eq 0 ] || { cat log; echo "FAIL: perideal exited with $rc"; exit 1; }
check_output_series "$nprocs"
csv="$dir/energies.csv"
[ -f "$csv" ] || { echo "FAIL: no $csv"; exit 1; }

drift=$(sed -n 's/^# check: max_energy_drift *//p' input.prm)
if [ -n "$drift" ]; then
  awk -F, -v tol="$drift" 'NR == 2 { b0 = $6 } NR > 1 { d = $6 - b0; if (d < 0) d = -d; if (d > m) m = d; if ($3 + $4 > e) e = $3 + $4 }
    END { m = m / e; printf "largest energy drift %.3e (tolerance %s)\n", m, tol; exit !(m <= tol) }' "$csv" \
    || { cat "$csv"; echo "FAIL: energy balance drifts"; exit 1; }
fi
min_new=$(sed -n 's/^# check: min_new_broken_bonds *//p' input.prm)
if [ -n "$min_new" ]; then
  awk -F, -v n="$min_new" 'NR == 2 { b0 = $7 } END { printf "bonds broken during the run: %d (at least %d)\n", $7 - b0, n; exit !($7 - b0 >= n) }' "$csv" \
    || { cat "$csv"; echo "FAIL: too few bonds broke"; exit 1; }
fi

# cell_size CHECK: the larger cell side of the box mesh (one subdivision
# count may stand for all directions), or a failure naming CHECK.
cell_size() {
  cell=$(awk -F= '/^ *set Lower corner *=/ { lo = $2 } /^ *set Upper corner *=/ { up = $2 }
    /^ *set Subdivisions *=/ { sub_ = $2 }
    END { n = split(lo, a, ","); split(up, b, ","); m = split(sub_, s, ","); h = 0
          for (k = 1; k <= n; ++k) { w = (b[k] - a[k]) / s[m > 1 ? k : 1]; if (w > h) h = w }
          print h }' input.prm)
  awk -v h="$cell" 'BEGIN { exit !(h > 0) }' \
    || { echo "FAIL: $1 needs a box mesh ('Geometry/Lower corner', 'Upper corner', 'Subdivisions') for the cell size"; exit 1; }
}

speed=$(sed -n 's/^# check: tip_speed_below_rayleigh *//p' input.prm)
if [ -n "$speed" ]; then
  awk -F, -v spec="$speed" 'NR == 1 { for (k = 1; k <= NF; ++k) col[$k] = k; next }
    { t = $1; d = $col["tip_distance"]
      if (NR > 2 && t > t0) { v = (d - d0) / (t - t0); if (v > vmax) { vmax = v; at = t } }
      t0 = t; d0 = d }
    function f(c) { return (2 - c * c / cs2) ^ 2 - 4 * sqrt(1 - c * c / cd2) * sqrt(1 - c * c / cs2) }
    END { split(spec, p, " "); E = p[1]; nu = p[2]; rho = p[3]
          cs2 = E / (2 * rho * (1 + nu))
          cd2 = (p[4] == "plane" && p[5] == "stress") ? E / (rho * (1 - nu * nu)) : E * (1 - nu) / (rho * (1 + nu) * (1 - 2 * nu))
          lo = 0.5 * sqrt(cs2); hi = sqrt(cs2) * (1 - 1e-12)
          for (k = 0; k < 200; ++k) { c = (lo + hi) / 2; if (f(c) * f(lo) > 0) lo = c; else hi = c }
          printf "fastest tip advance %.4g m/s (at t = %g), %.3f of the Rayleigh speed %.4g m/s (c_d %.4g, c_s %.4g)\n", vmax, at, vmax / c, c, sqrt(cd2), sqrt(cs2)
          exit !(vmax > 0 && vmax < c) }' "$csv" \
    || { echo "FAIL: the crack tip outran the Rayleigh speed (or never moved)"; exit 1; }
fi

ramp=$(sed -n 's/^# check: lefm_initiation_ramp *//p' input.prm)
if [ -n "$ramp" ]; then
  awk -F, -v spec="$ramp" 'NR == 2 { b0 = $7 } NR > 2 && !found && $7 > b0 { found = 1; t = $1 }
    END { split(spec, p, " "); a = p[1]; b = p[2]; E = p[3]; G = p[4]; rate = p[5]; tol = p[6]
          pi = atan2(0, -1); F = sqrt(1 / cos(pi * a / (2 * b)))
          lefm = sqrt(E * G) / (F * sqrt(pi * a)); s = rate * t
          printf "bonds first break at t = %g under sigma = %.5g; LEFM (Feddersen F = %.4f) %.5g: %+.2f %% (tolerance %g %%)\n", t, s, F, lefm, 100 * (s / lefm - 1), 100 * tol
          d = s / lefm - 1; if (d < 0) d = -d; exit !(found && d <= tol) }' "$csv" \
    || { echo "FAIL: initiation under the slow ramp against LEFM"; exit 1; }
fi

dissipation=$(sed -n 's/^# check: dissipation_per_crack_length *//p' input.prm)
if [ -n "$dissipation" ]; then
  cell_size dissipation_per_crack_length
  awk -F, -v spec="$dissipation" -v h="$cell" 'NR == 1 { for (k = 1; k <= NF; ++k) col[$k] = k; next }
    NR == 2 { b0 = $6; d0 = $col["tip_distance"] }
    { split(spec, p, " "); a = $col["tip_distance"] - d0
      if (a >= p[2] && $col["front_spread"] <= h * (1 + 1e-9)) {
        r = (b0 - $6) / (p[1] * a); n++
        if (n == 1 || r < rmin) rmin = r; if (n == 1 || r > rmax) rmax = r } }
    END { printf "dissipated energy over G0 x crack advance on %d rows of a single crack: %.3f to %.3f (expected in [%s, %s])\n", n, rmin, rmax, p[3], p[4]
          exit !(n >= 2 && rmin >= p[3] && rmax <= p[4]) }' "$csv" \
    || { echo "FAIL: the energy dissipated per crack length is not G0"; exit 1; }
fi

angle=$(sed -n 's/^# check: crack_angle *//p' input.prm)
if [ -n "$angle" ]; then
  cell_size crack_angle
  awk -F, -v spec="$angle" -v h="$cell" 'NR == 1 { for (k = 1; k <= NF; ++k) col[$k] = k; next }
    { x = $col["tip_x"]; y = $col["tip_y"] }
    END { split(spec, a, " "); dx = x - a[1]; dy = y - a[2]
          deg = atan2(dy, dx) * 45 / atan2(1, 1); r = sqrt(dx * dx + dy * dy)
          printf "crack tip at (%g, %g): %.1f deg from (%s, %s), %g away (expected %s to %s deg, at least two cells = %g away)\n", x, y, deg, a[1], a[2], r, a[3], a[4], 2 * h
          exit !(deg >= a[3] && deg <= a[4] && r >= 2 * h) }' "$csv" \
    || { echo "FAIL: crack angle"; exit 1; }
fi

order=$(sed -n 's/^# check: verlet_energy_order *//p' input.prm)
if [ -n "$order" ] && [ "$nprocs" -eq 1 ]; then
  dt=$(sed -n 's/.* time step \([0-9.eE+-]*\) s (.*/\1/p' log | head -1)
  read -r order every <<< "$order"
  [ -n "$every" ] || every=$(sed -n 's/^ *set Energy every steps *= *//p' input.prm)
  every=${every:-10}
  [ -n "$dt" ] || { cat log; echo "FAIL: no time step in the log"; exit 1; }
  for k in 1 2; do
    # The window as End time = n_steps dt, its step End time / (k n_steps)
    # (a whole number of steps), energy rows every k * every steps.
    awk -v dt="$dt" -v n="$order" -v k="$k" -v every="$every" '
      BEGIN { end = n * dt; printf "%.17g %.17g %d\n", end, end / (k * n), k * every }' > window
    read -r end step rows < window
    sed -E '/^ *set (End time|Time step|Energy every steps|Output every steps|Output interval|Write VTU|Directory) *=/d' input.prm \
      | sed -e "s/^\( *\)subsection explicit dynamics *$/&\n\1  set End time = $end\n\1  set Time step = $step\n\1  set Energy every steps = $rows/" \
            -e "s/^\( *\)subsection Output *$/&\n\1  set Write VTU = false\n\1  set Directory = order$k/" > order$k.prm
    "$perideal" order$k.prm > order$k.log 2>&1 \
      || { cat order$k.log; echo "FAIL: the dt/$k window run failed"; exit 1; }
  done
  awk -F, 'FNR == 1 { ++run; next }
    FNR == 2 { b0[run] = $6; k0[run] = $7 }
    { d = $6 - b0[run]; if (d < 0) d = -d; if (d > m[run]) m[run] = d
      if ($3 + $4 > e[run]) e[run] = $3 + $4; if ($7 != k0[run]) broke[run] = 1; n[run]++ }
    END { ratio = m[2] > 0 ? m[1] / m[2] : 0
          printf "energy balance over the first steps: largest drift %.4e at dt, %.4e at dt/2 (ratio %.3f, expected 4 within [3, 5.33]; %d and %d rows)\n", m[1], m[2], ratio, n[1], n[2]
          if (broke[1] || broke[2]) { print "bonds broke in the window: make it shorter"; exit 1 }
          if (n[1] < 2 || n[1] != n[2]) { print "the two runs must have the same rows, at least two"; exit 1 }
          if (m[1] <= 1e-9 * e[1]) { print "the drift is round-off: nothing to compare"; exit 1 }
          exit !(ratio >= 3 && ratio <= 16 / 3) }' order1/energies.csv order2/energies.csv \
    || { echo "FAIL: the energy balance does not move as O(dt^2) before bonds break"; exit 1; }
fi

# Energies to 1e-8 relative; the broken-bond counts (integers) exactly.
if ! "$numdiff" -q -r 1e-8 -a 1e-14 -s ' \t\n,' "$csv" "$expected" > /dev/null; then
  echo "FAIL: energy history differs from $expected"; diff "$csv" "$expected"; exit 1
fi
if ! diff <(cut -d, -f2,7 "$csv") <(cut -d, -f2,7 "$expected") > /dev/null; then
  echo "FAIL: broken bonds differ from $expected"; exit 1
fi
grep "step .*/" log | tail -1
echo "OK"
