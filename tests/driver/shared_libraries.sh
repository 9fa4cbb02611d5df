#!/usr/bin/env bash
# Usage: shared_libraries.sh PERIDEAL PAIR_MODEL_LIB PRECONDITIONER_LIB DUPLICATE_NAME_LIB UNDEFINED_SYMBOL_LIB
#
# 'Additional shared libraries': a material model in a library of its own
# (plugin_pair_model.cc) is selected by name, reads its own parameter and
# solves a patch test to round-off, on 1 and 2 processes; a preconditioner
# in a library (plugin_preconditioner.cc: Jacobi times a factor) preconditions
# matrix-free CG with the iterations of the built-in Jacobi, reads its own
# parameter, and is refused where it cannot run; libraries that
# cannot be loaded (no such file, a name without '/', not a library, a
# plugin name already registered, an undefined symbol) stop every process
# with a message naming the entry, the library and the reason, exit
# non-zero and leave no output.
set -u
perideal="$1"; pair_model="$2"; preconditioner="$3"; duplicate_name="$4"; undefined_symbol="$5"
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

# A preconditioner plugin: matrix-free CG on the LPS traction case of
# lps_2d_traction_matrix_free.prm with 'test scaled jacobi' (Scale = 1000)
# against the built-in 'Jacobi' and against 'none'. CG's iterates do not
# change when the preconditioner is scaled, so the plugin must take the
# iterations of Jacobi (one more or less for round-off in the stopping
# test), not those of the unpreconditioned CG (134 against 142 when this
# was written), and reach the same error against the analytical solution.
{
  echo "set Additional shared libraries = $preconditioner"
  sed -e 's/^  set Preconditioner .*/  set Preconditioner     = test scaled jacobi\n  subsection test scaled jacobi\n    set Scale = 1000\n  end/' \
      -e 's/^  set Write VTU = false/  set Write VTU = false\n  set Directory = out/' \
      "$(dirname "$0")/lps_2d_traction_matrix_free.prm"
} > pc.prm
grep -qF "set Scale = 1000" pc.prm && grep -qF "set Directory = out" pc.prm \
  || fail "pc.prm was not made from lps_2d_traction_matrix_free.prm"
# iterations_of LOG: the iteration count of the line 'solved with ...';
# error_of LOG: the line of the error against the analytical solution.
iterations_of() { sed -n 's/.*solved with .*: \([0-9]*\) iteration(s).*/\1/p' "$1"; }
error_of() { grep -F "error against the analytical solution" "$1"; }
for builtin in Jacobi none; do
  sed -e '/subsection test scaled jacobi/,/^  end/d' \
      -e "s/set Preconditioner     = test scaled jacobi/set Preconditioner     = $builtin/" pc.prm > "$builtin.prm"
  "$perideal" "$builtin.prm" > "$builtin.log" 2>&1 || { cat "$builtin.log"; fail "the run with '$builtin' failed"; }
  rm -rf out
done
reference=$(iterations_of Jacobi.log); unpreconditioned=$(iterations_of none.log)
within_one() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; exit !(a != "" && b != "" && d <= 1 && d >= -1) }'; }
! within_one "$reference" "$unpreconditioned" \
  || fail "Jacobi ($reference iterations) and none ($unpreconditioned) cannot be told apart on this case"
for np in 1 2; do
  if [ "$np" -eq 1 ]; then
    "$perideal" pc.prm > pc.log 2>&1
  else
    timeout 120 mpirun --oversubscribe -np 2 "$perideal" pc.prm > pc.log 2>&1
  fi
  rc=$?
  rm -rf out
  if [ $rc -ne 0 ]; then
    cat pc.log; fail "the preconditioner plugin's run failed on $np process(es) (exit $rc)"
    continue
  fi
  grep -qF "solved with CG + test scaled jacobi (matrix-free operator)" pc.log \
    || fail "the log does not name the plugin preconditioner on $np process(es)"
  iterations=$(iterations_of pc.log)
  within_one "$iterations" "$reference" \
    || fail "CG with the plugin took '$iterations' iterations, with Jacobi '$reference', on $np process(es)"
  [ "$(error_of pc.log)" = "$(error_of Jacobi.log)" ] \
    || fail "the plugin's error on $np process(es), '$(error_of pc.log)', is not Jacobi's, '$(error_of Jacobi.log)'"
  echo "$np process(es): plugin preconditioner, $iterations CG iterations (Jacobi: $reference, none: $unpreconditioned)"
done
cp pc.prm base.prm
# Its parameter is read and checked by the plugin; the solver refuses it for
# the assembled matrix (it says it supports the matrix-free form only);
# entries for a preconditioner that is not selected are refused.
expect_error 's/    set Scale = 1000/    set Scale = -2/' \
  "Invalid value '-2' for the parameter 'Linear solver/test scaled jacobi/Scale'" 2
expect_error 's/  set Operator           = matrix-free/  set Operator           = assembled/' \
  "Invalid value 'test scaled jacobi' for the parameter 'Linear solver/Preconditioner': 'test scaled jacobi' is a preconditioner of the matrix-free operator" 2
expect_error 's/  set Preconditioner     = test scaled jacobi/  set Preconditioner     = Jacobi/' \
  "belongs to 'test scaled jacobi', but 'Linear solver/Preconditioner' selects 'Jacobi', so it would be ignored"

if [ "$failures" -eq 0 ]; then echo "OK"; else exit 1; fi
