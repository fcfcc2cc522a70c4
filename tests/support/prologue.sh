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
#    later (`... & pid=$!`) starts "$mpiexec" itself, so that $! is mpiexec's own pid.

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
on_ranks() {
  local n=$1
  shift
  "${mpiexec:?on_ranks: the test has no mpiexec argument}" -n "$n" --oversubscribe "$@"
}
