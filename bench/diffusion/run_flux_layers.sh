#!/usr/bin/env bash
# What the treatment of a flux (Neumann) boundary does to the error: the
# paper's Example 2 (tests/diffusion/manufactured_2d.prm, C = sin(5t)
# (x^2 y^2 + x^3 y + x^4 + x y^3 + y^4) with its source) on (-0.5, 0.5)^2,
# the exact values prescribed in Dirichlet layers of one horizon on y =
# +-0.5, and on x = +-0.5 the flux into the body q = K dC/dn of the
# manufactured solution, given through ('diffusion/Flux layer values'):
#   source  a layer of one horizon inside the body whose nodes get the
#           source q / delta (the PD convention: the flux spread over the
#           layer); the body ends at x = +-0.5 (free surface);
#   mirror  a fictitious layer of one horizon outside the body, filled by
#           the even reflection C(x_m) + |x - x_m| q(x_b) / K (a first-order
#           Taylor expansion about the surface point with the normal
#           gradient the flux gives, exact for quadratics along the normal).
# Forward Euler, dt = 1e-5, to t = 0.2, m = 4, dx = 1/39 and 1/78, the
# micro-diffusivity calibrated on the lattice (so that the interior error
# is small and the boundary's shows) and on the continuum (the paper's
# Eq. 25). Writes results/diffusion/flux_layers.csv (mode, calibration, dx,
# nodes, relative l2 error and largest nodal error at the end, wall
# seconds) and flux_layers.png (error against dx and against wall time).
#
# Usage: bench/diffusion/run_flux_layers.sh BUILD_DIR [--quick]
#   --quick: t = 0.005 and dx = 1/39 only.
set -eu
build="$(cd "$1" && pwd)"; quick="${2:-}"
here="$(cd "$(dirname "$0")" && pwd)"
out="$(pwd)/results/diffusion"; mkdir -p "$out/flux_layers"
end=0.2; grids="39 78"
[ "$quick" = "--quick" ] && { end=0.005; grids="39"; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export LD_LIBRARY_PATH="$build/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
csv="$out/flux_layers.csv"
echo "mode,calibration,dx,nodes,relative_l2_error,max_error,wall_s" > "$csv"
# The flux into the body through x = +-0.5 at the surface point (x, y):
# K dC/dn with n = (sign(x), 0) and x = +-0.5 in the derivative (the
# 'source' mode evaluates it at the layer nodes; with X = 0.5 sign(x) both
# modes see the same surface data).
flux='sin(5*t)*sign(x)*(2*(0.5*sign(x))*y^2 + 3*(0.5*sign(x))^2*y + 4*(0.5*sign(x))^3 + y^3)'
for n in $grids; do
  delta=$(python3 -c "print(4 / $n)")
  half_out=$(python3 -c "print(0.5 + 4 / $n)")
  for calibration in lattice continuum; do
    for mode in source mirror; do
      if [ "$mode" = source ]; then xhalf=0.5; nx=$n; else xhalf=$half_out; nx=$((n + 8)); fi
      ny=$((n + 8))
      tag="${mode}_${calibration}_$n"
      dir="$out/flux_layers/$tag"
      sed -e "s/set Lower corner = .*/set Lower corner = -$xhalf, -$half_out/" \
          -e "s/set Upper corner = .*/set Upper corner = $xhalf, $half_out/" \
          -e "s/set Subdivisions = .*/set Subdivisions = $nx, $ny/" \
          -e "s/set Function constants  = d=.*/set Function constants  = d=$delta/" \
          -e "s/set End time           = .*/set End time = $end/" \
          -e "s/set Output interval     = .*/set Output interval = 0/" \
          -e "s/set History every steps = .*/set History every steps = 1000/" \
          -e "s|set Directory = out|set Directory = $dir\n  set Write VTU = false|" \
          -e "s/  set Dirichlet boundary ids    = 0, 1, 2, 3/  set Dirichlet boundary ids = 2, 3\n  set Flux boundary ids = 0, 1\n  set Flux layer values = $mode\n  set Micro-diffusivity calibration = $calibration\n  subsection Boundary flux\n    set Function expression = $flux\n  end/" \
          "$here/../../tests/diffusion/manufactured_2d.prm" > "$out/flux_layers/$tag.prm"
      start=$(date +%s.%N)
      "$build/bin/perideal" "$out/flux_layers/$tag.prm" --threads 1 > "$out/flux_layers/$tag.log" 2>&1 < /dev/null \
        || { cat "$out/flux_layers/$tag.log"; exit 1; }
      wall=$(python3 -c "import time; print(round(time.time() - $start, 2))")
      last=$(tail -1 "$dir/history.csv")
      rel=$(cut -d, -f7 <<<"$last"); max=$(cut -d, -f8 <<<"$last")
      echo "$mode,$calibration,1/$n,$((nx * ny)),$rel,$max,$wall" | tee -a "$csv"
    done
  done
done
/usr/bin/python3 - "$csv" "$out/flux_layers.png" <<'PY'
import csv, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.ticker import NullFormatter
rows = list(csv.DictReader(open(sys.argv[1])))
fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
for mode in ["source", "mirror"]:
    for calibration, style in [("lattice", "-o"), ("continuum", "--s")]:
        sel = [r for r in rows if r["mode"] == mode and r["calibration"] == calibration]
        if not sel:
            continue
        dx = [1 / float(r["dx"].split("/")[1]) for r in sel]
        err = [float(r["relative_l2_error"]) for r in sel]
        wall = [float(r["wall_s"]) for r in sel]
        axes[0].loglog(dx, err, style, label=f"{mode}, {calibration}")
        axes[1].loglog(wall, err, style, label=f"{mode}, {calibration}")
axes[0].set_xlabel("dx (m = 4)")
axes[1].set_xlabel("wall time (s, 1 core)")
for ax in axes:
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_ylabel("relative l2 error at the end")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
fig.suptitle("Example 2 with a flux on x = +-0.5: flux layer values")
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)
PY
echo "wrote $csv and $out/flux_layers.png"
