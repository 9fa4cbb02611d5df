# Fields of a perideal explicit-dynamics log, for the benchmark scripts
# (sourced): log_field LOG nodes|bonds|visits|steps|loop|wall|memory
#   nodes, bonds, visits: of the set-up lines (bond visits per step);
#   steps: the number of time steps; loop: seconds in the time loop
#   (TimerOutput); wall: total wall time; memory: peak MB over processes.
log_field() {
  case "$2" in
    nodes)  sed -n 's/.*explicit dynamics: \([0-9]*\) nodes.*/\1/p' "$1" ;;
    bonds)  sed -n 's/.*bonds: \([0-9]*\) .*/\1/p' "$1" ;;
    visits) sed -n 's/.* \([0-9]*\) bond visits per step.*/\1/p' "$1" ;;
    steps)  sed -n 's/.*time step .* (\([0-9]*\) steps.*/\1/p' "$1" ;;
    loop)   sed -n 's/^| time steps *| *1 | *\([0-9.e+-]*\)s.*/\1/p' "$1" ;;
    wall)   sed -n 's/^total wall time \([0-9.e+-]*\) s.*/\1/p' "$1" ;;
    memory) sed -n 's/.*peak memory (all processes) \([0-9.e+-]*\) MB.*/\1/p' "$1" ;;
    *) echo "log_field: unknown field $2" >&2; return 1 ;;
  esac
}
