#!/usr/bin/env bash
# The sweep and inspect commands from the outside: bad specifications and unusable output files
# fail with exit status 2 and one line naming the key, before any file is written; a resume
# with another specification is refused, and so is a checkpoint lacking a response dataset the
# evaluator declares (one line naming it, exit 2, the file byte for byte unchanged); inspect
# reports axes, responses and completion.
# usage: cli_test.sh SKEWBRIDGE SWEEP_DRIVER WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args skewbridge driver work -- "$@"
fresh_dir "$work"
spec() {  # spec FILE EXTRA_AXIS_LINE
  cat > "$1" <<TOML
[sweep]
name = "cli"
family = "subsystem"
[axes]
pulse = ["cosine", "sine"]
$2
w0_over_wg = {logspace = [0.5, 2.0, 4]}
[fixed]
eta0 = 1.5
TOML
}
expect_error() {  # expect_error PATTERN COMMAND...
  local pattern=$1; shift
  local status=0
  "$@" > out.txt 2> err.txt || status=$?
  [ "$status" -eq 2 ] || fail "$* exited with $status, expected 2"
  grep -q -- "$pattern" err.txt || fail "$*: message '$(cat err.txt)' lacks '$pattern'"
  [ "$(wc -l < err.txt)" -eq 1 ] || fail "$*: more than one line on stderr"
}

spec bad_axis.toml 'skew = [10, 20]'
expect_error "bad_axis.toml:6: axes.skew: unknown parameter" "$driver" bad_axis.toml --out a.h5
spec bad_pi.toml 'Pi_delta = [1.0, -0.5]'
expect_error "axes.Pi_delta: must be a number >= 0 (got -0.5)" "$driver" bad_pi.toml --out a.h5
spec bad_n.toml 'a_deg = {linspace = [10, 50, 0]}'
expect_error "axes.a_deg.linspace: n must be a whole number >= 1" "$driver" bad_n.toml --out a.h5
ls a.h5* >/dev/null 2>&1 && fail "a bad specification left an output file"
# The program itself: same parser, and a clear refusal for a family it cannot evaluate.
expect_error "axes.skew: unknown parameter" "$skewbridge" sweep bad_axis.toml --out a.h5

spec good.toml 'a_deg = [10, 40]'
"$driver" good.toml --out cube.h5 --quiet --work 10 2> /dev/null
expect_error "cube.h5: already exists; use --resume to continue it or --force" \
  "$driver" good.toml --out cube.h5
spec other.toml 'a_deg = [10, 45]'
expect_error "cube.h5: cannot resume: other.toml: key axes.a_deg differs from the specification the cube was computed with (cube: \[10, 40\]; now: \[10, 45\])" \
  "$driver" other.toml --out cube.h5 --resume
cp cube.h5 copy.h5
"$driver" good.toml --out cube.h5 --resume --quiet 2> err.txt
grep -q "already complete" err.txt || fail "resume of a complete cube: $(cat err.txt)"

"$skewbridge" inspect cube.h5 > inspect.txt
grep -q "sweep cli (family subsystem" inspect.txt || fail "inspect: no sweep line"
grep -Eq "w0_over_wg +4  0.5 .. 2" inspect.txt || fail "inspect: w0_over_wg axis"
grep -Eq "pulse +2  cosine, sine" inspect.txt || fail "inspect: pulse axis"
grep -q "x_peak" inspect.txt || fail "inspect: responses"
grep -q "completion: 16/16 cells done (100.0%), complete" inspect.txt || fail "inspect: completion"
expect_error "nothing.h5: the file does not exist" "$skewbridge" inspect nothing.h5
printf 'not hdf5\n' > text.h5
expect_error "text.h5: cannot open as an HDF5 file" "$skewbridge" inspect text.h5

# A checkpoint from a program version without one response: interrupted (SIGTERM, as a batch
# system would), one response dataset deleted with h5py, then --resume refuses before any work.
"$driver" good.toml --out old.h5 --quiet --work 10 --sleep-ms 100 2> /dev/null &
pid=$!
for _ in $(seq 1 200); do [ -f old.h5.partial ] && break; sleep 0.02; done
kill -TERM "$pid"
wait "$pid" || true
[ -f old.h5.partial ] && [ ! -f old.h5 ] || fail "no checkpoint left by the interrupted sweep"
/usr/bin/python3 -c "import h5py; f = h5py.File('old.h5.partial', 'r+'); del f['sweeps/cli/responses/theta_peak']; f.close()"
cp old.h5.partial old.before
expect_error "old.h5.partial: cannot resume: it has no dataset sweeps/cli/responses/theta_peak" \
  "$driver" good.toml --out old.h5 --resume --quiet --work 10
cmp -s old.h5.partial old.before || fail "the refused checkpoint was modified"
[ ! -f old.h5 ] || fail "the refused resume wrote old.h5"
echo "cli_test: ok"
