#!/usr/bin/env bash
# What the treatment of the Dirichlet layers does to the error: the paper's
# Example 2 (tests/diffusion/manufactured_2d.prm) to t = 0.2 with forward
# Euler (dt = 1e-5), m = 4, dx = 1/39 and 1/78, the micro-diffusivity
# calibrated on the continuum (the paper's Eq. 25) or on the lattice, and
# the three ways of filling the layer of one horizon outside the square
# ('diffusion/Dirichlet layer values'):
#   function       the exact solution at every layer node (needs it inside
#                  the layer: only a manufactured problem has that);
#   surface value  the boundary value at the nearest point of the surface,
#                  extended as a constant through the layer (what a user
#                  who knows only the boundary data would do naively);
#   mirror         2 g(x_b) - C(x_m): odd reflection through the surface of
#                  the solution at the mirror node (a first-order Taylor
#                  extrapolation through the boundary value; reflected again
#                  near corners).
# Writes results/diffusion/layer_values.csv (mode, calibration, dx, nodes,
# relative l2 error and largest nodal error at t = 0.2, wall seconds) and
# layer_values.png (error against dx per mode and calibration).
#
# Usage: bench/diffusion/run_layer_values.sh BUILD_DIR [--quick]
#   --quick: t = 0.005 and dx = 1/39 only.
set -eu
build="$(cd "$1" && pwd)"; quick="${2:-}"
here="$(cd "$(dirname "$0")" && pwd)"
out="$(pwd)/results/diffusion"; mkdir -p "$out/layer_values"
end=0.2; grids="39 78"
[ "$quick" = "--quick" ] && { end=0.005; grids="39"; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
csv="$out/layer_values.csv"
echo "mode,calibration,dx,nodes,relative_l2_error,max_error,wall_s" > "$csv"
for n in $grids; do
  cells=$((n + 8))
  half=$(python3 -c "print(0.5 + 4 / $n)")
  delta=$(python3 -c "print(4 / $n)")
  for calibration in continuum lattice; do
    for mode in function "surface value" mirror; do
      tag="${mode// /_}_${calibration}_$n"
      dir="$out/layer_values/$tag"
      sed -e "s/set Lower corner = .*/set Lower corner = -$half, -$half/" \
          -e "s/set Upper corner = .*/set Upper corner = $half, $half/" \
          -e "s/set Subdivisions = .*/set Subdivisions = $cells, $cells/" \
          -e "s/set Function constants  = d=.*/set Function constants  = d=$delta/" \
          -e "s/set End time           = .*/set End time = $end/" \
          -e "s/set Output interval     = .*/set Output interval = 0/" \
          -e "s/set History every steps = .*/set History every steps = 1000/" \
          -e "s|set Directory = out|set Directory = $dir\n  set Write VTU = false|" \
          -e "s/  set Dirichlet layer thickness = 1/  set Dirichlet layer thickness = 1\n  set Dirichlet layer values = $mode\n  set Micro-diffusivity calibration = $calibration/" \
          "$here/../../tests/diffusion/manufactured_2d.prm" > "$out/layer_values/$tag.prm"
      start=$(date +%s.%N)
      "$build/bin/perideal" "$out/layer_values/$tag.prm" --threads 1 > "$out/layer_values/$tag.log" 2>&1 < /dev/null
      wall=$(python3 -c "import time; print(round(time.time() - $start, 2))")
      last=$(tail -1 "$dir/history.csv")
      rel=$(cut -d, -f7 <<<"$last"); max=$(cut -d, -f8 <<<"$last")
      echo "$mode,$calibration,1/$n,$((cells * cells)),$rel,$max,$wall" | tee -a "$csv"
    done
  done
done
/usr/bin/python3 - "$csv" "$out/layer_values.png" <<'PY'
import csv, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
rows = list(csv.DictReader(open(sys.argv[1])))
fig, ax = plt.subplots(figsize=(6, 4.5))
for mode in ["function", "surface value", "mirror"]:
    for calibration, style in [("continuum", "-o"), ("lattice", "--s")]:
        sel = [r for r in rows if r["mode"] == mode and r["calibration"] == calibration]
        if not sel:
            continue
        dx = [1 / float(r["dx"].split("/")[1]) for r in sel]
        err = [float(r["relative_l2_error"]) for r in sel]
        ax.loglog(dx, err, style, label=f"{mode}, {calibration}")
ax.set_xlabel("dx (m = 4)")
ax.set_ylabel("relative l2 error at the end")
ax.set_title("Example 2: Dirichlet layer values")
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)
PY
echo "wrote $csv and $out/layer_values.png"
