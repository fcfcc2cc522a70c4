#!/usr/bin/env bash
# A damaged checkpoint is never resumed onto: one flipped byte in a done cell's response (its
# chunk fails the Fletcher-32 checksum), a done cell's status rewritten as 7777 through HDF5
# (valid checksum, status outside the table), done flags set on 100 uncomputed cells, and
# random 16-byte blocks (12 seeds). Each --resume either refuses with exit status 2, one line
# naming the file and the dataset, the checkpoint byte for byte unchanged and no FILE written,
# or (a block that hit no stored byte that matters) completes a cube identical to the
# uninterrupted one. Resumes run on 1 and 2 ranks. A damaged final cube makes `inspect` fail
# with one line naming the file, the dataset and the checksum.
# usage: checkpoint_corruption_test.sh SWEEP_DRIVER MPIEXEC CORRUPT_PY SKEWBRIDGE WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args driver mpiexec corrupt exe work -- "$@"
fresh_dir "$work"
cat > spec.toml <<'TOML'
[sweep]
name = "bytes"
family = "subsystem"
[axes]
pulse = ["cosine", "sine"]
a_deg = [10, 25, 40, 55]
w0_over_wg = {linspace = [0.25, 4.0, 30]}
[fixed]
eta0 = 2.0
TOML
run() {  # run RANKS ARGS...: 1 rank without mpiexec (whose banner would follow any failure)
  local n=$1; shift
  if [ "$n" -eq 1 ]; then "$driver" spec.toml --quiet "$@"
  else on_ranks "$n" "$driver" spec.toml --quiet "$@"; fi
}
# The program's own lines on stderr (mpiexec adds its banner after a non-zero exit).
own_lines() { grep -c "^[a-z_]*: error: " err.txt || true; }
same_cube() {  # same_cube A B: responses, status and solver statistics identical
  for ds in responses/x_peak responses/theta_peak responses/cell_echo status done stats/events \
            stats/steps; do
    h5diff "$1" "$2" "/sweeps/bytes/$ds" "/sweeps/bytes/$ds" >/dev/null ||
      fail "$1 and $2 differ in $ds"
  done
}
done_count() {
  /usr/bin/python3 -c "import h5py,sys; print(int(h5py.File(sys.argv[1],'r')['sweeps/bytes/done'][()].sum()))" "$1" 2>/dev/null || echo 0
}

run 1 --out ref.h5 --work 50
# The final cube carries the checksums too.
/usr/bin/python3 -c "import h5py,sys; d=h5py.File('ref.h5','r')['sweeps/bytes/responses/x_peak']; sys.exit(0 if d.fletcher32 else 1)" ||
  fail "the final cube's datasets carry no Fletcher-32 checksum"

# A checkpoint with some cells done and some not: killed (SIGKILL) mid-way.
"$driver" spec.toml --quiet --out base.h5 --work 50 --sleep-ms 15 --checkpoint-cells 8 &
pid=$!
for _ in $(seq 1 400); do
  sleep 0.05
  [ -f base.h5.partial ] && [ "$(done_count base.h5.partial)" -ge 40 ] && break
done
kill -KILL "$pid"; wait "$pid" || true
n=$(done_count base.h5.partial)
[ "$n" -ge 40 ] && [ "$n" -lt 240 ] || fail "the killed sweep left $n done cells, need 40..239"
/usr/bin/python3 -c "import h5py,sys; d=h5py.File('base.h5.partial','r')['sweeps/bytes/status']; sys.exit(0 if d.fletcher32 else 1)" ||
  fail "the checkpoint's datasets carry no Fletcher-32 checksum"
# Unharmed, it resumes to the reference cube.
cp base.h5.partial ok.h5.partial
run 2 --out ok.h5 --resume --work 50 2> /dev/null || fail "the unharmed checkpoint did not resume"
same_cube ref.h5 ok.h5

expect_refusal() {  # expect_refusal NAME RANKS PATTERN MODE [SEED]
  local name=$1 ranks=$2 pattern=$3 status=0
  rm -f "$name.h5" "$name.h5.partial"
  cp base.h5.partial "$name.h5.partial"
  /usr/bin/python3 "$corrupt" "$name.h5.partial" bytes "${@:4}" > /dev/null
  cp "$name.h5.partial" "$name.before"
  run "$ranks" --out "$name.h5" --resume --work 50 > out.txt 2> err.txt || status=$?
  [ "$status" -eq 2 ] || fail "$name: resume exited with $status, expected 2: $(cat err.txt)"
  grep -q -- "$name.h5.partial: cannot resume: dataset sweeps/bytes/$pattern" err.txt ||
    fail "$name: message '$(cat err.txt)' lacks '$pattern'"
  [ "$(own_lines)" -eq 1 ] || fail "$name: not one error line on stderr: $(cat err.txt)"
  [ "$ranks" -gt 1 ] || [ "$(wc -l < err.txt)" -eq 1 ] || fail "$name: more than one line: $(cat err.txt)"
  cmp -s "$name.h5.partial" "$name.before" || fail "$name: the refused checkpoint was modified"
  [ ! -e "$name.h5" ] || fail "$name: a refused resume wrote $name.h5"
  echo "$name ($ranks ranks): $(cat err.txt)"
}
expect_refusal flip1 1 "responses/x_peak is corrupted (Fletcher-32 checksum mismatch)" flip-done-cell
expect_refusal flip2 2 "responses/x_peak is corrupted (Fletcher-32 checksum mismatch)" flip-done-cell
expect_refusal status1 1 "status is corrupted (cell [0-9]* is done with status 7777" status-7777
expect_refusal status2 2 "status is corrupted (cell [0-9]* is done with status 7777" status-7777
expect_refusal undone1 1 "status is corrupted (cell [0-9]* is done with status -1" done-uncomputed
expect_refusal undone2 2 "status is corrupted (cell [0-9]* is done with status -1" done-uncomputed

refused=0 resumed=0
for seed in $(seq 1 12); do
  name=random$seed status=0
  cp base.h5.partial "$name.h5.partial"
  /usr/bin/python3 "$corrupt" "$name.h5.partial" bytes random-blocks "$seed" > /dev/null
  cp "$name.h5.partial" "$name.before"
  run $((seed % 2 + 1)) --out "$name.h5" --resume --work 50 > out.txt 2> err.txt || status=$?
  if [ "$status" -eq 0 ]; then
    same_cube ref.h5 "$name.h5"
    resumed=$((resumed + 1))
  elif [ "$status" -eq 2 ]; then
    grep -q "^[^:]*: error: .*$name.h5.partial" err.txt || fail "$name: message '$(cat err.txt)'"
    [ "$(own_lines)" -eq 1 ] || fail "$name: not one error line: $(cat err.txt)"
    cmp -s "$name.h5.partial" "$name.before" || fail "$name: the refused checkpoint was modified"
    [ ! -e "$name.h5" ] || fail "$name: a refused resume wrote $name.h5"
    refused=$((refused + 1))
  else
    fail "$name: resume exited with $status: $(cat err.txt)"
  fi
done
echo "random blocks: $refused refused, $resumed resumed to the identical cube"
cp ref.h5 damaged.h5
/usr/bin/python3 "$corrupt" damaged.h5 bytes flip-status-chunk > /dev/null
status=0
"$exe" inspect damaged.h5 > out.txt 2> err.txt || status=$?
[ "$status" -ne 0 ] || fail "inspect of a damaged cube exited 0"
grep -q "^skewbridge: error: damaged.h5: H5Dread /sweeps/bytes/status: Fletcher-32 checksum mismatch$" err.txt ||
  fail "inspect of a damaged cube: '$(cat err.txt)'"
echo "damaged final cube, inspect: exit $status: $(cat err.txt)"
echo "checkpoint_corruption_test: ok"
