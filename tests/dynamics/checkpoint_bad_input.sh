#!/usr/bin/env bash
# Usage: checkpoint_bad_input.sh PERIDEAL NPROCS
#
# A checkpoint that the input to resume does not fit, a corrupt checkpoint,
# and a run that would replace a newer checkpoint, on NPROCS processes. Each
# case must exit non-zero without hanging, say what differs (the entry, the
# checkpoint's value and this input's) or "Corrupt checkpoint" with the
# file, and leave the checkpoint and the output as they were. The corrupt
# files are made by hand: one flipped byte in a value (caught by the
# checksum), a flipped byte in a count (caught by the count checks before
# anything is allocated: a broken-bond count hung 1 and 2 processes, a row
# count was reported as "Out of memory"), a truncated file.
set -u
perideal="$1"; nprocs="$2"
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/../bad_input_checks.sh"
enter_work "checkpoint_bad_input.np$nprocs"
run() { # run PRM LOG
  if [ "$nprocs" -eq 1 ]; then timeout 60 "$perideal" "$1" > "$2" 2>&1
  else timeout 60 mpirun --oversubscribe -np "$nprocs" "$perideal" "$1" --threads 1 > "$2" 2>&1; fi
}
# Bitwise NOT of the byte at OFFSET of FILE.
flip() { # flip FILE OFFSET
  local b; b=$(od -An -tu1 -j "$2" -N1 "$1" | tr -d ' \n')
  printf "$(printf '\\%03o' $((b ^ 255)))" | dd of="$1" bs=1 seek="$2" conv=notrunc status=none
}
listing() { find out -type f | sort | xargs md5sum; }

# The input of bad_input.sh, with a checkpoint every 10 steps of 20, a
# probe, and bonds that break.
sed -e "s/^    set Poisson's ratio = 0.25/    set Young's modulus = 7.2e10\n&/" \
    -e 's/^    set Critical stretch = 0.01$/    set Critical stretch = 0.0001/' \
    -e 's/^  set End time = 1e-4$/  set End time = 2e-4\n  set Steps per run = 10\n  set Energy every steps = 5\n  set Progress interval = 0/' \
    -e 's/^  set Pre-cracks = 0, 0.25, 0.5, 0.25$/&\n  set Probe points = 0.7, 0.25/' \
    "$here/bad_input/base.prm" > first.prm
for entry in "Young's modulus = 7.2e10" "Critical stretch = 0.0001" "End time = 2e-4" "Steps per run = 10" "Probe points = 0.7, 0.25"; do
  grep -qF "set $entry" first.prm || fail "first.prm: the edit to 'set $entry' of bad_input/base.prm matched nothing"
done
sed 's/  set Steps per run = 10/  set Steps per run = 10\n  set Resume from checkpoint = true/' first.prm > next.prm
run first.prm first.log || { cat first.log; fail "the first chunk failed"; }
run next.prm next.log || { cat next.log; fail "the second chunk failed"; }
grep -q "resumed from .*checkpoint at step 10" next.log || fail "the second chunk did not resume at step 10"
grep -q "checkpoint at step 20 written" next.log || fail "the second chunk wrote no checkpoint at step 20"
rm -rf good && cp -a out good
last=$((nprocs - 1))

# expect_refusal PRM "substring of the message" [what to do to out/ first]
expect_refusal() {
  local prm="$1" expected="$2" damage="${3:-}" rc before
  rm -rf out && cp -a good out
  [ -z "$damage" ] || eval "$damage"
  before=$(listing)
  run "$prm" case.log; rc=$?
  check_clean_exit "$rc" "$(cat case.log)" "$prm ${damage:+($damage) }on $nprocs processes"
  grep -qF -- "$expected" case.log \
    || { tail -5 case.log; fail "no \"$expected\" in the message for $prm ${damage:+($damage)}"; }
  [ "$(listing)" = "$before" ] || fail "the checkpoint or the output changed for $prm ${damage:+($damage)}"
  return 0
}

# Another input than the one that wrote the checkpoint: the entry, both
# values and the fix.
sed 's/bond-based/linear peridynamic solid/' next.prm > model.prm
expect_refusal model.prm "Invalid value 'linear peridynamic solid' for the parameter 'Material model/Model': the checkpoint in 'out/checkpoint' was written with 'bond-based'; set 'Material model/Model' back to 'bond-based' to resume from it, or start afresh without 'explicit dynamics/Resume from checkpoint'"
sed "s/Young's modulus = 7.2e10/Young's modulus = 7.3e10/" next.prm > constant.prm
expect_refusal constant.prm "Invalid value '7.3e10' for the parameter 'Material model/bond-based/Young's modulus': the checkpoint in 'out/checkpoint' was written with '7.2e10'; set 'Material model/bond-based/Young's modulus' back to '7.2e10'"
sed 's/^subsection Geometry/subsection Horizon\n  set m-ratio = 3.5\nend\nsubsection Geometry/' next.prm > horizon.prm
expect_refusal horizon.prm "Invalid value '3.5' for the parameter 'Horizon/m-ratio': the checkpoint in 'out/checkpoint' was written with '3'"
sed 's/set Probe points = 0.7, 0.25/set Probe points = 0.7, 0.25; 0.3, 0.1/' next.prm > probes.prm
expect_refusal probes.prm "Invalid value '0.7, 0.25; 0.3, 0.1' for the parameter 'explicit dynamics/Probe points': the checkpoint in 'out/checkpoint' was written with '0.7, 0.25'"
sed 's/  set Probe points = 0.7, 0.25/  set Probe points = 0.7, 0.25\n  set Crack tip origin = 0.5, 0.25/' next.prm > tip.prm
expect_refusal tip.prm "for the parameter 'explicit dynamics/Crack tip origin': the checkpoint in 'out/checkpoint' was written with ''"

# Corrupt files: a flipped byte of a value (the time; a velocity), a
# flipped byte of a count (the number of energy rows at byte 80 of run.bin;
# the broken-bond count of the first node record at byte 16 + 10 * 8 of a
# 2D state file), a truncated file.
expect_refusal next.prm "Corrupt checkpoint: 'out/checkpoint/run.bin' does not match its checksum" "flip out/checkpoint/run.bin 17"
expect_refusal next.prm "Corrupt checkpoint: 'out/checkpoint/state.$last.bin' does not match the checksum" "flip out/checkpoint/state.$last.bin 50"
expect_refusal next.prm "Corrupt checkpoint: 'out/checkpoint/run.bin' gives" "flip out/checkpoint/run.bin 87"
expect_refusal next.prm "Corrupt checkpoint: 'out/checkpoint/state.$last.bin' gives" "flip out/checkpoint/state.$last.bin 103"
expect_refusal next.prm "Corrupt checkpoint: 'out/checkpoint/run.bin'" "truncate -s -9 out/checkpoint/run.bin"
expect_refusal next.prm "Corrupt checkpoint: 'out/checkpoint/state.$last.bin' has" "truncate -s -8 out/checkpoint/state.$last.bin"
expect_refusal next.prm "Corrupt checkpoint: 'out/checkpoint/state.$last.bin' is missing" "rm out/checkpoint/state.$last.bin"

# A run that starts afresh would replace the checkpoint at step 20 with one
# at step 10.
expect_refusal first.prm "Invalid value 'false' for the parameter 'explicit dynamics/Resume from checkpoint': 'out/checkpoint' holds a checkpoint at step 20"
expect_refusal first.prm "'out/checkpoint.old' holds a checkpoint at step 20" "mv out/checkpoint out/checkpoint.old"
sed 's/  set Steps per run = 10/  set Steps per run = 10\n  set Overwrite checkpoint = true/' next.prm > both.prm
expect_refusal both.prm "Invalid value 'true' for the parameter 'explicit dynamics/Overwrite checkpoint'"

# What is allowed: the same number written otherwise; replacing the newer
# checkpoint when asked to.
rm -rf out && cp -a good out
sed "s/Young's modulus = 7.2e10/Young's modulus = 72e9/" next.prm > same.prm
run same.prm same.log || { tail -5 same.log; fail "resuming with 'Young's modulus = 72e9' (the checkpoint's 7.2e10) failed"; }
grep -q "resumed from .*checkpoint at step 20" same.log || fail "72e9 did not resume at step 20"
rm -rf out && cp -a good out
sed 's/  set Steps per run = 10/  set Steps per run = 10\n  set Overwrite checkpoint = true/' first.prm > overwrite.prm
run overwrite.prm overwrite.log || { tail -5 overwrite.log; fail "'Overwrite checkpoint = true' failed"; }
grep -q "checkpoint at step 10 written" overwrite.log || fail "'Overwrite checkpoint = true' wrote no checkpoint at step 10"

finish "every bad checkpoint was refused"
