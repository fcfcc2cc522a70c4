# The common start of the shell tests run by ctest (tests/*/*.sh), sourced as their first
# command:
#   source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
#   args exe mpiexec work -- "$@"   # the usage line's arguments, in order
#   fresh_dir "$work"               # or: temp_dir (a folder removed at exit, in $work)
# It gives every test the same ground, by hand and in CI alike (CI=true, no terminal, root):
#  - strict mode (set -euo pipefail): a failing command ends the test with its status. A command
#    expected to fail is written `cmd || status=$?`, or tested by `if` / `||`;
#  - stdin from /dev/null: nothing waits for a terminal that CI does not have;
#  - fail MESSAGE: one line "TEST: FAIL: MESSAGE" on stderr, exit status 1 (TEST is test_name,
#    the script's name without .sh; a test may set it to say more, e.g. its mode);
#  - test_data: the absolute path of tests/data (shared model files and records);
#  - at_exit COMMAND: COMMAND (a string, evaluated) runs when the test exits, whatever the
#    status; commands run in the order given;
#  - Open MPI's permission to run as root and to oversubscribe the cores, exported, and
#    on_ranks N COMMAND...: COMMAND on N ranks through $mpiexec. A process the test signals
#    later (`... & pid=$!`) starts "$mpiexec" itself, so that $! is mpiexec's own pid;
#  - interrupt_at_checkpoint PID FILE.partial [SIGNAL]: the signal reaches a sweep at a
#    checkpoint that holds finished cells, never after its last cell, however small the grid.

set -euo pipefail
exec </dev/null

test_name=$(basename "$0" .sh)
# The source tree's tests/data (models, records), found from this file's place.
test_data=$(cd "$(dirname "${BASH_SOURCE[0]}")/../data" && pwd)

# fail MESSAGE...: one line naming the test on stderr, exit status 1.
fail() {
  echo "$test_name: FAIL: $*" >&2
  exit 1
}

# args NAME... -- VALUE...: the test's positional arguments into the variables NAME..., in
# order; a missing one is a usage error (exit status 2) that lists them.
args() {
  local names=()
  while [ $# -gt 0 ] && [ "$1" != "--" ]; do
    names+=("$1")
    shift
  done
  [ $# -gt 0 ] && shift
  if [ $# -lt ${#names[@]} ]; then
    echo "usage: $test_name.sh ${names[*]^^}" >&2
    exit 2
  fi
  local name
  for name in "${names[@]}"; do
    printf -v "$name" '%s' "$1"
    shift
  done
}

sb_exit_commands=()
sb_run_exit_commands() {
  local command
  for command in ${sb_exit_commands[@]+"${sb_exit_commands[@]}"}; do
    eval "$command" || true
  done
}
trap sb_run_exit_commands EXIT

# at_exit COMMAND: evaluates COMMAND when the test exits.
at_exit() { sb_exit_commands+=("$1"); }

# fresh_dir DIR: DIR emptied, created and entered; it stays after the test for a look.
fresh_dir() {
  rm -rf "$1" && mkdir -p "$1" && cd "$1"
}

# temp_dir: a new temporary folder in $work, removed when the test exits.
temp_dir() {
  work=$(mktemp -d)
  at_exit 'rm -rf "$work"'
}

# Open MPI refuses root without these, and more ranks than cores without oversubscription.
set -a
source "$(dirname "${BASH_SOURCE[0]}")/../../scripts/openmpi.env"
set +a

# on_ranks N COMMAND...: COMMAND on N MPI ranks through $mpiexec (the test's argument).
# When a rank exits non-zero, Open MPI's mpiexec ends the others with SIGTERM and waits
# odls_base_sigkill_timeout (1 s) before each SIGKILL round, about 2 s per refused command.
# Every rank of a refusal has passed MPI_Finalize (which waits for all ranks) or never started
# MPI when the first one exits, and a failure past the setup ends the job with MPI_Abort, so
# the wait protects nothing here: it is 0. A test that signals a sweep to make it checkpoint
# starts "$mpiexec" itself and keeps the 1 s grace.
on_ranks() {
  local n=$1
  shift
  OMPI_MCA_odls_base_sigkill_timeout=0 \
    "${mpiexec:?on_ranks: the test has no mpiexec argument}" -n "$n" --oversubscribe "$@"
}

# checkpointed_cells FILE: the finished cells of every sweep in the checkpoint FILE (0 while
# it cannot be read, e.g. half-written).
checkpointed_cells() {
  /usr/bin/python3 - "$1" 2>/dev/null <<'PY' || echo 0
import sys
import h5py
with h5py.File(sys.argv[1], "r") as f:
    print(sum(int(g["done"][()].sum()) for g in f["sweeps"].values()))
PY
}

# interrupt_at_checkpoint PID FILE.partial [SIGNAL]: sends SIGNAL (default TERM) to the sweep
# started in the background as PID (skewbridge itself, or "$mpiexec" with its ranks) once its
# checkpoint FILE.partial holds a finished cell (to its ranks while they are frozen, then to PID);
# KILL goes to PID and its ranks at once, as a crash. The ranks run in steps of 10 ms and are frozen (SIGSTOP) while the test reads the
# checkpoint between steps: the reading takes no time of theirs, so the signal finds cells done
# and cells to do even when the sweep takes well under a second, however busy the machine. The
# caller waits for PID and checks what the signal left.
interrupt_at_checkpoint() {
  local pid=$1 partial=$2 signal=${3:-TERM} step ranks="" child cells=0 tick
  # The checkpoint file is made when the sweep begins, before its first cell.
  for step in $(seq 1 6000); do
    [ -f "$partial" ] && break
    kill -0 "$pid" 2>/dev/null || fail "the sweep ended before it made $partial"
    sleep 0.01
  done
  [ -f "$partial" ] || fail "no $partial after 60 s"
  # mpiexec's children are the ranks; a sweep without mpiexec is its own rank (its child, the
  # Open MPI daemon of a single process, is left to run).
  for child in $(pgrep -P "$pid"); do
    [ "$(cat "/proc/$child/comm" 2>/dev/null)" = orted ] || ranks+=" $child"
  done
  [ -n "$ranks" ] || ranks=$pid
  exec {tick}<> <(:)  # a pipe nobody writes to: `read -t` on it waits without a process
  # shellcheck disable=SC2086 # the pids are words
  kill -STOP $ranks 2>/dev/null || true
  for step in $(seq 1 3000); do
    [ -f "$partial" ] || break
    cells=$(checkpointed_cells "$partial")
    [ "$cells" -gt 0 ] && break
    kill -CONT $ranks 2>/dev/null || true
    read -r -t 0.01 -u "$tick" || true
    kill -STOP $ranks 2>/dev/null || true
  done
  exec {tick}<&-
  if [ "$cells" -eq 0 ]; then
    kill -CONT $ranks 2>/dev/null || true
    fail "the sweep ended, or wrote no finished cell in 3000 steps, before it could be interrupted"
  fi
  if [ "$signal" = KILL ]; then
    kill -KILL "$pid" $ranks 2>/dev/null || true
  else
    # The signal waits, pending, in each frozen rank and is handled the instant it resumes:
    # a signal sent only to mpiexec after the ranks resume can arrive after their last cell.
    kill "-$signal" $ranks 2>/dev/null || true
    kill -CONT $ranks 2>/dev/null || true
    [ "$ranks" = "$pid" ] || kill "-$signal" "$pid"
  fi
  # mpiexec can return before its ranks have finished exiting; a rank still alive could write in
  # the folder after the caller's `wait`. Wait (at most 30 s) until each is gone or a zombie.
  local rank state
  if [ "$ranks" != "$pid" ]; then
    for rank in $ranks; do
      for step in $(seq 1 3000); do
        state=$(awk '{print $3}' "/proc/$rank/stat" 2>/dev/null) || break
        [ "$state" != Z ] || break
        sleep 0.01
      done
    done
  fi
}
