#!/usr/bin/env bash
# 1D pit growth of SS304 in NaCl with the corrosion model of the diffusion
# problem type, on the true 1D driver (Dimension = 1; K = 8.6e-10 m^2/s,
# C_sat = 4.6 M, C_solid = 142.9 M, n = 2.19). The set-up is the one of
# tests/diffusion/corrosion_stefan_1d.prm (template pit_1d.prm.in): metal
# in x < 0, electrolyte (C = 0) in 0 < x < s0 = 10 um, C = 0 held in a
# Dirichlet layer one horizon beyond x = 10 um (the pit mouth); constant
# influence, lattice calibration, m = 4, h = delta / 4 exactly.
#
#   (a) diffusion control, 'dissolution rate' (i = 1e6 A/m^2, q = 1):
#       delta = 4, 2, 1, 0.5, 0.25 um, 40 s, against the exact Stefan
#       solution s(40 s) = 48.637 um (s = s0 + pit_volume_with_damage);
#   (b) diffusion control, 'interface diffusivity' (K_LS = K, q = 2):
#       delta = 4, 2, 1, 0.5 um, 40 s;
#   (c) activation control, 'dissolution rate' with i = 5.1e3 A/m^2
#       (q = 1): delta = 2 and 1 um, 40 s, against v t (v = 0.1745 um/s)
#       and i/(nF) t;
#   (d) the ctest case (a at delta = 1 um) on 2 MPI processes, compared
#       with 1 process;
#   plus the time step: a few cases of (a) and (b) again with the safety
#   factor of the step bound 0.3 and 0.1 instead of 0.9 (*_sf03, *_sf01).
#
#   bash bench/diffusion/run_pit_growth_1d.sh BUILD_DIR [--quick]
#        [--output-dir DIR] [--only CASE[,CASE...]]
#
# --quick: delta = 4 and 2 um only, 5 s of simulated time (a few seconds
# in all); DIR then defaults to results/diffusion_pit_growth_1d_quick.
# --only: run only these cases of the list; the other rows of an existing
# DIR/runs.csv are kept, then everything is plotted.
# Writes DIR/runs.csv (case, interface, delta_um, h_um, nodes, steps, s_um,
# error_percent against 48.637 um (40 s diffusion-control cases only),
# wall_s, then the other settings), DIR/runs/<case>/ (history.csv, VTU),
# DIR/logs/, DIR/inputs/, and (plot_pit_growth_1d.py) the PNGs and the
# tables on stdout. DIR defaults to results/diffusion_pit_growth_1d.
# Nothing is built: BUILD_DIR must hold bin/perideal. One process, one
# thread, unless the case says otherwise; the wall time is the driver's
# 'total wall time'.
set -euo pipefail
usage="usage: bash bench/diffusion/run_pit_growth_1d.sh BUILD_DIR [--quick] [--output-dir DIR] [--only CASE[,CASE...]]"
[ $# -ge 1 ] || { echo "$usage" >&2; exit 2; }
build="$(cd "$1" && pwd)"; shift
perideal="$build/bin/perideal"
[ -x "$perideal" ] || { echo "no $perideal" >&2; exit 2; }
# The library next to the binary first (a copied build dir works too).
export LD_LIBRARY_PATH="$build/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
here="$(cd "$(dirname "$0")" && pwd)"
quick=0
only=
out=
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --output-dir) out="$2"; shift ;;
    --only) only="$2"; shift ;;
    *) echo "$usage" >&2; exit 2 ;;
  esac
  shift
done
if [ -z "$out" ]; then
  out=results/diffusion_pit_growth_1d
  [ $quick -eq 0 ] || out=results/diffusion_pit_growth_1d_quick
fi
mkdir -p "$out/logs" "$out/inputs" "$out/runs"
out=$(cd "$out" && pwd)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# Cases: name control delta_um m lower_um end_s interface current_density
#        K_LS flux_exponent ranks threads [safety_factor]
# control: diffusion (compared with the Stefan solution) or activation.
# interface: dr = dissolution rate (current density), id = interface
#   diffusivity (K_LS). The upper corner is always 10 um + delta (the
#   Dirichlet layer); the metal must reach below the final front.
# safety_factor: of the time step bound (default 0.9, the driver's).
if [ $quick -eq 1 ]; then
  cases="a_dr_d4 diffusion 4 4 -48 5 dr 1e6 0 1 1 1
a_dr_d2 diffusion 2 4 -45 5 dr 1e6 0 1 1 1
b_id_d4 diffusion 4 4 -48 5 id 0 8.6e-10 2 1 1
b_id_d2 diffusion 2 4 -45 5 id 0 8.6e-10 2 1 1
c_act_d2 activation 2 4 -15 5 dr 5.1e3 0 1 1 1
a_dr_d2_np2 diffusion 2 4 -45 5 dr 1e6 0 1 2 1"
else
  cases="a_dr_d4 diffusion 4 4 -48 40 dr 1e6 0 1 1 1
a_dr_d2 diffusion 2 4 -45 40 dr 1e6 0 1 1 1
a_dr_d1 diffusion 1 4 -45 40 dr 1e6 0 1 1 1
a_dr_d0.5 diffusion 0.5 4 -45 40 dr 1e6 0 1 1 1
a_dr_d0.25 diffusion 0.25 4 -45 40 dr 1e6 0 1 1 1
b_id_d4 diffusion 4 4 -48 40 id 0 8.6e-10 2 1 1
b_id_d2 diffusion 2 4 -45 40 id 0 8.6e-10 2 1 1
b_id_d1 diffusion 1 4 -45 40 id 0 8.6e-10 2 1 1
b_id_d0.5 diffusion 0.5 4 -45 40 id 0 8.6e-10 2 1 1
c_act_d2 activation 2 4 -15 40 dr 5.1e3 0 1 1 1
c_act_d1 activation 1 4 -15 40 dr 5.1e3 0 1 1 1
a_dr_d1_np2 diffusion 1 4 -45 40 dr 1e6 0 1 2 1
a_dr_d1_sf03 diffusion 1 4 -45 40 dr 1e6 0 1 1 1 0.3
a_dr_d1_sf01 diffusion 1 4 -45 40 dr 1e6 0 1 1 1 0.1
b_id_d2_sf03 diffusion 2 4 -45 40 id 0 8.6e-10 2 1 1 0.3
b_id_d1_sf03 diffusion 1 4 -45 40 id 0 8.6e-10 2 1 1 0.3
b_id_d1_sf01 diffusion 1 4 -45 40 id 0 8.6e-10 2 1 1 0.1
b_id_d0.5_sf03 diffusion 0.5 4 -45 40 id 0 8.6e-10 2 1 1 0.3"
fi

summary="$out/runs.csv"
header="case,interface,delta_um,h_um,nodes,steps,s_um,error_percent,wall_s,control,m,lower_um,upper_um,end_time,current_density,interface_diffusivity,flux_exponent,ranks,threads,time_step,model_limited,history_every,safety_factor"
if [ -n "$only" ]; then
  cases=$(echo "$cases" | awk -v only=",$only," 'index(only, "," $1 ",")')
  [ -n "$cases" ] || { echo "no case named in --only $only" >&2; exit 2; }
  if [ -f "$summary" ]; then
    # keep the other cases' rows
    awk -F, -v only=",$only," 'NR > 1 && !index(only, "," $1 ",")' "$summary" > "$summary.keep"
  else
    : > "$summary.keep"
  fi
  { echo "$header"; cat "$summary.keep"; } > "$summary"; rm -f "$summary.keep"
else
  echo "$header" > "$summary"
fi
echo "$cases" | while read -r name control delta m lower end iface cur kls q ranks threads safety; do
  safety=${safety:-0.9}
  # geometry in um: h = delta / m, upper = 10 + delta, and the number of
  # cells (upper - lower) / h must be an integer (checked here)
  read -r h upper n ok hist outint <<< "$(awk -v d="$delta" -v m="$m" \
    -v lo="$lower" -v T="$end" -v i="$iface" -v cur="$cur" -v sf="$safety" 'BEGIN {
      h = d / m; up = 10 + d; n = (up - lo) / h
      ok = (n - int(n + 0.5) < 1e-9 && int(n + 0.5) - n < 1e-9) ? 1 : 0
      # about 200 history rows: the diffusion bound on the step is about
      # 1.34e-4 s (q = 1) or 8.2e-5 s (q = 2) times (delta / um)^2; the
      # rate model limits it to about 1.95e-4 s (delta / um) (1e6 A/m^2 / i)
      if (i == "id") dt = 8.2e-5 * d * d
      else { dt = 1.34e-4 * d * d; lim = 1.95e-4 * d * 1e6 / cur; if (lim < dt) dt = lim }
      dt *= sf / 0.9
      hist = int(T / 200 / dt); if (hist < 1) hist = 1
      printf "%.10g %.10g %d %d %d %.10g\n", h, up, n + 0.5, ok, hist, T / 10 }')"
  [ "$ok" -eq 1 ] || { echo "$name: (upper - lower) / h = ($upper - $lower) / $h is not an integer" >&2; exit 1; }
  case "$iface" in
    dr) interface="dissolution rate"; drop='@KLS@' ;;
    id) interface="interface diffusivity"; drop='@I@' ;;
    *) echo "bad interface $iface" >&2; exit 2 ;;
  esac
  prm="$out/inputs/$name.prm"
  sed -e "/^ *set .*$drop/d" \
      -e "s|@LO@|${lower}e-6|g; s|@HI@|${upper}e-6|g; s|@N@|$n|g" \
      -e "s|@M@|$m|g; s|@Q@|$q|g; s|@END@|$end|g; s|@SF@|$safety|g" \
      -e "s|@IFACE@|$interface|g; s|@I@|$cur|g; s|@KLS@|$kls|g" \
      -e "s|@HIST@|$hist|g; s|@OUT@|$outint|g; s|@DIR@|$out/runs/$name|g" \
      "$here/pit_1d.prm.in" > "$prm"
  rm -rf "$out/runs/$name"
  log="$out/logs/$name.log"
  if [ "$ranks" -eq 1 ]; then
    "$perideal" --threads "$threads" "$prm" > "$log" 2>&1 || { tail -20 "$log"; echo "FAILED: $name" >&2; exit 1; }
  else
    mpirun --oversubscribe --bind-to none -np "$ranks" "$perideal" --threads "$threads" "$prm" < /dev/null > "$log" 2>&1 \
      || { tail -20 "$log"; echo "FAILED: $name" >&2; exit 1; }
  fi
  nodes=$(sed -n 's/.*diffusion: \([0-9]*\) nodes.*/\1/p' "$log")
  steps=$(sed -n 's/.*time step [0-9.e+-]* (\([0-9]*\) steps).*/\1/p' "$log")
  dt=$(sed -n 's/.*time step \([0-9.e+-]*\) (.*/\1/p' "$log")
  limited=$(grep -q "limits the time step" "$log" && echo yes || echo no)
  wall=$(sed -n 's/^total wall time \([0-9.e+-]*\) s.*/\1/p' "$log")
  # s = s0 + pit_volume_with_damage of the last history row (um); the
  # error against the exact Stefan value at 40 s (diffusion control only)
  read -r s err <<< "$(awk -F, -v c="$control" -v T="$end" '
    NR == 1 { for (k = 1; k <= NF; ++k) if ($k == "pit_volume_with_damage") col = k; next }
    { v = $col }
    END { s = 10 + v * 1e6
          e = (c == "diffusion" && T == 40) ? sprintf("%.4f", 100 * (s / 48.637 - 1)) : ""
          printf "%.4f %s\n", s, e }' "$out/runs/$name/history.csv")"
  echo "$name,$iface,$delta,$h,$nodes,$steps,$s,$err,$wall,$control,$m,$lower,$upper,$end,$cur,$kls,$q,$ranks,$threads,$dt,$limited,$hist,$safety" >> "$summary"
  echo "$name: $control, $interface, delta $delta um, h $h um, $nodes nodes, $steps steps (dt $dt s, model-limited: $limited), safety $safety, $ranks x $threads, s = $s um${err:+ ($err %)}, $wall s"
done
/usr/bin/python3 "$here/plot_pit_growth_1d.py" "$out"
