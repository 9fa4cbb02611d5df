#!/usr/bin/env bash
# Usage: bad_input.sh PERIDEAL
#
# Bad input to the diffusion problem type: each case must exit non-zero (on
# 1 and on 2 processes, without hanging), print a message that names the
# offending entry and its value, and leave no output that looks complete. A
# run whose concentration turns non-finite must stop with the step and the
# node named and keep the output written before it.
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
set Problem type = diffusion
subsection Geometry
  set Lower corner = 0, 0
  set Upper corner = 1, 0.5
  set Subdivisions = 20, 10
end
subsection diffusion
  set Diffusivity = 1
  set End time = 1e-3
  set Dirichlet boundary ids = 0
  subsection Initial concentration
    set Function expression = x
  end
  subsection Source
    set Function expression = 1
  end
end
subsection Output
  set Directory = out
end
PRM
"$perideal" base.prm > base.log 2>&1 || { cat base.log; fail "the valid base input failed"; }
[ -f out/solution.pvd ] && [ -f out/history.csv ] || fail "the valid base input wrote no out/solution.pvd or history.csv"
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
  [ -e out/history.csv ] && fail "a history file was left behind for: $edit"
  return 0
}

for np in 1 2; do
  expect_error 's/set End time = 1e-3/set End time = 1e-3\n  set Time step = 1e-2/' \
    "Invalid value '0.01' for the parameter 'diffusion/Time step': forward Euler is stable only up to" $np
  expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Dirichlet layer thickness = 0.01/' \
    "Invalid value '0.01' for the parameter 'diffusion/Dirichlet layer thickness': the layer of boundary id 0 holds no node centre" $np
done
expect_error 's/set Diffusivity = 1/set Diffusivity = -2/' \
  "Invalid value '-2' for the parameter 'diffusion/Diffusivity': give a diffusivity > 0"
expect_error 's/set Diffusivity = 1/set Diffusivity = 1\n  set Flux exponent = 4/' \
  "Invalid value '4' for the parameter 'diffusion/Flux exponent': q must be 0, 1, 2 or 3"
expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0, 9/' \
  "Invalid value '0, 9' for the parameter 'diffusion/Dirichlet boundary ids': boundary id 9 does not occur in the mesh"
expect_error 's/set Dirichlet boundary ids = 0/set Time stepping = steady state/' \
  "Invalid value '' for the parameter 'diffusion/Dirichlet boundary ids': a steady state needs prescribed values"
expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Time stepping = implicit/' \
  "Invalid value '0' for the parameter 'diffusion/Time step': implicit time stepping needs a time step > 0"
expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Dirichlet layer values = mirror\n  set Time stepping = implicit\n  set Time step = 1e-4/' \
  "Invalid value 'mirror' for the parameter 'diffusion/Dirichlet layer values': mirror layers need 'Time stepping = explicit'"
expect_error 's/set End time = 1e-3/set End time = -1/' \
  "Invalid value '-1' for the parameter 'diffusion/End time'"
expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Safety factor = 1.5/' \
  "Invalid value '1.5' for the parameter 'diffusion/Safety factor'"
expect_error 's/set Dimension = 2/set Dimension = 2\nsubsection Boundary treatment\n  set Treatment = fictitious layer\nend/' \
  "Invalid value 'fictitious layer' for the parameter 'Boundary treatment/Treatment': the diffusion problem supports the 'none' treatment only"

# Corrosion.
cat > corrosion.prm <<'PRM'
set Dimension = 2
set Problem type = diffusion
subsection Geometry
  set Lower corner = 0, -10e-6
  set Upper corner = 20e-6, 10e-6
  set Subdivisions = 20, 20
end
subsection diffusion
  set Model = corrosion
  set Diffusivity = 8.6e-10
  set End time = 0.1
  set Dirichlet boundary ids = 3
  subsection corrosion
    set Saturation concentration = 4600
    set Current density = 5.1e3
    subsection Initial phase
      set Function expression = y > 0 ? 0 : 1
    end
  end
end
subsection Output
  set Directory = out
end
PRM
"$perideal" corrosion.prm > corrosion.log 2>&1 || { cat corrosion.log; fail "the valid corrosion input failed"; }
rm -rf out
cp base.prm base.orig && cp corrosion.prm base.prm
for np in 1 2; do
  expect_error 's/      set Function expression = y > 0 ? 0 : 1/      set Function expression = 1/' \
    "Invalid value '1' for the parameter 'diffusion/corrosion/Initial phase/Function expression': no node starts as electrolyte" $np
  expect_error 's/      set Function expression = y > 0 ? 0 : 1/      set Function expression = y > 0 ? 0 : 3/' \
    "Invalid value 'y > 0 ? 0 : 3' for the parameter 'diffusion/corrosion/Initial phase/Function expression': the initial phase must be 0 (electrolyte), 1 (metal) or 2 (passive film) at every node" $np
done
expect_error 's/set Saturation concentration = 4600/set Saturation concentration = 2e5/' \
  "Invalid value '2e5' for the parameter 'diffusion/corrosion/Saturation concentration': give 0 < C_sat < 'Solid concentration' (142900)"
expect_error 's/set Current density = 5.1e3/set Current density = -1/' \
  "Invalid value '-1' for the parameter 'diffusion/corrosion/Current density': give a current density > 0"
expect_error 's/set Current density = 5.1e3/set Interface model = interface diffusivity/' \
  "Invalid value '0' for the parameter 'diffusion/corrosion/Interface diffusivity': give K_LS > 0"
expect_error 's/set End time = 0.1/set End time = 0.1\n  set Time stepping = implicit\n  set Time step = 1e-3/' \
  "Invalid value 'implicit' for the parameter 'diffusion/Time stepping': the model 'corrosion' runs with explicit time stepping only"
expect_error 's/set Model = corrosion/set Model = none/' \
  "The entry 'diffusion/corrosion/Saturation concentration' (line 14) belongs to 'corrosion', but 'diffusion/Model' selects 'none'"
expect_error 's/set End time = 0.1/set End time = 0.1\n  set Time step = 0.05/' \
  "Invalid value '0.05' for the parameter 'diffusion/Time step'"
cp base.orig base.prm

# Mirror flux layers: explicit only, at most one horizon thick, and a face
# carries either a value or a flux.
expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Flux boundary ids = 1\n  set Flux layer values = mirror\n  set Time stepping = implicit\n  set Time step = 1e-4/' \
  "Invalid value 'mirror' for the parameter 'diffusion/Flux layer values': mirror layers need 'Time stepping = explicit'"
expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Flux boundary ids = 1\n  set Flux layer values = mirror\n  set Flux layer thickness = 1.5/' \
  "Invalid value '1.5' for the parameter 'diffusion/Flux layer thickness': mirror layers reach nodes up to two layer thicknesses away" 2
expect_error 's/set Dirichlet boundary ids = 0/set Dirichlet boundary ids = 0\n  set Flux boundary ids = 0, 1/' \
  "Invalid value '0, 1' for the parameter 'diffusion/Flux boundary ids': boundary id 0 is also in 'Dirichlet boundary ids'" 2
# 1D: only the problem types registered for 1D, and 1D points.
expect_error 's/set Dimension = 2/set Dimension = 1/; s/set Problem type = diffusion/set Problem type = explicit dynamics/' \
  "Invalid value 'explicit dynamics' for the parameter 'Problem type': 1D runs ('Dimension = 1') offer only diffusion" 2
expect_error 's/set Dimension = 2/set Dimension = 1/' \
  "Invalid value '0, 0' for the parameter 'Geometry/Lower corner': it does not match the allowed form" 2

# A concentration that turns non-finite stops the run with the step and the
# node named; what was written before stays complete.

for np in 1 2; do
  sed -e 's/set End time = 1e-3/set End time = 8e-3\n  set Time step = 1e-3\n  set Output every steps = 2\n  set History every steps = 2/' \
      -e 's/    set Function expression = 1/    set Function expression = t > 3e-3 ? 0\/0 : 1/' base.prm > nan.prm
  rm -rf out
  out=$(timeout 120 mpirun --oversubscribe -np $np "$perideal" nan.prm 2>&1); rc=$?
  check_clean_exit "$rc" "$out" "the non-finite run on $np processes"
  grep -qE "not finite at step [0-9]+ .* at the node at" <<<"$out" || { echo "$out" | tail -5; fail "non-finite run: no step and node named"; }
  [ -f out/solution.pvd ] || fail "non-finite run: the earlier output is gone"
  for record in $(sed -n 's/.*file="\([^"]*\)".*/\1/p' out/solution.pvd); do
    [ -f "out/$record" ] || fail "non-finite run: $record named but missing"
  done
  ls out/*.tmp > /dev/null 2>&1 && fail "non-finite run: temporary files remain"
done

if [ "$failures" -eq 0 ]; then echo "OK: all bad inputs rejected with clear messages"; else exit 1; fi
