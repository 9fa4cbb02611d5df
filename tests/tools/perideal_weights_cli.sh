#!/usr/bin/env bash
# Usage: perideal_weights_cli.sh PATH/TO/perideal-weights
# Checks the CSV format of perideal-weights and its errors on bad input.
set -u
tool="$1"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect_error "substring of the message" args...
expect_error() {
  local expected="$1"; shift
  local out rc
  out=$("$tool" "$@" 2>&1 >/dev/null); rc=$?
  [ "$rc" -ne 0 ] || fail "'$*' exited with 0"
  grep -qF -- "$expected" <<<"$out" || fail "'$*': message lacks '$expected': $out"
  [ -z "$("$tool" "$@" 2>/dev/null)" ] || fail "'$*' printed output to stdout"
}

expect_error "--m-ratio must be a finite number > 0" --m-ratio -1
expect_error "--m-ratio must be a finite number > 0" --m-ratio 0
expect_error "--m-ratio must be a finite number > 0" --m-ratio nan
expect_error "option --m-ratio expects a number, got 'three'" --m-ratio three
expect_error "option --m-ratio needs a value" --m-ratio
expect_error "--m-ratio 1e4 needs an estimated" --m-ratio 1e4
# Below m = sqrt(d)/2 the ball does not contain the node's own cell: the
# neighbourhood measure counts only its part, and the exact rule must still
# match the ball's volume to round-off (counting the own cell fully was
# off by 4.3 % in 2D and 22 % in 3D at m = 0.6).
for d in 2 3; do
  err=$("$tool" --summary --dim $d --m-ratio 0.6 | awk '$1 == "exact" { print $3 }')
  awk -v e="$err" 'BEGIN { exit !(e < 1e-12) }' \
    || fail "--summary --dim $d --m-ratio 0.6: exact relative error $err, not < 1e-12"
done
expect_error "--dim must be 2 or 3" --dim 4
expect_error "unknown algorithm 'exakt'" --algorithm exakt
expect_error "unknown algorithm 'quasi-analytical' in 2D" --dim 2 --algorithm quasi-analytical
expect_error "--taylor-order applies to --algorithm quasi-analytical only" --taylor-order 8
expect_error "--taylor-order must be an integer in [1, 40]" --algorithm quasi-analytical --taylor-order 2.5
expect_error "unknown option '--wegde'" --wegde

# 2D, m = 1.2: the 8 cells around the origin, header x,y,beta.
out=$("$tool" --dim 2 --m-ratio 1.2)
[ "$(head -1 <<<"$out")" = "x,y,beta" ] || fail "2D header: $(head -1 <<<"$out")"
[ "$(tail -n +2 <<<"$out" | wc -l)" -eq 8 ] || fail "2D m=1.2: expected 8 rows"

# 3D, m = 3: header, integers, no origin, beta in (0, 1], 17 digits.
out=$("$tool" --dim 3 --m-ratio 3)
[ "$(head -1 <<<"$out")" = "x,y,z,beta" ] || fail "3D header"
tail -n +2 <<<"$out" | awk -F, '
  NF != 4 || $1 !~ /^-?[0-9]+$/ || $2 !~ /^-?[0-9]+$/ || $3 !~ /^-?[0-9]+$/ { print "bad row " $0; bad = 1 }
  $1 == 0 && $2 == 0 && $3 == 0 { print "origin listed"; bad = 1 }
  !($4 > 0 && $4 <= 1) { print "beta out of (0,1]: " $0; bad = 1 }
  END { exit bad }' || fail "3D rows"
grep -q '^0,0,3,0\.4720393649385' <<<"$out" || fail "3D m=3 (0,0,3): $(grep '^0,0,3,' <<<"$out")"
n_all=$(tail -n +2 <<<"$out" | wc -l)

# --wedge lists 0 <= x <= y <= z only, and its rows expand to all rows under
# the 48 symmetries.
wedge=$("$tool" --dim 3 --m-ratio 3 --wedge)
tail -n +2 <<<"$wedge" | awk -F, '!(0 <= $1 && $1 <= $2 && $2 <= $3) { exit 1 }' \
  || fail "--wedge lists an offset outside the wedge"
n_expanded=$(tail -n +2 <<<"$wedge" | awk -F, '
  { zeros = ($1 == 0) + ($2 == 0) + ($3 == 0);
    perms = 6 / (($1 == $2 && $2 == $3) ? 6 : (($1 == $2 || $2 == $3) ? 2 : 1));
    n += perms * 2 ^ (3 - zeros) }
  END { print n }')
[ "$n_expanded" -eq "$n_all" ] || fail "wedge expands to $n_expanded rows, full list has $n_all"

# quasi-analytical with a Taylor order runs.
"$tool" --algorithm quasi-analytical --taylor-order 8 --m-ratio 2.5 >/dev/null \
  || fail "quasi-analytical --taylor-order 8"

if [ "$failures" -eq 0 ]; then
  echo "perideal-weights command line: all checks passed"
else
  echo "perideal-weights command line: $failures check(s) failed"
  exit 1
fi
