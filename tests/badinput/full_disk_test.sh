#!/usr/bin/env bash
# A full disk, on a small tmpfs mounted for the test (skipped, status 77, where mounting is not
# permitted): when the checkpoint cannot be created the sweep exits 2 with one line naming
# FILE.partial and "No space left on device", nothing left; when the final cube cannot be
# written it exits 1 with one line naming FILE.tmp, no crash and no MPI_Abort, FILE.partial
# kept; once there is room, --resume writes the cube identical to one written with room.
# 1 and 2 ranks.
# usage: full_disk_test.sh SWEEP_DRIVER MPIEXEC WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args driver mpiexec work -- "$@"
if mountpoint -q "$work/disk" 2> /dev/null; then umount "$work/disk"; fi
fresh_dir "$work"
mkdir disk
mount -t tmpfs -o size=64k tmpfs disk 2> /dev/null || { echo "$test_name: cannot mount a tmpfs here: skipped"; exit 77; }
at_exit 'umount "$work/disk" 2> /dev/null || true'
cat > spec.toml <<'TOML'
[sweep]
name = "disk"
family = "subsystem"
[axes]
pulse = ["cosine", "sine"]
a_deg = [10, 25, 40, 55]
w0_over_wg = {linspace = [0.25, 4.0, 200]}
[fixed]
eta0 = 2.0
TOML
run() {
  local n=$1; shift
  if [ "$n" -eq 1 ]; then "$driver" spec.toml --quiet --work 5 "$@"
  else on_ranks "$n" "$driver" spec.toml --quiet --work 5 "$@"; fi
}
run 1 --out ref.h5 2> /dev/null
resize() { mount -o "remount,size=$1" disk; }

for ranks in 1 2; do
  rm -f disk/*
  resize 64k  # smaller than the checkpoint (150 kB)
  status=0
  run "$ranks" --out disk/c.h5 > out.txt 2> err.txt || status=$?
  [ "$status" -eq 2 ] || fail "creation ($ranks ranks): exit $status: $(cat err.txt)"
  grep -q "^skewbridge: error: disk/c.h5.partial: write: No space left on device$" err.txt ||
    fail "creation ($ranks ranks): '$(cat err.txt)'"
  [ "$(grep -c 'error: ' err.txt)" -eq 1 ] || fail "creation: not one error line: $(cat err.txt)"
  [ -z "$(ls disk)" ] || fail "creation ($ranks ranks) left $(ls disk)"
  echo "checkpoint on a full disk, $ranks ranks: $(grep 'error: ' err.txt)"

  resize 200k  # room for the checkpoint and the lock, not for the final cube beside it
  status=0
  run "$ranks" --out disk/c.h5 > out.txt 2> err.txt || status=$?
  [ "$status" -eq 1 ] || fail "final ($ranks ranks): exit $status: $(cat err.txt)"
  grep -q "^skewbridge: error: disk/c.h5.tmp: write: No space left on device$" err.txt ||
    fail "final ($ranks ranks): '$(cat err.txt)'"
  [ "$(grep -c 'error: ' err.txt)" -eq 1 ] || fail "final: not one error line: $(cat err.txt)"
  ! grep -q "MPI_ABORT\|Segmentation\|signal" err.txt || fail "final ($ranks ranks): $(cat err.txt)"
  [ "$(ls disk)" = "c.h5.partial" ] || fail "final ($ranks ranks) left '$(ls disk)'"
  echo "final cube on a full disk, $ranks ranks: $(grep 'error: ' err.txt)"

  resize 400k
  run "$ranks" --out disk/c.h5 --resume 2> err.txt || fail "resume ($ranks ranks): $(cat err.txt)"
  for ds in responses/x_peak responses/theta_peak status done stats/events stats/steps; do
    h5diff ref.h5 disk/c.h5 "/sweeps/disk/$ds" "/sweeps/disk/$ds" > /dev/null ||
      fail "the resumed cube differs in $ds"
  done
  [ "$(ls disk)" = "c.h5" ] || fail "after the resume: '$(ls disk)'"
done
echo "full_disk_test: ok"
