#!/usr/bin/env bash
# Usage: run_external_plugin_example.sh CMAKE BUILD_DIR EXAMPLE_DIR [LAUNCHER]
#
# examples/external-plugin as a user meets it: installs this build with
# `cmake --install BUILD_DIR --prefix <work>/prefix`, copies the example to
# <work>/src (a project outside PeriDEAL's tree; the source tree is not
# touched), configures it against the installed package only
# (CMAKE_PREFIX_PATH=<work>/prefix), builds the plugin library, and runs the
# installed perideal on the example's .prm on 1 and 2 processes. Checks:
#  - the installed perideal and the plugin resolve libperideal from the
#    prefix (RPATH), not from the build tree;
#  - the runs exit with 0, print the critical stretch of the plugin's
#    influence function, sqrt(8 pi G0 / (35 mu delta)) (the built-in
#    "constant" would give sqrt(pi G0 / (6 mu delta)), 15% less), to the
#    6 significant digits the run prints (5e-6 relative),
#    and break bonds beyond the pre-crack;
#  - 1 and 2 processes give the same energy history (broken bonds exactly).
# LAUNCHER (optional) is a compiler launcher such as ccache.
set -u
cmake="$1"; build="$2"; example="$3"; launcher="${4:-}"
work="$(pwd)/external-plugin"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*"; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

prefix="$work/prefix"
"$cmake" --install "$build" --prefix "$prefix" > install.log 2>&1 \
  || { cat install.log; fail "cmake --install failed"; }
perideal="$prefix/bin/perideal"
[ -x "$perideal" ] || fail "no $perideal after the install"
uses_prefix() {  # uses_prefix FILE: libperideal resolves into the prefix
  local lib
  lib=$(ldd "$1" | sed -n 's/^[[:space:]]*libperideal\.so => \([^ ]*\) .*/\1/p')
  [ "$(readlink -f "$lib")" = "$(readlink -f "$prefix")/lib/libperideal.so" ] \
    || fail "$1 uses libperideal '$lib', not the installed one: $(ldd "$1" | grep perideal)"
}
uses_prefix "$perideal"

cp -r "$example" src
"$cmake" -S src -B src/build -DCMAKE_PREFIX_PATH="$prefix" \
  ${launcher:+-DCMAKE_CXX_COMPILER_LAUNCHER="$launcher"} > configure.log 2>&1 \
  || { cat configure.log; fail "configuring the example against the installed package failed"; }
"$cmake" --build src/build -j2 > build.log 2>&1 \
  || { cat build.log; fail "building the example failed"; }
uses_prefix src/build/libquartic_bell.so

# The closed form of the example's .prm (E = 72 GPa, nu = 1/3, G0 = 3.8,
# h = 2 mm, m = 3): mu = 3E/8, delta = 3h.
expected=$(awk 'BEGIN { pi = atan2(0, -1); mu = 3 * 72e9 / 8; delta = 0.006;
                        printf "%.10e", sqrt(8 * pi * 3.8 / (35 * mu * delta)) }')
cd src
for np in 1 2; do
  rm -rf output
  if [ "$np" -eq 1 ]; then
    "$perideal" quartic_bell.prm > "../run.np$np.log" 2>&1
  else
    timeout 300 mpirun --oversubscribe -np 2 "$perideal" --threads 1 quartic_bell.prm > "../run.np$np.log" 2>&1
  fi
  rc=$?
  [ $rc -eq 0 ] || { cat "../run.np$np.log"; fail "perideal exited with $rc on $np process(es)"; }
  s0=$(sed -n 's/.*critical stretch \([0-9.eE+-]*\),.*/\1/p' "../run.np$np.log")
  awk -v s="$s0" -v e="$expected" 'BEGIN { d = (s - e) / e; if (d < 0) d = -d; exit !(s != "" && d < 5e-6) }' \
    || { cat "../run.np$np.log"; fail "critical stretch '$s0' on $np process(es), expected $expected (quartic bell)"; }
  echo "$np process(es): critical stretch $s0 (closed form $expected)"
  [ -f output/energies.csv ] || fail "no output/energies.csv"
  awk -F, 'NR == 2 { b0 = $7 } END { printf "  bonds broken during the run: %d\n", $7 - b0; exit !($7 > b0) }' output/energies.csv \
    || { cat output/energies.csv; fail "no bond broke"; }
  cp output/energies.csv "../energies.np$np.csv"
done
cmp -s ../energies.np1.csv ../energies.np2.csv || awk -F, '
  NR == FNR { row[FNR] = $0; next }
  { split(row[FNR], a, ","); if (a[7] != $7) exit 1
    for (c = 3; c <= 6; ++c) { d = a[c] - $c; if (d < 0) d = -d; s = a[c] < 0 ? -a[c] : a[c]
      if (d > 1e-8 * s + 1e-14) exit 1 } }' ../energies.np1.csv ../energies.np2.csv \
  || { paste -d'\n' ../energies.np1.csv ../energies.np2.csv; fail "1 and 2 processes differ"; }
echo "OK"
