#!/usr/bin/env bash
# Boundary-treatment verification (Scabbia, Zaccariotto, Galvanetto 2023):
# the cases of bench/boundary/*.prm.in run with the treatments 'none',
# 'surface nodes' (Taylor order N = 1, 2, 3) and, where it is well posed,
# 'fictitious layer', plus a convergence study of the manufactured case.
#
#   bash bench/run_boundary_treatment.sh [--quick] [--output-dir DIR]
#
# Cases (LPS, Gaussian influence, exact partial volumes, m-ratio 3, MUMPS):
#   traction_3d            paper Sect. 4.1 (p = 10 MPa), 16 x 8 x 8 cells
#   manufactured_3d        paper Sect. 4.2 (cubic field), 16 x 8 x 8 cells
#   plane_strain_2d        paper Sect. 5 (p = 240 MPa), 40 x 40 cells, m = 3
#                          and m = 5 (at m = 3 the 2D discrete constitutive
#                          error, ~1 %, dominates the corrected error)
#   dirichlet_manufactured_3d  the cubic field with every face prescribed,
#                          the case a fictitious layer alone can carry
# Studies of manufactured_3d, with and without treatment:
#   h at fixed horizon 0.25 (m = 2, 3, 4), horizon at fixed m = 3
#   (8, 12, 16 cells along x). Larger 3D grids are dense to factorise:
#   20 x 10 x 10 at m = 3 takes ~170 s (MUMPS, 9000 unknowns, 32M nonzeros).
#
# Writes DIR/boundary_treatment.csv (case,treatment,N,max_error,l2_error,
# n_nodes,seconds; max_error is the normalized error of the paper's Eq. 38,
# l2_error the relative volume-weighted L2 error), DIR/cost.csv (unknowns,
# nonzeros, assembly and solve time of every run), DIR/convergence.csv,
# DIR/summary.csv (all driver columns), DIR/vtu/ (PVTU files with the error
# fields), DIR/nodes/*.csv (per-node errors) and, with matplotlib,
# DIR/<case>_error_slices.png (mid-plane error maps), DIR/convergence.png
# and DIR/error_vs_time.png. DIR defaults to results/boundary_treatment.
# --quick: small grids, a few runs (under ctest), with the paper's
# qualitative result asserted: surface nodes at least 100 times more
# accurate than 'none' on the traction cases (2D at m = 5), at least 10
# times on the coarse (8 x 4 x 4) manufactured case.
set -euo pipefail
cd "$(dirname "$0")/.."

source bench/driver_study.sh
driver_study_setup results/boundary_treatment "$@"
mkdir -p "$out/vtu" "$out/nodes" "$out/inputs"
rm -f "$out/summary.csv"

# run CASE NX NY M TREATMENT N TAG
run() {
  local case=$1 nx=$2 ny=$3 m=$4 treatment=$5 n=$6 tag=$7
  local name="${case}_${tag}"
  local h horizon layer
  h=$(awk "BEGIN{print 1.0/$nx}")
  horizon=$(awk "BEGIN{printf \"%.17g\", $m/$nx}")
  # 'none' and 'fictitious layer': Dirichlet layer of the outermost nodes.
  layer=$(awk "BEGIN{printf \"%.6g\", 0.6/$m}")
  # Only the selected treatment's subsection may hold entries.
  local section=""
  [ "$treatment" = none ] ||
    section="  subsection $treatment\\n    set Taylor order = ${n:-1}\\n  end"
  sed -e "s/@NX@/$nx/g; s/@NY@/$ny/g; s/@M@/$m/g; s/@N@/${n:-1}/g" \
      -e "s/@TREATMENT_SECTION@/$section/" \
      -e "s/@TREATMENT@/$treatment/g; s/@HORIZON@/$horizon/g" \
      -e "s/@LAYER@/$layer/g; s/@VTU@/true/g; s#@DIR@#$out/vtu#g" \
      -e "s/@NAME@/$name/g; s#@SUMMARY@#$out/summary.csv#g" \
      -e "s#@NODES@#$out/nodes/$name.csv#g" \
      "bench/boundary/$case.prm.in" > "$out/inputs/$name.prm"
  local start end
  start=$(date +%s.%N)
  "$perideal" "$out/inputs/$name.prm" > "$out/logs/$name.log" 2>&1 ||
    { echo "run $name failed, see $out/logs/$name.log" >&2; exit 1; }
  end=$(date +%s.%N)
  echo "$case,$tag,$nx,$m,$(awk "BEGIN{print $end-$start}")" >> "$out/runs.csv"
  grep -h "normalized max" "$out/logs/$name.log" | sed "s/^ */$name: /"
}

rm -f "$out/runs.csv"
if [ $quick -eq 1 ]; then
  run traction_3d 12 6 3 none "" none
  run traction_3d 12 6 3 "surface nodes" 1 sn1
  run plane_strain_2d 20 20 5 none "" none
  run plane_strain_2d 20 20 5 "surface nodes" 1 sn1
  run manufactured_3d 8 4 3 none "" none
  run manufactured_3d 8 4 3 "surface nodes" 3 sn3
  run dirichlet_manufactured_3d 8 4 3 "fictitious layer" 2 fl2
else
  for n in "" 1 2 3; do
    tag=${n:+sn$n}; treatment=${n:+surface nodes}
    run traction_3d 16 8 3 "${treatment:-none}" "$n" "${tag:-none}"
    run plane_strain_2d 40 40 3 "${treatment:-none}" "$n" "${tag:-none}"
    run plane_strain_2d 40 40 5 "${treatment:-none}" "$n" "${tag:-none}_m5"
    run manufactured_3d 16 8 3 "${treatment:-none}" "$n" "${tag:-none}"
  done
  run dirichlet_manufactured_3d 16 8 3 none "" none
  for n in 1 2 3; do
    run dirichlet_manufactured_3d 16 8 3 "fictitious layer" $n fl$n
    run dirichlet_manufactured_3d 16 8 3 "surface nodes" $n sn$n
  done
  # Convergence: h at fixed horizon 0.25 (m = 2..4), horizon at fixed m = 3.
  for m in 2 3 4; do
    nx=$((4 * m)); ny=$((2 * m))
    run manufactured_3d $nx $ny $m none "" "h_none_m$m"
    run manufactured_3d $nx $ny $m "surface nodes" 3 "h_sn3_m$m"
  done
  for nx in 8 12 16; do
    run manufactured_3d $nx $((nx / 2)) 3 none "" "delta_none_nx$nx"
    run manufactured_3d $nx $((nx / 2)) 3 "surface nodes" 3 "delta_sn3_nx$nx"
  done
fi

/usr/bin/python3 bench/tabulate_boundary_treatment.py "$out"
plot_if_possible bench/plot_boundary_treatment.py "$out"

if [ $quick -eq 1 ]; then
  /usr/bin/python3 - "$out/boundary_treatment.csv" <<'PY'
import csv, sys
rows = {(r["case"], r["treatment"], r["N"]): float(r["max_error"])
        for r in csv.DictReader(open(sys.argv[1]))}
failed = False
for case in ("traction_3d", "plane_strain_2d"):
    none, sn = rows[(case, "none", "0")], rows[(case, "surface nodes", "1")]
    print(f"{case}: none {none:.3e}, surface nodes N=1 {sn:.3e}, "
          f"ratio {none / sn:.0f}")
    if not none > 100 * sn:
        print(f"{case}: surface nodes not 100 times better", file=sys.stderr)
        failed = True
man = (rows[("manufactured_3d", "none", "0")],
       rows[("manufactured_3d", "surface nodes", "3")])
print(f"manufactured_3d: none {man[0]:.3e}, surface nodes N=3 {man[1]:.3e}")
if not man[0] > 10 * man[1]:
    print("manufactured_3d: surface nodes not 10 times better", file=sys.stderr)
    failed = True
sys.exit(1 if failed else 0)
PY
fi
