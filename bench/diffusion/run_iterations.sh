#!/usr/bin/env bash
# Iterations of the implicit solves of the diffusion problem (CG on the
# matrix-free operator, tolerance 1e-10 relative to the lifted right-hand
# side) against the grid spacing and the m-ratio, for the steady state
# (-L C = S, one solve from C = 0) and for backward Euler with a large step
# (dt = 0.1, 5 steps from C = 0), each with Preconditioner = jacobi and
# local laplacian (AMG on the 5-point finite-volume Laplacian). Unit square
# with Dirichlet layers of one horizon all round
# (bench/diffusion/iterations_2d.prm.in).
#  - h = 1/32, 1/64, 1/128, 1/256, 1/512 at m = 3;
#  - m = 2, 3, 4, 6 at h = 1/64.
#
# Usage: bench/diffusion/run_iterations.sh BUILD_DIR [--quick]
#   --quick: h = 1/32, 1/64 and m = 2, 3; 2 backward Euler steps.
#   THREADS=N (default 1): threads per run (--threads N).
# Writes results/diffusion/iterations.csv (one row per run: study, stepping,
# preconditioner, h, m, nodes, solves, mean and largest iterations per
# solve, seconds in the solves (local Laplacian and AMG set-up included),
# seconds of the AMG set-up alone, wall seconds) and iterations_h.png,
# iterations_m.png, iterations_time.png (plot_iterations.py).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/../dynamics/log_fields.sh"
build=$(cd "${1:?usage: run_iterations.sh BUILD_DIR [--quick]}" && pwd)
quick=${2:-}
threads=${THREADS:-1}
perideal="$build/bin/perideal"
[ -x "$perideal" ] || { echo "no $perideal: build the target perideal first"; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out="$(pwd)/results/diffusion"; mkdir -p "$out"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT

if [ "$quick" = "--quick" ]; then
  h_list="32 64"; m_list="2 3"; be_end=0.2
else
  h_list="32 64 128 256 512"; m_list="2 3 4 6"; be_end=0.5
fi
# case: study cells_per_unit m
cases=$(for n in $h_list; do echo "h $n 3"; done; for m in $m_list; do echo "m 64 $m"; done)

# Seconds of a TimerOutput section of a log (empty if absent).
section() { sed -n "s/^| $2 *| *[0-9]* | *\([0-9.e+-]*\)s.*/\1/p" "$1"; }

summary="$out/iterations.csv"
echo "study,stepping,preconditioner,h,m,nodes,solves,mean_iterations,max_iterations,solve_seconds,amg_setup_seconds,wall_seconds" > "$summary"
echo "$cases" | while read -r study n m; do
  for stepping in steady_state backward_Euler; do
    for pre in jacobi local_laplacian; do
      name="${study}_n${n}_m${m}_${stepping}_${pre}"
      lower=$(awk -v n=$n -v m=$m 'BEGIN { printf "%.16g", -m / n }')
      upper=$(awk -v n=$n -v m=$m 'BEGIN { printf "%.16g", 1 + m / n }')
      cells=$((n + 2 * m))
      [ "$stepping" = steady_state ] && { what="steady state"; dt=0; end=1; } \
        || { what="implicit"; dt=0.1; end=$be_end; }
      sed -e "s/@LOWER@/$lower/g; s/@UPPER@/$upper/g; s/@N@/$cells/g; s/@M@/$m/" \
          -e "s/@STEPPING@/$what/; s/@PRECONDITIONER@/${pre//_/ }/" \
          -e "s/@DT@/$dt/; s/@END@/$end/; s|@DIR@|$name|" \
          "$here/iterations_2d.prm.in" > "$work/$name.prm"
      ( cd "$work" && "$perideal" --threads "$threads" "$name.prm" < /dev/null ) > "$work/$name.log" 2>&1 \
        || { tail -20 "$work/$name.log"; echo "FAILED: $name"; exit 1; }
      cp "$work/$name.log" "$out/iterations_$name.log"
      nodes=$(sed -n 's/.*diffusion: \([0-9]*\) nodes.*/\1/p' "$work/$name.log")
      wall=$(log_field "$work/$name.log" wall)
      amg=$(section "$work/$name.log" "local Laplacian"); amg=${amg:-0}
      if [ "$stepping" = steady_state ]; then
        solve=$(section "$work/$name.log" "steady solve")
      else
        loop=$(log_field "$work/$name.log" loop)
        solve=$(awk -v a="$loop" -v b="$amg" 'BEGIN { printf "%.4g", a + b }')
      fi
      # Iterations of every solve (steady: the one row; implicit: the rows
      # after t = 0, one per step).
      read -r solves mean largest <<< "$(awk -F, -v steady="$stepping" 'NR == 1 { for (k = 1; k <= NF; ++k) c[$k] = k; next }
        steady == "steady_state" || $c["step"] > 0 { i = $c["iterations"]; s += i; ++r; if (i > l) l = i }
        END { printf "%d %.2f %d", r, (r > 0 ? s / r : 0), l }' "$work/$name/history.csv")"
      echo "$study,${stepping//_/ },${pre//_/ },$(awk -v n=$n 'BEGIN { printf "%.10g", 1 / n }'),$m,$nodes,$solves,$mean,$largest,$solve,$amg,$wall" >> "$summary"
      echo "$name: $nodes nodes, $solves solve(s), iterations mean $mean max $largest, solves $solve s (AMG set-up $amg s), wall $wall s"
    done
  done
done
if /usr/bin/python3 -c 'import matplotlib' 2> /dev/null; then
  /usr/bin/python3 "$here/plot_iterations.py" "$out"
else
  echo "matplotlib not importable by /usr/bin/python3: no plots"
fi
