#!/usr/bin/env bash
# Usage: shared_libraries.sh PERIDEAL PAIR_MODEL_LIB DUPLICATE_NAME_LIB UNDEFINED_SYMBOL_LIB
#
# 'Additional shared libraries': a material model in a library of its own
# (plugin_pair_model.cc) is selected by name, reads its own parameter and
# solves a patch test to round-off, on 1 and 2 processes; libraries that
# cannot be loaded (no such file, a name without '/', not a library, a
# plugin name already registered, an undefined symbol) stop every process
# with a message naming the entry, the library and the reason, exit
# non-zero and leave no output.
set -u
perideal="$1"; pair_model="$2"; duplicate_name="$3"; undefined_symbol="$4"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

work="$(pwd)/shared_libraries"
rm -rf "$work" && mkdir -p "$work" && cd "$work"

# A linear field prescribed in a layer one horizon thick: a bond-based model
# (any micromodulus) reproduces it to round-off.
cat > base.prm <<PRM
set Additional shared libraries = $pair_model
set Dimension = 2
subsection Geometry
  set Lower corner = 0, 0
  set Upper corner = 1, 1
  set Subdivisions = 10, 10
end
subsection Horizon
  set m-ratio = 3
end
subsection Material model
  set Model = test pair model
  subsection test pair model
    set Micromodulus = 2e12
  end
end
subsection Boundary conditions
  set Dirichlet boundary ids    = 0, 1, 2, 3
  set Dirichlet layer thickness = 1
  subsection Dirichlet displacement
    set Variable names      = x,y
    set Function expression = 1e-3*(x + 2*y); 1e-3*(0.5*x - y)
  end
end
subsection Analytical solution
  set Compare with analytical solution = true
  subsection Displacement
    set Variable names      = x,y
    set Function expression = 1e-3*(x + 2*y); 1e-3*(0.5*x - y)
  end
end
subsection Linear solver
  set Method = direct
end
subsection Output
  set Directory = out
end
PRM
for np in 1 2; do
  rm -rf out
  if [ "$np" -eq 1 ]; then
    "$perideal" base.prm > base.log 2>&1
  else
    timeout 120 mpirun --oversubscribe -np 2 "$perideal" base.prm > base.log 2>&1
  fi
  rc=$?
  if [ $rc -ne 0 ]; then
    cat base.log; fail "the plugin model's patch test failed on $np process(es) (exit $rc)"
  else
    error=$(sed -n 's/.*error against the analytical solution: relative L2 \([^,]*\),.*/\1/p' base.log)
    awk -v e="$error" 'BEGIN { exit !(e != "" && e < 1e-12) }' \
      || fail "the plugin model's patch test on $np process(es): relative L2 error '$error', not below 1e-12"
    echo "$np process(es): plugin model, patch test error $error"
  fi
done
rm -rf out

# expect_error "sed expression" "substring of the message" [nprocs]
expect_error() {
  local edit="$1" expected="$2" nprocs="${3:-1}" out rc
  sed -e "$edit" base.prm > case.prm
  cmp -s base.prm case.prm && { fail "edit '$edit' changed nothing"; return; }
  if [ "$nprocs" -eq 1 ]; then
    out=$("$perideal" case.prm 2>&1); rc=$?
  else
    out=$(timeout 120 mpirun --oversubscribe -np "$nprocs" "$perideal" case.prm 2>&1); rc=$?
  fi
  [ "$rc" -ne 124 ] || fail "'$edit' hung on $nprocs processes"
  [ "$rc" -ne 0 ] || fail "'$edit' exited with 0"
  [ "$rc" -lt 128 ] || fail "'$edit' ended with a signal (exit $rc): $out"
  grep -qF -- "$expected" <<<"$out" || fail "'$edit': message lacks '$expected': $out"
  [ ! -e out ] || { fail "'$edit' left output behind"; rm -rf out; }
}

# The plugin's own parameter is read and checked by the plugin.
expect_error 's/set Micromodulus = 2e12/set Micromodulus = -1/' \
  "Invalid value '-1' for the parameter 'Material model/test pair model/Micromodulus'" 2
expect_error "s|^set Additional shared libraries = .*|set Additional shared libraries = ./no_such_plugin.so|" \
  "Invalid value './no_such_plugin.so' for the parameter 'Additional shared libraries': the library could not be loaded (./no_such_plugin.so: cannot open shared object file: No such file or directory)"
expect_error "s|^set Additional shared libraries = .*|set Additional shared libraries = ./no_such_plugin.so|" \
  "Invalid value './no_such_plugin.so' for the parameter 'Additional shared libraries'" 2
expect_error "s|^set Additional shared libraries = .*|set Additional shared libraries = libno_such_plugin.so|" \
  "write './libno_such_plugin.so' for a library in the working directory"
expect_error "s|^set Additional shared libraries = .*|set Additional shared libraries = ./base.prm|" \
  "Invalid value './base.prm' for the parameter 'Additional shared libraries': the library could not be loaded (./base.prm: "
expect_error "s|^set Additional shared libraries = .*|set Additional shared libraries = $pair_model, $duplicate_name|" \
  "Invalid value '$duplicate_name' for the parameter 'Additional shared libraries': its plugins could not be registered (The influence function 'gaussian' is registered twice" 2
expect_error "s|^set Additional shared libraries = .*|set Additional shared libraries = $undefined_symbol|" \
  "undefined symbol: perideal_test_function_that_nobody_defines" 2

if [ "$failures" -eq 0 ]; then echo "OK"; else exit 1; fi
