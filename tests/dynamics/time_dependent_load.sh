#!/usr/bin/env bash
# Usage: time_dependent_load.sh PERIDEAL NPROCS
#
# Loads that depend on t act at each step's time. A free bar [0,1] x [0,0.4]
# (10 x 4 nodes, all probed) is pushed along x by a load F(t) per unit
# volume of the bar; the internal bond forces cancel in pairs, so the mean
# displacement (the centre of mass) is the double integral of F/M,
# whatever the waves inside do:
#  - ramp  traction p t on x = 1 ('Traction'), the same through 'Boundary
#          stress' with half the stress and 'Load history = 2', and a body
#          force p t ('Body force'): X(T) = p T^3 / (6 rho).
#          Velocity Verlet integrates a linear force with the trapezoidal
#          rule, exact for the velocity; the displacement gains p dt^3 /
#          (6 rho) per step too little, X_N = X(T) (1 - (dt/T)^2): the
#          tolerance is (dt/T)^2 plus round-off.
#  - step  traction 't > t0 ? p : 0', t0 = T/2: no displacement and no
#          kinetic energy up to t0 (no impulse before the load starts), then
#          X(T) = p (T - t0)^2 / (2 rho), within p dt (T - t0 + dt) / (2 rho)
#          (Verlet with the jump between two steps; derivation in
#          doc/explicit-dynamics.md).
# A load frozen at t = 0 is zero in every case and fails each of them.
set -u
perideal="$1"; nprocs="$2"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

work="$(pwd)/time_dependent_load.np${nprocs}"
rm -rf "$work" && mkdir -p "$work" && cd "$work"

p=1e6; rho=1000; T=1e-3
# x = 0.05, 0.15, ..., 0.95 and y = 0.05, ..., 0.35: the node centres.
probes=""
for j in 0 1 2 3; do
  for i in 0 1 2 3 4 5 6 7 8 9; do
    probes="${probes:+$probes; }$(awk -v i=$i -v j=$j 'BEGIN { printf "%.2f, %.2f", 0.05 + 0.1 * i, 0.05 + 0.1 * j }')"
  done
done

# write_input NAME BOUNDARY_CONDITIONS_BODY [EXTRA explicit dynamics LINES]
write_input() {
  cat > "$1.prm" <<PRM
set Dimension = 2
set Problem type = explicit dynamics
subsection Geometry
  set Lower corner = 0, 0
  set Upper corner = 1, 0.4
  set Subdivisions = 10, 4
end
subsection Material model
  set Model = bond-based
  subsection bond-based
    set Density = $rho
  end
end
subsection Boundary conditions
$2
end
subsection explicit dynamics
  set End time = $T
  set Energy every steps = 1
  set Probe points = $probes
${3:-}
end
subsection Output
  set Directory = $1
  set Write VTU = false
end
PRM
}

run() {
  local out rc
  if [ "$nprocs" -eq 1 ]; then
    out=$("$perideal" "$1.prm" 2>&1); rc=$?
  else
    out=$(timeout 120 mpirun --oversubscribe -np "$nprocs" "$perideal" "$1.prm" 2>&1); rc=$?
  fi
  [ $rc -eq 0 ] || { echo "$out"; fail "$1: exit code $rc"; return 1; }
  n_steps=$(sed -n 's/.*time step .* s (\([0-9]*\) steps to .*/\1/p' <<<"$out")
  [ -n "$n_steps" ] || { echo "$out"; fail "$1: no step count in the log"; return 1; }
  return 0
}

# mean_ux CSV: the mean x displacement of the probes in the last row.
mean_ux() {
  awk -F, 'NR == 1 { for (k = 1; k <= NF; ++k) if ($k ~ /^probe[0-9]+_ux$/) col[++n] = k; next }
    { s = 0; for (k = 1; k <= n; ++k) s += $col[k]; m = s / n }
    END { printf "%.17g\n", m }' "$1"
}

ramp_case() {
  local name="$1" mean
  run "$name" || return
  mean=$(mean_ux "$name/energies.csv")
  awk -v m="$mean" -v p=$p -v rho=$rho -v T=$T -v n="$n_steps" -v name="$name" 'BEGIN {
      exact = p * T * T * T / (6 * rho); dt = T / n; tol = (dt / T) ^ 2 + 1e-9
      rel = (m - exact) / exact; if (rel < 0) rel = -rel
      printf "%s: centre of mass moved %.6e, closed form %.6e, relative difference %.3e (Verlet bound %.3e, %d steps)\n", name, m, exact, rel, tol, n
      exit !(rel <= tol) }' || fail "$name: the centre of mass is not where the load puts it"
}

write_input traction "  set Traction boundary ids = 1
  subsection Traction
    set Function constants  = p=$p
    set Function expression = p*t; 0
  end"
ramp_case traction

write_input stress "  set Traction boundary ids = 1
  set Traction given as = stress tensor
  subsection Boundary stress
    set Function constants  = p=$p
    set Function expression = p*t/2; 0; 0; 0
  end" "  set Load history = 2"
ramp_case stress

write_input body_force "  subsection Body force
    set Function constants  = p=$p
    set Function expression = p*t; 0
  end"
ramp_case body_force

# The step load: nothing before t0, then the parabola.
write_input step "  set Traction boundary ids = 1
  subsection Traction
    set Function constants  = p=$p, t0=5e-4
    set Function expression = t > t0 ? p : 0; 0
  end"
if run step; then
  awk -F, 'NR == 1 { for (k = 1; k <= NF; ++k) if ($k ~ /^probe/) col[++n] = k; next }
    $1 <= 5e-4 { for (k = 1; k <= n; ++k) if ($col[k] != 0) bad = 1; if ($3 != 0) bad = 1; ++rows }
    END { printf "step: %d rows up to t0, displacement and kinetic energy zero in all: %s\n", rows, bad ? "no" : "yes"; exit bad || rows < 2 }' \
    step/energies.csv || fail "step: the body moved before the load started"
  mean=$(mean_ux step/energies.csv)
  awk -v m="$mean" -v p=$p -v rho=$rho -v T=$T -v t0=5e-4 -v n="$n_steps" 'BEGIN {
      exact = p * (T - t0) ^ 2 / (2 * rho); dt = T / n; tol = p * dt * (T - t0 + dt) / (2 * rho)
      d = m - exact; if (d < 0) d = -d
      printf "step: centre of mass moved %.6e, closed form %.6e, difference %.3e (Verlet bound %.3e, %d steps)\n", m, exact, d, tol, n
      exit !(d <= tol) }' || fail "step: the centre of mass is not where the load puts it"
fi

if [ "$failures" -eq 0 ]; then echo "OK"; else exit 1; fi
