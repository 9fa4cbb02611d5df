#!/usr/bin/env bash
# Usage: run_fracture.sh PERIDEAL NUMDIFF NPROCS INPUT.prm EXPECTED.output
#
# Runs a load-stepped quasi-static fracture input on NPROCS MPI processes in
# a fresh directory and checks:
#  - exit code 0, a PVD damage series whose every record exists with one
#    VTU piece per process, no temporary file left, a load-displacement CSV
#    with the columns of the issue (step,time,reaction_x,reaction_y,
#    broken_bonds,iterations);
#  - the assertions written in the input as comment lines
#      # check: lefm_initiation <a> <b> <E'> <G0> <tolerance>
#          (fracture mechanics) a centre crack of half-length a in a strip
#          of half-width b under a remote stress sigma (the reaction of the
#          top grip divided by 2b, per unit thickness): the load of the
#          first step at which bonds break beyond the pre-crack, at its
#          first equilibrium (before any bond breaks, so the linear
#          reaction / t of the first step times its t; the step control
#          finds it to 'Critical stretch tolerance'), must be
#          sigma_c = sqrt(E' G0) / (F sqrt(pi a)) within the relative
#          tolerance, F = sqrt(sec(pi a / (2 b))) (Feddersen's finite-width
#          factor, within 0.3 % of Tada's for a/b <= 0.7);
#      # check: lefm_senb <a> <W> <S> <E'> <G0> <tolerance>
#          (fracture mechanics) a single-edge-notched beam of depth W, notch
#          depth a, span S, in three-point bending (the reaction_y of the
#          load point, per unit thickness): the load at which bonds first
#          break beyond the pre-crack (as for lefm_initiation) must be
#          P_c = sqrt(E' G0) W^(3/2) / (S f(a/W)) within the relative
#          tolerance, f the ASTM E399 geometry factor for S/W = 4 (Srawley
#          1976, within 0.5 % of the collocation results for all a/W). The
#          peak load is printed beside it, not checked (it lies above P_c:
#          doc/quasi-static-fracture.md);
#      # check: linear_before_initiation <tolerance>
#          (closed form) before bonds break the problem is linear and the
#          load proportional to t, so reaction_y / t is the same at every
#          step to the tolerance (the solver's): the step control, the warm
#          start and the reaction add nothing;
#      # check: complete_failure
#          the log reports complete failure and the last reaction is below
#          1 % of the peak;
#      # check: unstable_growth
#          the log reports unstable growth with the critical load;
#      # check: same_curve_as <other.output> <tolerance>
#          the same steps, times and broken bonds as the expected history
#          of another input (the same problem with another solver), and
#          reactions within the tolerance times the peak reaction;
#      # check: held <nodes> <directions>
#          (counted by hand from the geometry of the pre-cracks) the first
#          step's progress line holds exactly <nodes> nodes without bonds
#          and <directions> directions without stiffness (a node whose
#          bonds left all lie across a direction), and the run goes on;
#      # check: bitwise
#          the CSV is byte-identical to EXPECTED.output (written on one
#          process): the iterates do not depend on the partition;
#  - the load-displacement file against EXPECTED.output, the same file for
#    1 and 2 processes: broken bonds at every step exactly, reactions to
#    1e-6 relative (a snapshot for regressions and the 1-vs-2-process check:
#    the Krylov solves agree to their tolerance, not bitwise; the assertions
#    above are the verification).
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
check_output_series "$nprocs" damage
csv="$dir/load_displacement.csv"
[ -f "$csv" ] || { echo "FAIL: no $csv"; exit 1; }
[ "$(head -1 "$csv")" = "step,time,reaction_x,reaction_y,broken_bonds,iterations" ] \
  || { head -1 "$csv"; echo "FAIL: columns of $csv"; exit 1; }

lefm=$(sed -n 's/^# check: lefm_initiation *//p' input.prm)
if [ -n "$lefm" ]; then
  awk -F, -v spec="$lefm" 'NR == 2 { b0 = $5; k = $4 / $2 } NR > 1 && !found && $5 > b0 { found = 1; r = k * $2; t = $2 }
    END { split(spec, p, " "); a = p[1]; b = p[2]; E = p[3]; G = p[4]; tol = p[5]
          pi = atan2(0, -1); F = sqrt(1 / cos(pi * a / (2 * b)))
          lefm = sqrt(E * G) / (F * sqrt(pi * a)); s = r / (2 * b)
          printf "bonds first break at t = %g under sigma = %.5g; LEFM (Feddersen F = %.4f) %.5g: %+.2f %% (tolerance %g %%)\n", t, s, F, lefm, 100 * (s / lefm - 1), 100 * tol
          d = s / lefm - 1; if (d < 0) d = -d; exit !(found && d <= tol) }' "$csv" \
    || { cat "$csv"; echo "FAIL: initiation against LEFM"; exit 1; }
fi
senb=$(sed -n 's/^# check: lefm_senb *//p' input.prm)
if [ -n "$senb" ]; then
  awk -F, -v spec="$senb" 'NR == 2 { b0 = $5; k = ($4 < 0 ? -$4 : $4) / $2 } NR > 1 { r = $4 < 0 ? -$4 : $4; if (r > peak) peak = r
      if (!found && $5 > b0) { found = 1; init = k * $2; t = $2 } }
    END { split(spec, p, " "); a = p[1]; W = p[2]; S = p[3]; E = p[4]; G = p[5]; ti = p[6]
          al = a / W
          f = 3 * sqrt(al) * (1.99 - al * (1 - al) * (2.15 - 3.93 * al + 2.7 * al * al)) / (2 * (1 + 2 * al) * (1 - al) ^ 1.5)
          lefm = sqrt(E * G) * W ^ 1.5 / (S * f)
          di = init / lefm - 1; dp = peak / lefm - 1
          printf "bonds first break at t = %g under P = %.5g; LEFM (f(%.3g) = %.4f) %.5g: %+.2f %% (tolerance %g %%); peak %.5g (%+.2f %%, not checked)\n", t, init, al, f, lefm, 100 * di, 100 * ti, peak, 100 * dp
          if (di < 0) di = -di
          exit !(found && di <= ti) }' "$csv" \
    || { cat "$csv"; echo "FAIL: three-point bending against LEFM"; exit 1; }
fi
linear=$(sed -n 's/^# check: linear_before_initiation *//p' input.prm)
if [ -n "$linear" ]; then
  awk -F, -v tol="$linear" 'NR == 2 { b0 = $5; k0 = $4 / $2 } NR > 1 && $5 == b0 { n++; d = ($4 / $2) / k0 - 1; if (d < 0) d = -d; if (d > m) m = d }
    END { printf "reaction / t before bonds break: %d steps, largest relative spread %.2e (tolerance %g)\n", n, m, tol
          exit !(n >= 2 && m <= tol) }' "$csv" \
    || { cat "$csv"; echo "FAIL: the response before initiation is not linear"; exit 1; }
fi
if grep -q "^# check: complete_failure" input.prm; then
  grep -q "complete failure at t" log || { cat log; echo "FAIL: no complete failure reported"; exit 1; }
  awk -F, 'NR > 1 { r = $4 < 0 ? -$4 : $4; if (r > p) p = r; last = r }
    END { printf "last reaction %.4g, peak %.4g\n", last, p; exit !(last < 0.01 * p) }' "$csv" \
    || { echo "FAIL: the last reaction is not below 1 % of the peak"; exit 1; }
fi
if grep -q "^# check: unstable_growth" input.prm; then
  grep -q "unstable crack growth at t = .*critical load: reaction" log \
    || { cat log; echo "FAIL: no unstable growth reported"; exit 1; }
fi

same=$(sed -n 's/^# check: same_curve_as *//p' input.prm)
if [ -n "$same" ]; then
  set -- $same
  other="$(dirname "$input")/$1"
  awk -F, -v tol="$2" 'NR == FNR { if (FNR > 1) { t[FNR] = $2; r[FNR] = $4; b[FNR] = $5; a = $4 < 0 ? -$4 : $4; if (a > p) p = a }; n = FNR; next }
    FNR > 1 { if ($2 != t[FNR] || $5 != b[FNR]) { bad = 1 }
              d = ($4 - r[FNR]) / p; if (d < 0) d = -d; if (d > m) m = d; k = FNR }
    END { printf "against %s: %d of %d rows, same steps and broken bonds: %s, largest reaction difference %.2e of the peak (tolerance %g)\n", ARGV[1], k - 1, n - 1, bad ? "no" : "yes", m, tol
          exit !(!bad && k == n && m <= tol) }' "$other" "$csv" \
    || { echo "FAIL: the load-displacement curve differs from $other"; exit 1; }
fi
held=$(sed -n 's/^# check: held *//p' input.prm)
if [ -n "$held" ]; then
  set -- $held
  first=$(grep -m1 "step 1, t = " log)
  echo "$first" | grep -q ", $1 node(s) without bonds held" \
    && echo "$first" | grep -q ", $2 direction(s) without stiffness held" \
    || { echo "$first"; echo "FAIL: not $1 node(s) and $2 direction(s) held at step 1"; exit 1; }
  echo "held at step 1: $1 node(s) without bonds, $2 direction(s) without stiffness"
fi
if grep -q "^# check: bitwise" input.prm; then
  cmp "$csv" "$expected" > /dev/null \
    || { diff "$csv" "$expected" | head; echo "FAIL: not byte-identical to $expected"; exit 1; }
  echo "byte-identical to $(basename "$expected")"
fi

# Reactions to 1e-6 relative; the broken-bond counts exactly (numdiff needs
# seekable files).
cut -d, -f1-5 "$csv" > result.cut; cut -d, -f1-5 "$expected" > expected.cut
if ! "$numdiff" -q -r 1e-6 -a 1e-3 -s ' \t\n,' result.cut expected.cut > /dev/null; then
  echo "FAIL: load-displacement history differs from $expected"; diff "$csv" "$expected"; exit 1
fi
if ! diff <(cut -d, -f1,2,5 "$csv") <(cut -d, -f1,2,5 "$expected") > /dev/null; then
  echo "FAIL: steps or broken bonds differ from $expected"; diff <(cut -d, -f1,2,5 "$csv") <(cut -d, -f1,2,5 "$expected"); exit 1
fi
tail -n 1 "$csv"
echo "OK"
