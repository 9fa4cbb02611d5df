# Shared by the tests' run scripts (sourced): running perideal on 1 or N
# MPI processes, and the checks of its PVD output series.

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# run_perideal PERIDEAL NPROCS [DIR]: perideal on DIR/input.prm (DIR
# defaults to the current directory) on NPROCS MPI processes, one thread
# each when there are several, its output in DIR/log. Returns its exit
# code.
run_perideal() {
  local perideal="$1" nprocs="$2" dir="${3:-.}"
  if [ "$nprocs" -eq 1 ]; then
    (cd "$dir" && "$perideal" input.prm > log 2>&1)
  else
    (cd "$dir" && mpirun --oversubscribe -np "$nprocs" "$perideal" input.prm \
       --threads 1 > log 2>&1)
  fi
}

# check_output_series NPROCS [FIELD]: the run's 'Output/Directory' (from
# input.prm, default output; set as $dir) holds solution.pvd, every record
# it names exists with one VTU piece per process (and a FIELD field when
# given), and no temporary file is left. Exits with FAIL otherwise.
check_output_series() {
  local nprocs="$1" field="${2:-}" pvd record pieces
  dir=$(sed -n 's/^ *set Directory *= *//p' input.prm); dir=${dir:-output}
  pvd="$dir/solution.pvd"
  [ -f "$pvd" ] || { cat log; echo "FAIL: no $pvd"; exit 1; }
  for record in $(sed -n 's/.*file="\([^"]*\)".*/\1/p' "$pvd"); do
    [ -f "$dir/$record" ] || { echo "FAIL: $record named in $pvd is missing"; exit 1; }
    pieces=$(grep -c "<Piece" "$dir/$record")
    [ "$pieces" -eq "$nprocs" ] || { echo "FAIL: $record has $pieces pieces"; exit 1; }
    [ -z "$field" ] || grep -q "Name=\"$field\"" "$dir/$record" \
      || { echo "FAIL: $record has no $field field"; exit 1; }
  done
  ! ls "$dir"/*.tmp > /dev/null 2>&1 || { echo "FAIL: temporary files remain"; exit 1; }
}
