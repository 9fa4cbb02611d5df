#!/usr/bin/env bash
# Usage: energy_monitor.sh PERIDEAL CRACK_LPS_3D.prm NPROCS
#
# Kind: assertion against a physical law (an energy balance that broken
# bonds can only lower). The state-based fracture run of crack_lps_3d.prm
# near incompressibility (nu = 0.4999999) makes energy when bonds break
# (doc/explicit-dynamics.md, "LPS near incompressibility"): its balance
# rose from 0.0055 J to 9e4 J and the run exited 0 (issue 26, class 10).
# The energy monitor must stop it with a clear error naming the step and
# the entry to change, and leave the output it wrote before complete; with
# 'Allow energy growth = true' the same run must warn exactly once.
# The same input at nu = 0.3 runs to the end (dynamics/crack_lps_3d).
set -u
perideal="$1"; input="$2"; nprocs="$3"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

work="$(pwd)/energy_monitor.np${nprocs}"
rm -rf "$work" && mkdir -p "$work" && cd "$work"

grep -q "set Poisson's ratio = 0.3$" "$input" || { echo "FAIL: $input has no 'Poisson's ratio = 0.3' line"; exit 1; }
sed -e "s/set Poisson's ratio = 0.3$/set Poisson's ratio = 0.4999999/" \
    -e 's/set End time = .*/set End time = 2.5e-6/' "$input" > nu.prm

out=$(timeout 240 mpirun --oversubscribe -np "$nprocs" "$perideal" nu.prm 2>&1); rc=$?
[ $rc -ne 0 ] && [ $rc -ne 124 ] || { echo "$out" | tail -5; fail "exit code $rc: the run that makes energy was not stopped"; }
grep -qE "The energy balance \(kinetic \+ elastic energy - external work\) rose to .* at step [0-9]+" <<<"$out" \
  || { echo "$out" | tail -5; fail "no energy-balance message"; }
grep -qF "'explicit dynamics/Energy balance tolerance' = 0.1" <<<"$out" || fail "the message does not name the tolerance entry"
dir=$(sed -n 's/^ *set Directory *= *//p' nu.prm); dir=${dir:-output}
[ -f "$dir/energies.csv" ] || fail "the energy history written before is gone"
ls "$dir"/*.tmp > /dev/null 2>&1 && fail "temporary files remain"

sed -i 's/set End time = 2.5e-6/set End time = 2.5e-6\n  set Allow energy growth = true/' nu.prm
rm -rf "$dir"
out=$(timeout 240 mpirun --oversubscribe -np "$nprocs" "$perideal" nu.prm 2>&1); rc=$?
[ "$(grep -c "Warning: The energy balance" <<<"$out")" -eq 1 ] || { echo "$out" | tail -5; fail "'Allow energy growth = true': not exactly one warning"; }

# A load that starts late (the velocities at t >= 1 us), which the monitor
# stopped twice over before (kind: a correct run that must not be stopped,
# checked by its exit code, the absence of the message and the bonds it
# breaks):
#  - before the load, the energies are the noise of the positions'
#    round-off (4e-28 to 1e-27 J here), whose relative rise (0.6) means
#    nothing; the monitor judges them against its round-off energy
#    (1/2) lambda_max sum m (100 eps |x|_max)^2 (3.6e-20 J here);
#  - at the jump, the prescribed nodes move by dt v(t - dt/2) = 0 and get
#    v = 5 m/s: the reactions' work m (v1 - v0)/dt (u1 - u0) was 0 and the
#    balance rose by their whole kinetic energy (0.81 of the energies);
#    the work is now 1/2 m (v1^2 - v0^2) less the bond forces' work.
grep -q "set Function expression = 0; y > 0.005 ? 5 : -5; 0" "$input" \
  || { echo "FAIL: $input does not prescribe the velocities this test delays"; exit 1; }
sed -e 's/set Function expression = 0; y > 0.005 ? 5 : -5; 0/set Function expression = 0; t < 1e-6 ? 0 : (y > 0.005 ? 5 : -5); 0/' \
    -e 's/set End time = .*/set End time = 7e-6/' "$input" > late.prm
rm -rf "$dir"
out=$(timeout 240 mpirun --oversubscribe -np "$nprocs" "$perideal" late.prm 2>&1); rc=$?
[ $rc -eq 0 ] || { echo "$out" | tail -5; fail "a load that starts at 1 us: exit code $rc"; }
grep -q "energy balance" <<<"$out" && { echo "$out" | grep "energy balance" | head -2; fail "a load that starts at 1 us: the monitor stopped or warned"; }
broken=$(awk -F, 'NR > 1 { b = $NF } END { print b + 0 }' "$dir/energies.csv" 2>/dev/null)
first=$(awk -F, 'NR == 2 { print $NF + 0 }' "$dir/energies.csv" 2>/dev/null)
[ -n "$broken" ] && [ -n "$first" ] && [ $((broken - first)) -ge 100 ] \
  || fail "a load that starts at 1 us: the crack did not grow (broken bonds ${first:-?} -> ${broken:-?})"

if [ "$failures" -eq 0 ]; then echo "OK: the energy monitor stops a run that makes energy, and not a correct run whose load starts late"; else exit 1; fi
