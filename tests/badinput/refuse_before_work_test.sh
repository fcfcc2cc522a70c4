#!/usr/bin/env bash
# Bad input refused before any work: each case exits 2 with exactly one line of the program's
# own naming the file (or option) at fault, and leaves no output, partial, lock or temporary
# file. Sweep cases run on 1 rank (no mpiexec) and on 2 ranks (the line must survive mpiexec).
# usage: refuse_before_work_test.sh SKEWBRIDGE MPIEXEC WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec work -- "$@"
fresh_dir "$work"
cases=0
leftovers() { ls -d out.h5* run.h5* run.csv 2> /dev/null || true; }
expect() {  # expect RANKS PATTERN ARGS...: exit 2, one own line matching PATTERN, nothing left
  local ranks=$1 pattern=$2 status=0; shift 2
  if [ "$ranks" -eq 1 ]; then "$exe" "$@" > out.txt 2> err.txt || status=$?
  else on_ranks "$ranks" "$exe" "$@" > out.txt 2> err.txt || status=$?; fi
  [ "$status" -eq 2 ] || fail "$* ($ranks ranks): exit $status, expected 2: $(cat err.txt)"
  local own
  own=$(grep -c "^skewbridge: error: " err.txt || true)
  [ "$own" -eq 1 ] || fail "$* ($ranks ranks): $own error lines, expected 1: $(cat err.txt)"
  grep -q -- "$pattern" err.txt || fail "$* ($ranks ranks): '$(cat err.txt)' lacks '$pattern'"
  [ "$ranks" -gt 1 ] || [ "$(wc -l < err.txt)" -eq 1 ] || fail "$*: more than one line: $(cat err.txt)"
  [ -z "$(leftovers)" ] || fail "$* ($ranks ranks) left $(leftovers)"
  cases=$((cases + 1))
  echo "ok ($ranks ranks): $(grep '^skewbridge: error: ' err.txt)"
}
sweep_both() {  # sweep_both PATTERN ARGS...: the sweep case on 1 and 2 ranks
  local pattern=$1; shift
  expect 1 "$pattern" sweep "$@"
  expect 2 "$pattern" sweep "$@"
}
spec() {  # spec FILE AXES_LINES FIXED_LINES
  printf '[sweep]\nname = "bad"\nfamily = "subsystem"\n[axes]\n%b\n[fixed]\n%b\n' "$2" "$3" > "$1"
}

spec good.toml 'w0_over_wg = [0.5, 1.0]' 'eta0 = 1.5'
# The output path.
sweep_both "error: --out: FILE: is empty" good.toml --out ""
mkdir folder.h5
sweep_both "folder.h5: is a folder; --out names the cube file" good.toml --out folder.h5 --force
rmdir folder.h5
sweep_both "nowhere/out.h5: its folder nowhere does not exist" good.toml --out nowhere/out.h5
# A folder nobody may create files in (even root): the lock file cannot be made.
sweep_both "/proc/out.h5.lock: cannot create the lock file of the output: " good.toml --out /proc/out.h5
# A parameter named twice through its symbol.
spec alias_fixed.toml 'w0_over_wg = [0.5, 1.0]' 'eta0 = 1.5\nW0_over_w0 = 1\n"W0/w0" = 2'
sweep_both 'alias_fixed.toml:[89]: fixed.W0[/_].*: names the parameter W0_over_w0 a second time' \
  alias_fixed.toml --out out.h5
spec alias_axes.toml 'w0_over_wg = [0.5, 1.0]\n"w0/w_g" = [2.0]' 'eta0 = 1.5'
sweep_both 'alias_axes.toml:[56]: axes.w0[/_].*: names the parameter w0_over_wg a second time' \
  alias_axes.toml --out out.h5
# The cell count against --max-cells (default 1e8): 10^9 and 2 x 10^10 cells.
spec huge.toml 'w0_over_wg = {linspace = [0.1, 4, 1000]}\na_deg = {linspace = [1, 60, 1000]}\nPi_delta = {linspace = [0.1, 4, 1000]}' 'eta0 = 1.5'
sweep_both "huge.toml: the grid has 1000000000 cells (1000 x 1000 x 1000), more than --max-cells 100000000" \
  huge.toml --out out.h5
spec huger.toml 'w0_over_wg = {linspace = [0.1, 4, 20000]}\na_deg = {linspace = [1, 60, 1000]}\nPi_delta = {linspace = [0.1, 4, 1000]}' 'eta0 = 1.5'
sweep_both "huger.toml: the grid has 20000000000 cells" huger.toml --out out.h5
sweep_both "good.toml: the grid has 2 cells (2), more than --max-cells 1" good.toml --out out.h5 --max-cells 1
# A record set with one label twice.
printf '0.00 0.0\n0.01 0.1\n0.02 -0.1\n0.03 0.0\n' > rec.txt
cat > dup.toml <<'TOML'
name = "dup"
[[record]]
file = "rec.txt"
format = "time-acc"
units = "g"
label = "A"
[[record]]
file = "rec.txt"
format = "time-acc"
units = "g"
label = "A"
TOML
printf '[sweep]\nname = "bad"\nfamily = "pilot-bridge"\n[records]\nset = "dup.toml"\n[axes]\nrecord = ["A"]\nPi_delta = [1.0]\n' > rec_spec.toml
sweep_both "dup.toml:7: label: duplicate record label 'A' (also the record of line 2)" \
  rec_spec.toml --out out.h5
expect 1 "dup.toml:7: label: duplicate record label 'A'" records info dup.toml

# Run controls and derived lengths of a model file, counted before the run.
base=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)/docs/examples/subsystem.toml
mk() {  # mk FILE PERIOD RUN_LINES
  sed -e "s/^T_g = 0.5 .*/T_g = $2/" -e '/^\[run\]/,$d' "$base" > "$1"
  printf '[run]\n%b\n' "$3" >> "$1"
}
mk step.toml 0.5 'method = "time-stepping"\ntime_step_s = 1e-300'
expect 1 "step.toml: run.time_step_s: the run of 2.5 s would take 2.[0-9]*e+300 steps, more than run.max_steps" \
  run step.toml --out run.h5 --csv run.csv
mk interval.toml 0.5 'output_interval_s = 1e-9'
expect 1 "interval.toml: run.output_interval_s: the run of 2.5 s would store [0-9.e+]* history samples; allowed at most 1e7" \
  run interval.toml --out run.h5 --csv run.csv
mk end.toml 0.5 'end_time_s = 1e308\noutput_interval_s = 0.01'
expect 1 "end.toml: run.end_time_s: the run would end at t = 1e+308 s" run end.toml --out run.h5
mk period.toml 1e308 'tail_s = 2.0'
expect 1 "period.toml: excitation: the run would end at t = 1e+308 s" run period.toml --out run.h5
# Excitation numbers at the edge, each named with its file and line.
sed 's/^a_g_g = 0.5 .*/a_g_g = 1e308/' "$base" > ag.toml
expect 1 "ag.toml:29: excitation.a_g_g: the amplitude is inf m/s^2; allowed: finite" run ag.toml --out run.h5
sampled() {  # sampled FILE EXCITATION_LINES
  sed -e '/^\[excitation\]/,$d' "$base" > "$1"
  printf '[excitation]\nkind = "sampled"\ndirection = "x"\n%b\n' "$2" >> "$1"
}
sampled dt0.toml 'values = [0.0, 0.1, 0.0]\ndt_s = 0\nunits = "g"'
expect 1 "dt0.toml:[0-9]*: excitation.dt_s: must be > 0 (got 0)" run dt0.toml --out run.h5
printf '0.0 0.0\n0.02 0.1\n0.01 0.0\n' > reversed.txt
sampled reversed.toml 'file = "reversed.txt"\nunits = "g"'
expect 1 "reversed.txt:3: time 0.01 s does not increase (the line before has 0.02 s)" run reversed.toml --out run.h5
printf '0.0 0.0\n0.0 0.1\n0.0 0.0\n' > still.txt
sampled still.toml 'file = "still.txt"\nunits = "g"'
expect 1 "still.txt:2: time 0 s does not increase (the line before has 0 s)" run still.toml --out run.h5
printf '0.0 0.0\n0.01 1e308\n0.02 0.0\n' > huge.txt
sampled hugeacc.toml 'file = "huge.txt"\nunits = "g"'
expect 1 "huge.txt:2: acceleration 1e+308 times units and scale (9.80665) is not a finite number in m/s^2" run hugeacc.toml --out run.h5
sampled scale.toml 'file = "still.txt"\nunits = "g"\nscale = 1e308'
expect 1 "scale.toml:[0-9]*: excitation.scale: must be finite and at most 1e6" run scale.toml --out run.h5

# Under mpirun the program's line must reach the terminal every time, not 3 runs in 4: each
# of these specifications (a table twice, no axes, a slash in the name, a NaN coordinate, a
# negative xi) 6 times on 2 ranks.
printf '[sweep]\nname = "bad"\nfamily = "subsystem"\n[axes]\nw0_over_wg = [1.0]\n[axes]\na_deg = [10]\n' > twice.toml
printf '[sweep]\nname = "bad"\nfamily = "subsystem"\n[fixed]\neta0 = 1.5\n' > noaxes.toml
printf '[sweep]\nname = "b/ad"\nfamily = "subsystem"\n[axes]\nw0_over_wg = [1.0]\n' > slash.toml
printf '[sweep]\nname = "bad"\nfamily = "subsystem"\n[axes]\nw0_over_wg = [1.0, nan]\n' > nan.toml
printf '[sweep]\nname = "bad"\nfamily = "subsystem"\n[axes]\nw0_over_wg = [1.0]\n[fixed]\nxi = -0.05\n' > xi.toml
for f in twice noaxes slash nan xi; do
  for _ in 1 2 3 4 5 6; do expect 2 "$f.toml" sweep "$f.toml" --out out.h5 > /dev/null; done
  echo "ok (2 ranks, 6 times): $(grep '^skewbridge: error: ' err.txt)"
done
echo "refuse_before_work_test: $cases cases ok"
