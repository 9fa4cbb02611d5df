#!/usr/bin/env bash
# Usage: hybrid_impact.sh PERIDEAL
#
# The adaptive hybrid scheme under an impact (a coarse Kalthoff-Winkler
# plate, h = 2 mm, m = 3, 16 m/s, 90 us; bench/dynamics/
# kalthoff_winkler_2d.prm.in at its coarsest), where the stress wave takes
# some bonds from below alpha s0 to beyond s0 within one step: late
# switches (doc/collocation.md, "Late switches"). Kinds of check: exact
# invariants and an independent reference (the all-standard run):
#  - 1 process (2 threads) and 2 processes (1 thread) break the same bonds
#    and switch the same nodes at every step, with the same late switches
#    (the broken-bond and standard-node columns of the energy file at
#    every step, exactly; energies to 1e-8 relative). Before the fix in
#    BondOperator::commit_broken_bonds() a process without a late switch
#    of its own kept its old work lists when another process had one, and
#    the two runs parted at step 120 (43 against 45 late switches);
#  - the run has late switches (else this tests nothing), warns once while
#    it runs and once at the end, naming 'Critical stretch fraction';
#  - against the all-standard run: broken bonds at the end within 5 %
#    (5252 against 5171 when written, +1.6 %). The crack tip is not compared: on
#    this 2-mm grid it moves by two to three cells with alpha alone (0.8:
#    6.3 mm from the all-standard tip; 0.6: 4.5 mm; 0.4: 2.8 mm); at 1 mm
#    the tips agree within a cell (doc/collocation.md, "Late switches").
set -u
perideal="$1"
work="$(pwd)/hybrid_impact"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fail() { echo "FAIL: $*"; exit 1; }

cat > standard.prm <<'PRM'
set Dimension = 2
set Problem type = explicit dynamics
subsection Geometry
  set Lower corner = 0, -0.1
  set Upper corner = 0.1, 0.1
  set Subdivisions = 50, 100
end
subsection Horizon
  set m-ratio = 3
end
subsection Material model
  set Model = bond-based
  subsection bond-based
    set Young's modulus = 191e9
    set Poisson's ratio = 0.25
    set Plane model     = plane strain
    set Density         = 8000
    set Fracture energy = 42408
  end
end
subsection Boundary conditions
  set Dirichlet boxes = 0, -0.025, 0.006, 0.025
  set Dirichlet components = x
  subsection Dirichlet displacement
    set Variable names      = x,y,t
    set Function expression = 16; 0
  end
end
subsection explicit dynamics
  set End time            = 90e-6
  set Prescribed quantity = velocity
  set Pre-cracks          = 0, -0.025, 0.05, -0.025; 0, 0.025, 0.05, 0.025
  set Crack tip origin    = 0.05, 0.025
  set Crack tip region    = 0.0495, 0.025, 0.1, 0.1
  set Output interval     = 90e-6
  set Energy every steps  = 1
  set Progress interval   = 0
end
subsection Output
  set Directory = out
end
PRM
{ cat standard.prm
  printf 'subsection Quadrature\n  set Scheme = hybrid\n'
  printf '  subsection collocation\n    set Stabilisation = all orders\n  end\nend\n'
} > hybrid.prm

for name in standard hybrid1 hybrid2; do mkdir -p "$name"; done
cp standard.prm standard/input.prm; cp hybrid.prm hybrid1/input.prm; cp hybrid.prm hybrid2/input.prm
(cd standard && "$perideal" --threads 2 input.prm > log 2>&1) || { tail -5 standard/log; fail "the all-standard run failed"; }
(cd hybrid1 && "$perideal" --threads 2 input.prm > log 2>&1) || { tail -5 hybrid1/log; fail "the hybrid run on 1 process failed"; }
(cd hybrid2 && mpirun --oversubscribe -np 2 "$perideal" --threads 1 input.prm > log 2>&1) || { tail -5 hybrid2/log; fail "the hybrid run on 2 processes failed"; }

# Columns: time,step,kinetic,elastic,work,balance,broken_bonds,standard_nodes,tip_x,tip_y,...
h1=hybrid1/out/energies.csv; h2=hybrid2/out/energies.csv; s=standard/out/energies.csv
head -1 "$h1" | grep -q "broken_bonds,standard_nodes,tip_x,tip_y" || fail "unexpected columns: $(head -1 "$h1")"
cmp -s <(cut -d, -f2,7,8 "$h1") <(cut -d, -f2,7,8 "$h2") || {
  paste -d'|' <(cut -d, -f2,7,8 "$h1") <(cut -d, -f2,7,8 "$h2") | awk -F'|' '$1 != $2' | head -3
  fail "1 and 2 processes broke different bonds or switched different nodes (step,broken,standard shown)"; }
paste -d, <(cut -d, -f3 "$h1") <(cut -d, -f3 "$h2") | awk -F, 'NR > 1 { d = $1 - $2; if (d < 0) d = -d; if (d > 1e-8 * ($1 + 1e-300)) { print "kinetic energy " $1 " against " $2 " at row " NR; bad = 1; exit } } END { exit bad }' \
  || fail "the energies of 1 and 2 processes differ by more than 1e-8"

late1=$(sed -n 's/.* \([0-9][0-9]*\) late switches.*/\1/p' hybrid1/log | head -1)
late2=$(sed -n 's/.* \([0-9][0-9]*\) late switches.*/\1/p' hybrid2/log | head -1)
[ -n "$late1" ] && [ "$late1" -gt 0 ] || fail "no late switch (${late1:-none}): this input no longer tests them"
[ "$late1" = "$late2" ] || fail "late switches: $late1 on 1 process, $late2 on 2"
for log in hybrid1/log hybrid2/log; do
  [ "$(grep -c "^Warning: by step .* late switch" "$log")" -eq 1 ] || fail "$log: not one warning while the run goes on"
  [ "$(grep -c "^Warning: $late1 late switches: .*Critical stretch fraction" "$log")" -eq 1 ] || fail "$log: not one warning at the end"
done
grep -q "Warning" standard/log && fail "the all-standard run warns"

b_std=$(tail -1 "$s" | cut -d, -f7)
b_hyb=$(tail -1 "$h1" | cut -d, -f7)
awk -v a="$b_hyb" -v b="$b_std" 'BEGIN { d = (a - b) / b; if (d < 0) d = -d; exit !(d <= 0.05) }' \
  || fail "broken bonds: hybrid $b_hyb against all-standard $b_std (more than 5 %)"
echo "OK: hybrid under impact: 1 and 2 processes agree at every step ($late1 late switches, warned); broken bonds $b_hyb against $b_std all-standard"
