#!/usr/bin/env bash
# Usage: bad_input.sh PERIDEAL
#
# Bad input to the explicit dynamics problem type: each case must exit
# non-zero (on 1 and on 2 processes, without hanging), print a message that
# names the offending entry and its value, and leave no output that looks
# complete. An unstable run must stop with the step and the node named and
# keep the output written before it.
set -u
perideal="$1"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
. "$(cd "$(dirname "$0")" && pwd)/../bad_input_checks.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

work="$(pwd)/bad_input"
rm -rf "$work" && mkdir -p "$work" && cd "$work"

cat > base.prm <<'PRM'
set Dimension = 2
set Problem type = explicit dynamics
subsection Geometry
  set Lower corner = 0, 0
  set Upper corner = 1, 0.5
  set Subdivisions = 20, 10
end
subsection Material model
  set Model = bond-based
  subsection bond-based
    set Poisson's ratio = 0.25
    set Density = 1000
    set Critical stretch = 0.01
  end
end
subsection explicit dynamics
  set End time = 1e-4
  set Pre-cracks = 0, 0.25, 0.5, 0.25
  subsection Initial velocity
    set Variable names = x,y,t
    set Function expression = 0; y > 0.25 ? 1 : -1
  end
end
subsection Output
  set Directory = out
end
PRM
"$perideal" base.prm > base.log 2>&1 || { cat base.log; fail "the valid base input failed"; }
[ -f out/solution.pvd ] && [ -f out/energies.csv ] || fail "the valid base input wrote no out/solution.pvd or energies.csv"
rm -rf out

# expect_error "sed expression" "substring of the message" [nprocs]
expect_error() {
  local edit="$1" expected="$2" nprocs="${3:-1}" out rc
  sed -e "$edit" base.prm > case.prm
  rm -rf out
  if [ "$nprocs" -eq 1 ]; then
    out=$(timeout 120 "$perideal" case.prm 2>&1); rc=$?
  else
    out=$(timeout 120 mpirun --oversubscribe -np "$nprocs" "$perideal" case.prm 2>&1); rc=$?
  fi
  check_clean_exit "$rc" "$out" "$edit (on $nprocs processes)"
  check_names_entry_and_value "$expected" "$edit"
  grep -qF -- "$expected" <<<"$out" || { echo "$out"; fail "no '$expected' in the message for: $edit"; }
  [ -e out/solution.pvd ] && fail "a time series was left behind for: $edit"
  [ -e out/energies.csv ] && fail "an energy file was left behind for: $edit"
  return 0
}

for np in 1 2; do
  expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Time step = 1e-3/' \
    "Invalid value '0.001' for the parameter 'explicit dynamics/Time step': the step exceeds the stability bound" $np
  expect_error 's/set Pre-cracks = 0, 0.25, 0.5, 0.25/set Pre-cracks = 5, 5, 6, 6/' \
    "Invalid value '5, 5, 6, 6' for the parameter 'explicit dynamics/Pre-cracks': no bond crosses the pre-cracks" $np
  # Regions that hold no node: they would silently do nothing.
  expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set No-fail boxes = 2, 2, 3, 3/' \
    "Invalid value '2, 2, 3, 3' for the parameter 'explicit dynamics/No-fail boxes': box 1 holds no node centre" $np
  expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set No-fail boundary ids = 2\n  set No-fail layer thickness = 0.01/' \
    "Invalid value '0.01' for the parameter 'explicit dynamics/No-fail layer thickness': the no-fail layer of boundary id 2 holds no node centre" $np
  expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Boundary conditions\n  set Dirichlet boxes = 0, 0, 0.05, 0.5; 0.3, 0.3, 0.31, 0.31\nend/' \
    "Invalid value '0, 0, 0.05, 0.5; 0.3, 0.3, 0.31, 0.31' for the parameter 'Boundary conditions/Dirichlet boxes': box 2 holds no node centre" $np
done
expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set No-fail boundary ids = 7/' \
  "Invalid value '7' for the parameter 'explicit dynamics/No-fail boundary ids': boundary id 7 does not occur in the mesh"
expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Crack tip origin = 0.5, 0.25; 0, 0/' \
  "Invalid value '0.5, 0.25; 0, 0' for the parameter 'explicit dynamics/Crack tip origin': give one point"
expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Crack tip origin = 0.5/' \
  "Invalid value '0.5' for the parameter 'explicit dynamics/Crack tip origin': a point is 'x, y'"
expect_error 's/set Pre-cracks = 0, 0.25, 0.5, 0.25/set Pre-cracks = 0, 0.25, 0.5/' \
  "Invalid value '0, 0.25, 0.5' for the parameter 'explicit dynamics/Pre-cracks': a 2D pre-crack is a segment"
expect_error 's/set Pre-cracks = 0, 0.25, 0.5, 0.25/set Pre-cracks = 0, 0.25, half, 0.25/' \
  "Invalid value '0, 0.25, half, 0.25' for the parameter 'explicit dynamics/Pre-cracks': 'half' in '0, 0.25, half, 0.25' is not a number"
expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set No-fail boxes = 1, 0, 0, 1/' \
  "Invalid value '1, 0, 0, 1' for the parameter 'explicit dynamics/No-fail boxes': give the lower corner first"
expect_error 's/  set End time = 1e-4/  set End time = 1e-4\n  set Load history = t +* 2/' \
  "Invalid value 't +* 2' for the parameter 'explicit dynamics/Load history'"
unnamed="source/models/model.cc names 'Fracture energy', not 'Material model/bond-based/Fracture energy'" \
expect_error 's/    set Critical stretch = 0.01/    set Critical stretch = 0.01\n    set Fracture energy = 10/' \
  "Invalid value '10' for the parameter 'Fracture energy': give either 'Critical stretch' or 'Fracture energy'"
unnamed="source/models/model.cc names 'Fracture energy', not 'Material model/linear peridynamic solid/Fracture energy'" \
expect_error "s/  set Model = bond-based/  set Model = linear peridynamic solid/; s/  subsection bond-based/  subsection linear peridynamic solid/; s/    set Critical stretch = 0.01/    set Fracture energy = 10/" \
  "Invalid value '10' for the parameter 'Fracture energy': this model has no relation"
expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Boundary treatment\n  set Treatment = fictitious layer\nend/' \
  "Invalid value 'fictitious layer' for the parameter 'Boundary treatment/Treatment': explicit dynamics supports the 'none' treatment only"

# An unstable run stops with the step and the node named; what it wrote
# before stays complete (every record the time series names exists).
for np in 1 2; do
  sed -e 's/  set End time = 1e-4/  set End time = 0.1\n  set Time step = 1e-3\n  set Allow unstable time step = true\n  set Output every steps = 20/' \
      -e 's/set Critical stretch = 0.01/set Critical stretch = 0/' base.prm > unstable.prm
  rm -rf out
  out=$(timeout 120 mpirun --oversubscribe -np $np "$perideal" unstable.prm 2>&1); rc=$?
  check_clean_exit "$rc" "$out" "the unstable run on $np processes"
  grep -qE "not finite at step [0-9]+" <<<"$out" || { echo "$out" | tail -5; fail "unstable run: no step named"; }
  [ -f out/solution.pvd ] || fail "unstable run: the earlier output is gone"
  for record in $(sed -n 's/.*file="\([^"]*\)".*/\1/p' out/solution.pvd); do
    [ -f "out/$record" ] || fail "unstable run: $record named but missing"
  done
  ls out/*.tmp > /dev/null 2>&1 && fail "unstable run: temporary files remain"
done

if [ "$failures" -eq 0 ]; then echo "OK: all bad inputs rejected with clear messages"; else exit 1; fi
