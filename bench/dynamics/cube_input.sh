# The input of the cube of run_lammps_comparison.sh with its probe and
# initial velocity at the centre, for the benchmark scripts (sourced):
#   cube_input MODEL N S0 STEPS EVERY > cube.prm
# MODEL pmb or lps; N^3 nodes, h = 1 mm, delta = 3.0001 h, K = 48 GPa,
# G = 28.8 GPa, rho = 2440 kg/m^3, dt = 5e-8 s; S0 the critical stretch;
# STEPS steps, energies every EVERY steps.
cube_input() {
  local model=$1 N=$2 s0=$3 steps=$4 every=$5
  local h=1e-3 K=48e9 G=28.8e9 rho=2440 dt=5e-8 pd_model influence L xc delta
  case $model in
    pmb) pd_model="bond-based"; influence=constant ;;
    lps) pd_model="linear peridynamic solid"; influence="inverse distance" ;;
    *) echo "cube_input: unknown model $model" >&2; return 1 ;;
  esac
  delta=$(awk -v h=$h 'BEGIN { printf "%.10g", 3.0001 * h }')
  L=$(awk -v N=$N -v h=$h 'BEGIN { printf "%.17g", N * h }')
  xc=$(awk -v L=$L 'BEGIN { printf "%.17g", L / 2 }')
  sed -e "s/@N@/$N/g; s/@L@/$L/g; s/@delta@/$delta/g; s/@K@/$K/g; s/@G@/$G/g; s/@rho@/$rho/g; s/@s0@/$s0/g" \
      -e "s/@model@/$pd_model/g; s/@influence@/$influence/g" \
      -e "s/@end_time@/$(awk -v n=$steps -v dt=$dt 'BEGIN { printf "%.17g", n * dt }')/; s/@dt@/$dt/; s/@every@/$every/" \
      -e "s/@px@/$xc/; s/@py@/$xc/; s/@pz@/$xc/" \
      -e "s|@vx@|20*(x-$xc)/$L|; s|@vy@|10*(y-$xc)/$L+3*sin(300*x)|; s|@vz@|-10*(z-$xc)/$L|" \
      "$(dirname "${BASH_SOURCE[0]}")/lammps_cube.prm.in"
}
