# The harness of the bad-input tests (tests/dynamics/bad_input.sh,
# tests/diffusion/bad_input.sh, tests/driver/bad_input.sh and
# tests/dynamics/checkpoint_bad_input.sh), sourced by them: the failure
# count, the runs of perideal, the checks of a refused input, and the case
# groups (one ctest each).
#
# A script sets perideal (the executable) before it runs a case; the cases
# (expect_error and the like) edit the input file named by base_prm
# (base.prm unless set) in the working directory. Each check reports
# through fail() and the script ends with finish.

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# enter_work NAME: a fresh working directory NAME below the current one.
enter_work() {
  work="$(pwd)/$1"
  rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
}

# finish MESSAGE: "OK: MESSAGE" (and the count of known gaps, see
# check_names_entry_and_value) and exit code 0 if no check failed, else 1.
finish() {
  [ "${known_gaps:-0}" -eq 0 ] || echo "$known_gaps known gaps (KNOWN GAP above)"
  if [ "$failures" -eq 0 ]; then echo "OK: $1"; else exit 1; fi
}

# run_perideal [--mpirun] NPROCS PRM [ARGS...]
#   Runs perideal on PRM, directly on one process (unless --mpirun) and
#   under mpirun on NPROCS processes, for at most 120 s (a hang exits with
#   124). Sets out (stdout and stderr together) and rc.
run_perideal() {
  local via_mpirun=
  [ "$1" = --mpirun ] && { via_mpirun=1; shift; }
  local nprocs="$1"; shift
  if [ "$nprocs" -eq 1 ] && [ -z "$via_mpirun" ]; then
    out=$(timeout 120 "$perideal" "$@" 2>&1); rc=$?
  else
    # A failure on one process must stop all of them: a hang is a failure.
    out=$(timeout 120 mpirun --oversubscribe -np "$nprocs" "$perideal" "$@" 2>&1); rc=$?
  fi
  in_case_group
}

# check_clean_exit RC OUTPUT WHAT
#   A clean error exit: non-zero, no timeout (124: a hang), no signal. A
#   process killed by signal N exits with 128 + N under bash; mpirun (Open
#   MPI 4) exits with 128 + N as well when a rank dies of a signal (134:
#   SIGABRT, 139: SIGSEGV) and prints "exited on signal N", unless another
#   rank's clean exit came first, so the message is checked too, with the
#   words of an abort (an uncaught exception: "terminate called") and of a
#   crash.
check_clean_exit() {
  local rc="$1" out="$2" what="$3"
  if [ "$rc" -eq 0 ]; then
    fail "exit code 0 for: $what"
  elif [ "$rc" -eq 124 ]; then
    fail "hang (timeout) for: $what"
  elif [ "$rc" -gt 128 ]; then
    fail "killed by signal $((rc - 128)) (exit code $rc), not a clean error, for: $what"
  fi
  if grep -qE "exited on signal|terminate called|Segmentation fault|Aborted|core dumped|MPI_ABORT was invoked" <<<"$out"; then
    echo "$out" | tail -20
    fail "a crash or an abort, not a clean error, for: $what"
  fi
  return 0
}

# check_names_entry_and_value EXPECTED WHAT
#   The expected message must name the entry with its subsection and the
#   value given, in one of the two forms of the messages:
#     Invalid value '<value>' for the parameter '<subsection>/<Entry>'
#     The entry '<subsection>/<Entry>' ... '<value>'
#   (top-level entries, 'Dimension' and 'Problem type', have no subsection),
#   so that the bad input is found from the message alone.
#   A case whose message cannot meet this yet runs with unnamed="<where the
#   message is made and what it lacks>": it is reported as a known gap (and
#   counted at the end), its other checks still apply.
check_names_entry_and_value() {
  local expected="$1" what="$2"
  local entry="'([^'/]+/)+[^']+'|'Dimension'|'Problem type'"
  if [ -n "${unnamed:-}" ]; then
    echo "KNOWN GAP: the message of '$what' does not name the entry and its value: $unnamed"
    known_gaps=$((${known_gaps:-0} + 1))
    return 0
  fi
  if ! grep -qE "Invalid value '[^']*' for the parameter ($entry)|The entry ($entry).*'[^']*'" <<<"$expected"; then
    fail "the expected message \"$expected\" does not name the entry ('subsection/Entry') and its value, for: $what"
  fi
  return 0
}

# check_message EXPECTED WHAT: the output of the run holds EXPECTED.
check_message() {
  grep -qF -- "$1" <<<"$out" || { echo "$out"; fail "no '$1' in the message for: $2"; }
  return 0
}

# check_records WHAT: the time series out/solution.pvd, where there is one,
# names no record that is missing, and no temporary file remains in out/.
check_records() {
  local record
  for record in $(sed -n 's/.*file="\([^"]*\)".*/\1/p' out/solution.pvd 2>/dev/null); do
    [ -f "out/$record" ] || fail "$record named but missing for: $1"
  done
  ls out/*.tmp > /dev/null 2>&1 && fail "temporary files remain for: $1"
  return 0
}

# edit_base EDIT FILE: the input $base_prm edited by the sed expression
# EDIT into FILE; an edit that changes nothing fails (the case would run
# the valid input) and returns 1.
base_prm=base.prm
edit_base() {
  sed -e "$1" "$base_prm" > "$2"
  if cmp -s "$base_prm" "$2"; then fail "the edit '$1' of $base_prm changed nothing"; return 1; fi
  return 0
}

# refused [--mpirun] FILE "sed expression" "substring of the message" NPROCS
#   The input edited into FILE, run on NPROCS processes with a fresh out/,
#   must end with a clean error exit and the message, which names the entry
#   and its value. Returns 1 (after a failure) when the edit changed nothing.
refused() {
  local via_mpirun=
  [ "$1" = --mpirun ] && { via_mpirun=--mpirun; shift; }
  local file="$1" edit="$2" expected="$3" nprocs="$4"
  edit_base "$edit" "$file" || return 1
  rm -rf out
  run_perideal $via_mpirun "$nprocs" "$file"
  check_clean_exit "$rc" "$out" "$edit (on $nprocs processes)"
  check_names_entry_and_value "$expected" "$edit"
  check_message "$expected" "$edit"
}

# expect_error "sed expression" "substring of the message" [nprocs]
#   Refused on nprocs processes (default 1) before any output: none of the
#   paths in left_behind (set by the script) is left behind.
expect_error() {
  local edit="$1" path
  refused case.prm "$edit" "$2" "${3:-1}" || return 0
  for path in $left_behind; do
    [ -e "$path" ] && fail "'$path' was left behind for: $edit"
  done
  return 0
}

# stops_during_run NPROCS PRM WHAT
#   PRM, run under mpirun (also on one process) with a fresh out/, stops
#   during its time loop with a clean error exit; the output written before
#   is there (out/solution.pvd) and complete. The caller checks the message.
stops_during_run() {
  local nprocs="$1" prm="$2" what="$3"
  rm -rf out
  run_perideal --mpirun "$nprocs" "$prm"
  check_clean_exit "$rc" "$out" "$what"
  [ -f out/solution.pvd ] || fail "the earlier output is gone for: $what"
  check_records "$what"
}

# expect_error_later "sed expression" "substring of the message" nprocs
#   A value that turns bad during the run stops it (stops_during_run) with
#   the message, which names the entry and its value.
expect_error_later() {
  local edit="$1" expected="$2" nprocs="$3"
  edit_base "$edit" later.prm || return 0
  stops_during_run "$nprocs" later.prm "$edit (on $nprocs processes)"
  check_names_entry_and_value "$expected" "$edit"
  check_message "$expected" "$edit"
}

# expect_stop "sed expression" "substring of the message" nprocs
#   As expect_error_later, for a run that stops inside its time loop before
#   its first output after t = 0: the initial record may stay (no record
#   after it), and every record the time series names exists.
expect_stop() {
  refused --mpirun case.prm "$@" || return 0
  if [ -f out/solution.pvd ]; then
    [ "$(grep -c '<DataSet' out/solution.pvd)" -le 1 ] || fail "records after t = 0 were left for: $1"
  fi
  check_records "$1"
}

# expect_valid NPROCS PRM WHAT [FILE...]: the valid input PRM runs (exit
# code 0) and writes each FILE.
expect_valid() {
  local nprocs="$1" prm="$2" what="$3" file
  shift 3
  run_perideal "$nprocs" "$prm"
  [ "$rc" -eq 0 ] || { echo "$out" | tail -20; fail "$what failed (exit code $rc)"; }
  for file; do
    [ -f "$file" ] || fail "$what wrote no $file"
  done
  return 0
}

# Case groups. A script defines its cases in functions group_<name> (each
# one self-contained: it writes or copies what it needs) and ends with
# run_case_group GROUP; tests/CMakeLists.txt finds the functions in the
# script and adds one ctest for each, so that ctest -j runs them side by
# side. GROUP 'all' runs every group, one after the other.
run_case_group() {
  local selected="$1" groups group
  groups=$(declare -F | sed -n 's/^declare -f group_//p')
  if [ "$selected" = all ]; then
    for group in $groups; do
      current_group="$group" base_prm=base.prm
      "group_$group"
    done
  elif grep -qxF -- "$selected" <<<"$groups"; then
    current_group="$selected"
    "group_$selected"
  else
    echo "FAIL: no case group '$selected'; the groups are:" $groups
    exit 2
  fi
  current_group=
}

# in_case_group: in a script with case groups, a run outside every group
# (it would run in each ctest of the script) fails.
in_case_group() {
  [ -n "${current_group:-}" ] || ! declare -F | grep -q '^declare -f group_' \
    || fail "a run outside every case group (function group_<name>)"
  return 0
}
