#!/usr/bin/env bash
# One writer per cube: while a sweep writes out.h5, a second sweep on the same --out (plain,
# --resume or --force; 1 and 2 ranks) exits 2 at once with one line naming the holder's pid and
# host, and the first one completes the same cube as an undisturbed run; the lock file goes
# with its holder. A stale lock (its holder killed with SIGKILL, or a file naming a dead
# process) is taken over.
# usage: writer_lock_test.sh SWEEP_DRIVER MPIEXEC WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args driver mpiexec work -- "$@"
fresh_dir "$work"
cat > spec.toml <<'TOML'
[sweep]
name = "lock"
family = "subsystem"
[axes]
pulse = ["cosine", "sine"]
a_deg = [10, 25, 40, 55]
w0_over_wg = {linspace = [0.25, 4.0, 10]}
[fixed]
eta0 = 2.0
TOML
run() {
  local n=$1; shift
  if [ "$n" -eq 1 ]; then "$driver" spec.toml --quiet "$@"
  else on_ranks "$n" "$driver" spec.toml --quiet "$@"; fi
}
same_cube() {
  for ds in responses/x_peak responses/theta_peak status done stats/events stats/steps; do
    h5diff "$1" "$2" "/sweeps/lock/$ds" "/sweeps/lock/$ds" >/dev/null || fail "$1, $2 differ in $ds"
  done
}
run 1 --out ref.h5 --work 50

"$driver" spec.toml --quiet --out out.h5 --work 50 --sleep-ms 200 --checkpoint-cells 4 &
holder=$!
for _ in $(seq 1 200); do [ -f out.h5.partial ] && [ -f out.h5.lock ] && break; sleep 0.05; done
[ -f out.h5.lock ] || fail "the running sweep holds no out.h5.lock"
grep -q "^$holder $(hostname)$" out.h5.lock || fail "out.h5.lock says '$(cat out.h5.lock)'"
for ranks in 1 2; do
  for flags in "" "--resume" "--force"; do
    status=0
    start=$(date +%s.%N)
    # shellcheck disable=SC2086
    run "$ranks" --out out.h5 --work 50 $flags > out.txt 2> err.txt || status=$?
    took=$(echo "$(date +%s.%N) - $start" | bc)
    [ "$status" -eq 2 ] || fail "second writer ($ranks ranks, '$flags') exited $status: $(cat err.txt)"
    grep -q "out.h5: is being written by another sweep (process $holder on host $(hostname)" err.txt ||
      fail "second writer ($ranks ranks, '$flags'): '$(cat err.txt)'"
    [ "$(grep -c 'error: ' err.txt)" -eq 1 ] || fail "not one error line: $(cat err.txt)"
    echo "second writer, $ranks ranks, '$flags': exit 2 in ${took} s: $(grep 'error: ' err.txt)"
  done
done
kill -0 "$holder" 2> /dev/null || fail "the first writer ended before the checks were done"
wait "$holder" || fail "the first writer failed"
same_cube ref.h5 out.h5
[ ! -e out.h5.lock ] || fail "out.h5.lock left after the run"
[ ! -e out.h5.partial ] || fail "out.h5.partial left after the run"

# A lock file naming a process that no longer exists holds no flock: taken over.
echo "999999 gone-host" > stale.h5.lock
run 1 --out stale.h5 --work 50 || fail "a stale lock file stopped the sweep"
same_cube ref.h5 stale.h5
[ ! -e stale.h5.lock ] || fail "stale.h5.lock left after the run"

# SIGKILL leaves the lock file behind; the resume takes it over.
"$driver" spec.toml --quiet --out killed.h5 --work 50 --sleep-ms 30 --checkpoint-cells 4 &
pid=$!
for _ in $(seq 1 200); do [ -f killed.h5.partial ] && break; sleep 0.05; done
sleep 0.3
kill -KILL "$pid"; wait "$pid" || true
[ -f killed.h5.lock ] || fail "no lock file left by the killed sweep"
run 2 --out killed.h5 --resume --work 50 2> /dev/null || fail "resume after SIGKILL refused"
same_cube ref.h5 killed.h5
[ ! -e killed.h5.lock ] || fail "killed.h5.lock left after the resume"
echo "writer_lock_test: ok"
