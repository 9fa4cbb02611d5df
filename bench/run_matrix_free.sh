#!/usr/bin/env bash
# The matrix-free operator at scale (issue 9): 3D LPS, m = 3, unit cube,
# manufactured quadratic field in Dirichlet layers (bench/matrix_free/
# lps_3d_quadratic.prm.in), matrix-free CG to 1e-8 with the local
# elasticity (AMG) and the Jacobi preconditioner, N^3 nodes for N = 20 ...
# 100; iterations against m at fixed h; the Peridigm bar
# (bench/bar/peridigm_bar.prm) with both preconditioners and the assembled
# path; the operator throughput benchmark. Writes CSVs and PNGs under the
# output directory.
#
#   bash bench/run_matrix_free.sh [--quick] [--output-dir DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
cd "$here/.."
source "$here/driver_study.sh"
driver_study_setup "results/matrix_free" "$@"
[ "${PERIDEAL_SKIP_BUILD:-0}" = 1 ] || cmake --build "${BUILD_DIR:-build}" -j2 \
  --target perideal-bond-operator-throughput > /dev/null
tool="$(dirname "$perideal")/perideal-bond-operator-throughput"
QUICK=$quick
cd "$out"
rm -f scaling.csv m_sweep.csv bar.csv

# N = S * 2^R nodes per direction.
if [ "$QUICK" = 1 ]; then
  sizes="5:2 10:1"; ms="2 3"; threads=2
else
  sizes="5:2 5:3 15:2 5:4 25:2"; ms="2 3 4 5"; threads=2
fi
run_case() { # S R m preconditioner summary [coarsening]
  # local elasticity: its matrix on every coarsening-th node; the Jacobi
  # weight that serves each best (the doc's iterations against it).
  local local_settings=""
  if [ "$4" = "local elasticity" ]; then
    local c="${6:-1}" w=0.3
    [ "$c" = 2 ] && w=0.8
    local_settings="  subsection local elasticity\\n    set Coarsening       = $c\\n    set PD Jacobi weight = $w\\n  end"
  fi
  sed -e "s/@S@/$1/g; s/@R@/$2/; s/@N@/$(( $1 * (1 << $2) ))/; s/@P@/$4/; s|@SUMMARY@|$5|; s/^@LOCAL_ELASTICITY@$/$local_settings/; s/(@LOCAL_ELASTICITY@:/(local elasticity:/" \
      "$here/matrix_free/lps_3d_quadratic.prm.in" \
    | sed -e "s/set m-ratio = 3/set m-ratio = $3/" > case.prm
  "$perideal" --threads "$threads" case.prm > case.log 2>&1 \
    || { cat case.log; echo "FAIL: S=$1 R=$2 m=$3 $4 coarsening ${6:-1}"; exit 1; }
  grep -E "solved with|error against" case.log
}
for sr in $sizes; do
  for p in "local elasticity" Jacobi; do
    run_case "${sr%%:*}" "${sr##*:}" 3 "$p" scaling.csv
  done
  # Local elasticity on every second node (issue 25, item 6).
  run_case "${sr%%:*}" "${sr##*:}" 3 "local elasticity" scaling.csv 2
done
for m in $ms; do
  for p in "local elasticity" Jacobi; do
    run_case 5 $([ "$QUICK" = 1 ] && echo 2 || echo 3) "$m" "$p" m_sweep.csv
  done
  run_case 5 $([ "$QUICK" = 1 ] && echo 2 || echo 3) "$m" "local elasticity" m_sweep.csv 2
done

# The bar of the Peridigm comparison, 1 process: matrix-free with both
# preconditioners on 1 and 2 threads, and the assembled path with CG + AMG.
for t in 1 2; do
  for p in Jacobi "local elasticity"; do
    sed -e "s/set Preconditioner     = local elasticity/set Preconditioner = $p/" \
        -e "s|set Write VTU = false|set Write VTU = false\n  set Summary file = bar.csv|" \
        "$here/bar/peridigm_bar.prm" > bar.prm
    "$perideal" --threads $t bar.prm > bar.log
    grep -E "solved with|total wall" bar.log
  done
done
sed -e "s/set Operator           = matrix-free/set Operator = assembled/" \
    -e "s/set Preconditioner     = local elasticity/set Preconditioner = AMG/" \
    -e "s|set Write VTU = false|set Write VTU = false\n  set Summary file = bar.csv|" \
    "$here/bar/peridigm_bar.prm" > bar.prm
"$perideal" --threads 1 bar.prm > bar.log
grep -E "solved with|total wall" bar.log

"$tool" $([ "$QUICK" = 1 ] && echo --quick) \
  --output-dir . > throughput.log
cat throughput.log

plot_if_possible "$here/plot_matrix_free.py" --output-dir .
echo "OK: results in $out"
