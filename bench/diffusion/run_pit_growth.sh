#!/usr/bin/env bash
# Pit growth of SS304 in NaCl with the corrosion model of the diffusion
# problem type (doc/corrosion-model.md; K = 8.6e-10 m^2/s, C_sat = 4.6 M,
# C_solid = 142.9 M, n = 2.19), against the 1D references:
#
#   (a) diffusion control in a quasi-1D 2D strip (metal below y = 0, a
#       10 um electrolyte layer s0 over it, C = 0 held in a Dirichlet layer
#       one horizon thick above it = the pit mouth): both interface models
#       ('dissolution rate' with i = 1e6 A/m^2, 'interface diffusivity' with
#       K_LS = K), horizon 4, 2 and 1 um (m = 4), strip widths 4, 8 and 16
#       horizons (4 and 8 at 1 um; the free sides of the strip lose bonds),
#       one case at 1 um also with the other interface; pit depth against
#       time to 40 s against the exact Stefan solution with s0 = 10 um
#       (48.64 um at 40 s), the quasi-steady s^2 = s0^2 + 2 K St t and the
#       formula d^2 = 2 K (C_sat/C_solid) t of the issue (47.06 um at 40 s);
#   (b) activation control (i = 5.1e3 A/m^2): front speed against
#       v = i/(nF)/(C_solid - C_sat) = 0.1745 um/s and the dissolved amount
#       (metal_amount) against i/(nF) t;
#   (c) pit shape from an opening in a passive film (phase 2) under a
#       10 um electrolyte layer, diffusion control: 2D (opening 6 um wide,
#       both interface models, 40 s) and a small 3D case (circular opening
#       of radius 3 um, ~24,000 nodes, 20 s, 2 threads);
#   plus one case on 2 MPI processes, compared with the same case on one.
#
#   bash bench/diffusion/run_pit_growth.sh BUILD_DIR [--quick]
#        [--output-dir DIR] [--only CASE[,CASE...]]
#
# --quick: short end times and small domains (a few seconds per case).
# --only: run only these cases of the list; the other rows of an existing
# DIR/runs.csv are kept (to add or rerun cases), then everything is plotted.
# Writes DIR/runs.csv (sizes, time steps, wall times), DIR/runs/<case>/
# (history.csv and PVTU output of every case), DIR/logs/, DIR/inputs/, and
# (plot_pit_growth.py, matplotlib) DIR/pit_growth.csv, DIR/*.png and the
# tables on stdout. DIR defaults to results/diffusion_pit_growth. Nothing
# is built: BUILD_DIR must hold bin/perideal. Runs on one process and one
# thread unless the case says otherwise; the wall time is the driver's
# 'total wall time'.
set -euo pipefail
usage="usage: bash bench/diffusion/run_pit_growth.sh BUILD_DIR [--quick] [--output-dir DIR] [--only CASE[,CASE...]]"
[ $# -ge 1 ] || { echo "$usage" >&2; exit 2; }
build="$(cd "$1" && pwd)"; shift
perideal="$build/bin/perideal"
[ -x "$perideal" ] || { echo "no $perideal" >&2; exit 2; }
# The library next to the binary first (a copied build dir works too).
export LD_LIBRARY_PATH="$build/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
here="$(cd "$(dirname "$0")" && pwd)"
quick=0
only=
out=results/diffusion_pit_growth
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --output-dir) out="$2"; shift ;;
    --only) only="$2"; shift ;;
    *) echo "$usage" >&2; exit 2 ;;
  esac
  shift
done
mkdir -p "$out/logs" "$out/inputs" "$out/runs"
out=$(cd "$out" && pwd)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# Cases: name kind delta_um m width_um ymin_um layer_um open_um end_s
#        interface current_density K_LS ranks threads [safety_factor]
# kind strip: width = strip width, layer = s0 (electrolyte over the metal),
#   ymin = bottom of the metal; shape2d/shape3d: width = half-width of the
#   box, layer = electrolyte over the film (film = one horizon thick),
#   open = half-width (2D) or radius (3D) of the opening.
# interface: dr = dissolution rate (current density), id = interface
#   diffusivity (K_LS). safety_factor: of the time step bound (default 0.9;
#   the cases *_sf03 use 0.3, to see what the step changes).
if [ $quick -eq 1 ]; then
  cases="a_dr_d2_w4 strip 2 4 8 -10 10 - 2 dr 1e6 0 1 1
a_id_d2_w4 strip 2 4 8 -10 10 - 2 id 0 8.6e-10 1 1
a_dr_d2_w4_np2 strip 2 4 8 -10 10 - 2 dr 1e6 0 2 1
b_d2_w4 strip 2 4 8 -8 10 - 4 dr 5.1e3 0 1 1
c2_id shape2d 2 4 10 -8 10 3 1 id 0 8.6e-10 1 1
c3_id shape3d 3 3 6 -6 3 3 0.5 id 0 8.6e-10 1 2"
else
  cases="a_dr_d2_w4 strip 2 4 8 -45 10 - 40 dr 1e6 0 1 1
a_dr_d2_w8 strip 2 4 16 -45 10 - 40 dr 1e6 0 1 1
a_id_d2_w4 strip 2 4 8 -45 10 - 40 id 0 8.6e-10 1 1
a_id_d2_w8 strip 2 4 16 -45 10 - 40 id 0 8.6e-10 1 1
a_dr_d2_w16 strip 2 4 32 -45 10 - 40 dr 1e6 0 1 1
a_id_d2_w16 strip 2 4 32 -45 10 - 40 id 0 8.6e-10 1 1
a_dr_d4_w4 strip 4 4 16 -48 10 - 40 dr 1e6 0 1 1
a_dr_d4_w8 strip 4 4 32 -48 10 - 40 dr 1e6 0 1 1
a_dr_d4_w16 strip 4 4 64 -48 10 - 40 dr 1e6 0 1 1
a_id_d4_w4 strip 4 4 16 -48 10 - 40 id 0 8.6e-10 1 1
a_id_d4_w8 strip 4 4 32 -48 10 - 40 id 0 8.6e-10 1 1
a_id_d4_w16 strip 4 4 64 -48 10 - 40 id 0 8.6e-10 1 1
a_dr_d4_w8_sf03 strip 4 4 32 -48 10 - 40 dr 1e6 0 1 1 0.3
a_id_d4_w8_sf03 strip 4 4 32 -48 10 - 40 id 0 8.6e-10 1 1 0.3
a_dr_d1_w4 strip 1 4 4 -42 10 - 40 dr 1e6 0 1 1
a_dr_d1_w8 strip 1 4 8 -42 10 - 40 dr 1e6 0 1 1
a_id_d1_w8 strip 1 4 8 -42 10 - 40 id 0 8.6e-10 1 1
a_dr_d2_w4_np2 strip 2 4 8 -45 10 - 40 dr 1e6 0 2 1
b_d2_w4 strip 2 4 8 -15 10 - 40 dr 5.1e3 0 1 1
b_d2_w8 strip 2 4 16 -15 10 - 40 dr 5.1e3 0 1 1
b_d1_w4 strip 1 4 4 -12 10 - 40 dr 5.1e3 0 1 1
c2_id shape2d 2 4 30 -35 10 3 40 id 0 8.6e-10 1 1
c2_dr shape2d 2 4 30 -35 10 3 40 dr 1e6 0 1 1
c3_id shape3d 3 3 15 -15 6 3 20 id 0 8.6e-10 1 2"
fi

summary="$out/runs.csv"
header="name,kind,dim,delta_um,m,width_um,ymin_um,layer_um,open_um,end_time,interface,current_density,interface_diffusivity,ranks,threads,nodes,steps,time_step,model_limited,wall_s,safety_factor"
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
echo "$cases" | while read -r name kind delta m width ymin layer open end iface cur kls ranks threads safety; do
  safety=${safety:-0.9}
  # geometry in um; the numbers below are exact multiples of h = delta / m
  read -r h ymax nx ny xw film top dim tpl hist outint <<< "$(awk \
    -v d="$delta" -v m="$m" -v w="$width" -v y0="$ymin" -v s="$layer" \
    -v k="$kind" -v T="$end" -v sf="$safety" 'BEGIN {
      h = d / m
      if (k == "strip") { film = 0; top = s; ymax = s + d; nx = w / h; xw = w }
      else { film = d; top = d + s; ymax = top + d; nx = 2 * w / h; xw = w }
      ny = (ymax - y0) / h
      dim = (k == "shape3d") ? 3 : 2
      tpl = (k == "strip") ? "pit_strip" : "pit_" (k == "shape3d" ? "shape_3d" : "shape_2d")
      # about 200 history rows: the step is about 6e-5 s * (delta/um)^2
      hist = int(T / 200 / (6e-5 * d * d * sf / 0.9)); if (hist < 1) hist = 1
      outint = T / (dim == 3 ? 4 : 10)
      printf "%.10g %.10g %d %d %.10g %.10g %.10g %d %s %d %.10g\n",
             h, ymax, nx + 0.5, ny + 0.5, xw, film, top, dim, tpl, hist, outint }')"
  # The constants of the other interface model would have no effect (an
  # error): their lines are dropped, as in run_pit_growth_1d.sh.
  case "$iface" in
    dr) interface="dissolution rate"; drop='@KLS@' ;;
    id) interface="interface diffusivity"; drop='@I@' ;;
    *) echo "bad interface $iface" >&2; exit 2 ;;
  esac
  prm="$out/inputs/$name.prm"
  sed -e "/^ *set .*$drop/d" \
      -e "s|@W@|${width}e-6|g; s|@XW@|${xw}e-6|g; s|@S0@|${layer}e-6|g" \
      -e "s|@YMIN@|${ymin}e-6|g; s|@YMAX@|${ymax}e-6|g; s|@YTOP@|${top}e-6|g" \
      -e "s|@NX@|$nx|g; s|@NY@|$ny|g; s|@M@|$m|g; s|@END@|$end|g" \
      -e "s|@F@|${film}e-6|g; s|@A@|${open}e-6|g" \
      -e "s|@IFACE@|$interface|g; s|@I@|$cur|g; s|@KLS@|$kls|g" \
      -e "s|@HIST@|$hist|g; s|@OUT@|$outint|g; s|@DIR@|$out/runs/$name|g" \
      -e "s|@SF@|$safety|g" \
      "$here/$tpl.prm.in" > "$prm"
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
  echo "$name,$kind,$dim,$delta,$m,$width,$ymin,$layer,$open,$end,$iface,$cur,$kls,$ranks,$threads,$nodes,$steps,$dt,$limited,$wall,$safety" >> "$summary"
  echo "$name: ${dim}D $kind, delta $delta um, m $m, $interface, $nodes nodes, $steps steps (dt $dt s, model-limited: $limited), $ranks x $threads, $wall s"
done
# The bond weights of a complete neighbourhood (exact partial volumes) for
# the long-wave diffusivity of the discrete operator, K_h / K (the plot
# script reads them if present): 2D m = 4, 3D m = 3.
weights="$build/bin/perideal-weights"
if [ -x "$weights" ]; then
  "$weights" --dim 2 --m-ratio 4 > "$out/inputs/weights_2d_m4.csv"
  "$weights" --dim 3 --m-ratio 3 > "$out/inputs/weights_3d_m3.csv"
fi
/usr/bin/python3 "$here/plot_pit_growth.py" "$out"
