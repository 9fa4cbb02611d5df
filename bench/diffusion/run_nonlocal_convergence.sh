#!/usr/bin/env bash
# Verification of the diffusion problem type against analytic NONLOCAL
# solutions: a Fourier mode
#   C = exp(-lambda t) sin(k1 x) sin(k2 y) [sin(k3 z)]
# on the unit square (cube), with the same formula prescribed in a Dirichlet
# layer one horizon thick around it, is an exact solution of the continuous
# PD equation; lambda = lambda(|k|) is the symbol of the PD operator
# (tests/diffusion/reference/fourier_mode.py, 30 digits). Crank-Nicolson
# with dt small enough that its error (~ lambda T (lambda dt)^2 / 12) is
# below 1e-5, or forward Euler compared with its time-discrete exact
# solution, so the errors are those of space. Every row also carries the
# error predicted by the discrete symbol lambda_h of the one-point rule
# (fourier_mode.py --weights, with perideal-weights).
#
#   bash bench/diffusion/run_nonlocal_convergence.sh BUILD_DIR [--quick]
#        [--output-dir DIR]
#
# Studies (rows of DIR/nonlocal_convergence.csv):
#   m_2d      2D, q = 1, constant omega, delta = 1/8, k = (2 pi, 2 pi),
#             m = delta/dx = 2, 3, 4, 6, 8: error against the PD solution
#             (m-convergence: the quadrature error of the one-point rule);
#             the configuration of tests/diffusion/fourier_mode_2d.prm.
#   m_2d_fe   2D, q = 0, Gaussian omega, forward Euler, on the strip of
#             tests/diffusion/fourier_mode_2d_explicit.prm, m = 2 ... 8.
#   m_3d      3D, q = 1, conical omega, delta = 1/3, k = (pi, pi, pi),
#             m = 2, 3, 4, 5 (tests/diffusion/fourier_mode_3d.prm: m = 4).
#   delta_2d  2D as m_2d, m = 3 and 4 fixed, delta = 1/4 ... 1/32: error
#             against the PD solution and against the CLASSICAL solution
#             exp(-K|k|^2 t) sin sin (each a run of its own).
#   delta_3d  3D as m_3d, m = 3, delta = 1/4, 1/8 (full run only).
# --quick: fewer points. Each run on one process, one thread; the wall time
# is the driver's 'total wall time'. Writes DIR/nonlocal_convergence.csv,
# DIR/logs/, DIR/inputs/, DIR/runs/ and (matplotlib) DIR/error_vs_spacing.png,
# DIR/error_vs_wall_time.png, and prints the tables. DIR defaults to
# results/diffusion_nonlocal_convergence. Nothing is built: BUILD_DIR must
# hold bin/perideal and bin/perideal-weights.
set -euo pipefail
usage="usage: bash bench/diffusion/run_nonlocal_convergence.sh BUILD_DIR [--quick] [--output-dir DIR]"
[ $# -ge 1 ] || { echo "$usage" >&2; exit 2; }
build="$1"; shift
perideal="$(cd "$build" && pwd)/bin/perideal"
[ -x "$perideal" ] || { echo "no $perideal" >&2; exit 2; }
cd "$(dirname "$0")/../.."
root=$(pwd)
quick=0
out=results/diffusion_nonlocal_convergence
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --output-dir) out="$2"; shift ;;
    *) echo "$usage" >&2; exit 2 ;;
  esac
  shift
done
mkdir -p "$out/logs" "$out/inputs"
out=$(cd "$out" && pwd)
python=/usr/bin/python3
mode="$root/tests/diffusion/reference/fourier_mode.py"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# Studies: "name dim q omega K T steps scheme domain k-vector m-list
# delta-list refs" (k and the lists comma-separated; delta as 1/N). domain
# square: the unit square (cube), f = sin(k1 x) sin(k2 y) [sin(k3 z)];
# strip (2D): (0, 1) x (0, 0.5), f = sin(k1 x + 1) cos(k2 y) (the input of
# tests/diffusion/fourier_mode_2d_explicit.prm). scheme cn:
# Crank-Nicolson, compared with exp(-lambda t) f(x); fe: forward Euler,
# compared with its time-discrete exact solution (1 - lambda dt)^(t/dt) f(x)
# (no time error at all: C^n = (1 - lambda dt)^n f solves the forward Euler
# recursion of the continuous operator).
if [ $quick -eq 1 ]; then
  studies=(
    "m_2d 2 1 constant 1 0.0125 100 cn square 2*pi,2*pi 2,3,4,6 1/8 pd"
    "m_2d_fe 2 0 gaussian 1 0.008 20 fe strip 2*pi,3*pi 2,3,4 1/8 pd"
    "m_3d 3 1 conical 1 0.035 40 cn square pi,pi,pi 2,3 1/3 pd"
    "delta_2d 2 1 constant 1 0.0125 100 cn square 2*pi,2*pi 3 1/4,1/8,1/16 pd,classical"
  )
else
  studies=(
    "m_2d 2 1 constant 1 0.0125 100 cn square 2*pi,2*pi 2,3,4,6,8 1/8 pd"
    "m_2d_fe 2 0 gaussian 1 0.008 20 fe strip 2*pi,3*pi 2,3,4,6,8 1/8 pd"
    "m_3d 3 1 conical 1 0.035 40 cn square pi,pi,pi 2,3,4,5 1/3 pd"
    "delta_2d 2 1 constant 1 0.0125 100 cn square 2*pi,2*pi 3,4 1/4,1/8,1/16,1/32 pd,classical"
    "delta_3d 3 1 conical 1 0.035 40 cn square pi,pi,pi 3 1/4,1/8 pd,classical"
  )
fi

csv="$out/nonlocal_convergence.csv"
echo "study,dim,q,omega,m,delta,dx,nodes,k_norm,end_time,steps,lambda_pd,lambda_classical,lambda_h,long_wave_ratio,reference,relative_l2_error,max_error,predicted_error,pd_classical_gap,wall_s" > "$csv"
weights="$(dirname "$perideal")/perideal-weights"
[ -x "$weights" ] || { echo "no $weights" >&2; exit 2; }

for study in "${studies[@]}"; do
  read -r name dim q omega K T steps scheme domain kvec mlist dlist refs <<< "$study"
  for delta in ${dlist//,/ }; do
    N=${delta#1/}
    # lambda of the PD operator, |k|^2 K, the components of k (17 digits)
    read -r lam classical knorm k1 k2 k3 <<< "$($python - "$mode" "$dim" "$q" "$omega" "$delta" "$K" "$kvec" <<'PY'
import subprocess, sys
import mpmath as mp
script, dim, q, omega, delta, K, kvec = sys.argv[1:]
res = subprocess.run(["/usr/bin/python3", script, "--dim", dim, "--q", q,
                      "--omega", omega, "--delta", delta, "--K", K,
                      "--k", kvec], check=True, capture_output=True,
                     text=True).stdout
vals = {a.strip(): b for a, b in (line.split("=") for line in res.strip().splitlines())}
k = [mp.mpf(eval(c, {"pi": mp.pi})) for c in kvec.split(",")] + [0] * 3
print(mp.nstr(mp.mpf(vals["lambda"]), 17), mp.nstr(mp.mpf(vals["K|k|^2"]), 17),
      mp.nstr(mp.sqrt(sum(c * c for c in k)), 17),
      " ".join(mp.nstr(c, 17) for c in k[:3]))
PY
)"
    [ -n "${k1:-}" ] || { echo "FAIL: lambda for $name, delta = $delta" >&2; exit 1; }
    for m in ${mlist//,/ }; do
      n=$((m * (N + 2)))          # (1 + 2 delta) / dx, dx = delta / m
      # the discrete symbol (one-point rule, exact partial volumes)
      "$weights" --dim "$dim" --m-ratio "$m" > "$out/inputs/weights_${dim}d_m$m.csv"
      lam_h=$($python "$mode" --dim "$dim" --q "$q" --omega "$omega" \
                --delta "$delta" --K "$K" --k "$kvec" --digits 17 \
                --weights "$out/inputs/weights_${dim}d_m$m.csv" --m-ratio "$m" \
              | sed -n 's/^lambda_h = //p')
      # lambda_h / lambda for |k| delta -> 0 (= lambda_h / (K |k|^2)): at
      # fixed m the discrete model tends to classical diffusion with this
      # factor on K as delta -> 0
      zero=$(printf '0,%.0s' $(seq 2 "$dim")); kzero="1e-3,${zero%,}"
      long=$($python "$mode" --dim "$dim" --q "$q" --omega "$omega" \
                --delta 1 --K 1 --k "$kzero" --digits 12 \
                --weights "$out/inputs/weights_${dim}d_m$m.csv" --m-ratio "$m" \
              | sed -n 's/^lambda_h \/ lambda = //p')
      for ref in ${refs//,/ }; do
        tag="${name}_m${m}_delta1-${N}_${ref}"
        prm="$out/inputs/$tag.prm"
        if [ "$dim" -eq 2 ] && [ "$domain" = strip ]; then
          lo="-$delta, -$delta"; hi="1+$delta, 0.5+$delta"
          sub="$n, $((m * (N + 4) / 2))"
          ids="0, 1, 2, 3"; shape="sin(k1*x + 1)*cos(k2*y)"
        elif [ "$dim" -eq 2 ]; then
          lo="-$delta, -$delta"; hi="1+$delta, 1+$delta"; sub="$n, $n"
          ids="0, 1, 2, 3"; shape="sin(k1*x)*sin(k2*y)"
        else
          lo="-$delta, -$delta, -$delta"; hi="1+$delta, 1+$delta, 1+$delta"
          sub="$n, $n, $n"; ids="0, 1, 2, 3, 4, 5"
          shape="sin(k1*x)*sin(k2*y)*sin(k3*z)"
        fi
        lo=$($python -c "print(', '.join(repr(eval(c)) for c in '$lo'.split(',')))")
        hi=$($python -c "print(', '.join(repr(eval(c)) for c in '$hi'.split(',')))")
        rate=$lam; [ "$ref" = pd ] || rate=$classical
        dt=$($python -c "print(repr($T / $steps))")
        consts="k1=$k1, k2=$k2, k3=$k3, dt=$dt"
        if [ "$scheme" = cn ]; then
          stepping="  set Time stepping      = implicit
  set Implicit scheme    = Crank-Nicolson
  set Solver tolerance   = 1e-12"
          decay="exp(-lam*t)"
        else
          stepping="  set Time stepping      = explicit"
          decay="(1 - lam*dt)^(t/dt)"
        fi
        cat > "$prm" <<EOF
# $tag: generated by bench/diffusion/run_nonlocal_convergence.sh
set Dimension = $dim
set Problem type = diffusion
subsection Geometry
  set Lower corner = $lo
  set Upper corner = $hi
  set Subdivisions = $sub
end
subsection Horizon
  set m-ratio = $m
end
subsection diffusion
  set Diffusivity        = $K
  set Flux exponent      = $q
  set Influence function = $omega
$stepping
  set Time step          = $dt
  set End time           = $T
  set Dirichlet boundary ids    = $ids
  set Dirichlet layer thickness = 1
  subsection Initial concentration
    set Function constants  = $consts
    set Function expression = $shape
  end
  subsection Source
    set Function expression = 0
  end
  subsection Boundary concentration
    set Function constants  = $consts, lam=$lam
    set Function expression = $decay*$shape
  end
  set Compare with analytical solution = true
  subsection Analytical concentration
    set Function constants  = $consts, lam=$rate
    set Function expression = $decay*$shape
  end
  set History every steps = $steps
  set History file        = history.csv
  set Progress interval   = 0
end
subsection Output
  set Directory = $out/runs/$tag
end
EOF
        # the PVTU output of the first and last step is written too (small)
        log="$out/logs/$tag.log"
        if ! "$perideal" --threads 1 "$prm" > "$log" 2>&1; then
          tail -20 "$log"; echo "FAIL: $tag" >&2; exit 1
        fi
        last=$(tail -1 "$out/runs/$tag/history.csv")
        err=$(echo "$last" | awk -F, '{ print $7 }')
        maxerr=$(echo "$last" | awk -F, '{ print $8 }')
        nodes=$(sed -n 's/.*diffusion: \([0-9]*\) nodes.*/\1/p' "$log")
        wall=$(sed -n 's/^total wall time \([0-9.e+-]*\) s.*/\1/p' "$log")
        gap=$($python -c "import math; print(abs(math.expm1(($classical - $lam) * $T)))")
        # interior error predicted by the discrete symbol
        if [ "$scheme" = cn ]; then
          predicted=$($python -c "import math; print(abs(math.expm1(($rate - $lam_h) * $T)))")
        else
          predicted=$($python -c "print(abs(((1 - $lam_h * $dt) / (1 - $rate * $dt))**$steps - 1))")
        fi
        dx=$($python -c "print(repr(1 / ($N * $m)))")
        echo "$name,$dim,$q,$omega,$m,$($python -c "print(repr(1/$N))"),$dx,$nodes,$knorm,$T,$steps,$lam,$classical,$lam_h,$long,$ref,$err,$maxerr,$predicted,$gap,$wall" >> "$csv"
        printf "%-34s %7s nodes  error %.4e  predicted %.4e  (%s s)\n" "$tag" "$nodes" "$err" "$predicted" "$wall"
      done
    done
  done
done

if /usr/bin/python3 -c 'import matplotlib' 2>/dev/null; then
  /usr/bin/python3 "$root/bench/diffusion/plot_nonlocal_convergence.py" "$csv" "$out"
else
  echo "matplotlib is not importable by /usr/bin/python3: CSV written, plots skipped." >&2
fi
echo "written: $csv"
