# Sourced by the bench/run_*.sh scripts that run the perideal driver:
#   driver_study_setup DEFAULT_OUTPUT_DIR "$@"
# parses [--quick] [--output-dir DIR], sets $quick (0/1), $out (absolute,
# with a logs/ subdirectory) and $perideal (the driver, built in $BUILD_DIR,
# default build/, unless PERIDEAL_SKIP_BUILD=1 as under ctest, where two
# builds at once must not happen), and lets Open MPI run as root.
driver_study_setup() {
  local script="bench/$(basename "$0")"
  quick=0
  out="$1"; shift
  while [ $# -gt 0 ]; do
    case "$1" in
      --quick) quick=1 ;;
      --output-dir) out="$2"; shift ;;
      *) echo "usage: bash $script [--quick] [--output-dir DIR]" >&2; exit 2 ;;
    esac
    shift
  done
  mkdir -p "$out/logs"
  out=$(cd "$out" && pwd)

  local build="${BUILD_DIR:-build}"
  if [ ! -f "$build/CMakeCache.txt" ]; then
    cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release
  fi
  [ "${PERIDEAL_SKIP_BUILD:-0}" = 1 ] || cmake --build "$build" -j2 --target perideal > /dev/null
  perideal="$(cd "$build" && pwd)/bin/perideal"
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
}

# plot_if_possible SCRIPT ARGS...: runs a matplotlib script with Debian's
# python3, or says why the plots are skipped.
plot_if_possible() {
  if /usr/bin/python3 -c 'import matplotlib' 2>/dev/null; then
    /usr/bin/python3 "$@"
  else
    echo "matplotlib is not importable by /usr/bin/python3 (Debian package" \
         "python3-matplotlib): CSV written, plots skipped." >&2
  fi
}
