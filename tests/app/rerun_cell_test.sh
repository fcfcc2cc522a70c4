#!/usr/bin/env bash
# A cell of a model-file sweep run again: the two real AT2 records of tests/data/records scaled to
# Sa(T1) stripes of a one-deck model file between abutments 20 mm away, with limit states (so the
# cube stores the exact corner travel). `skewbridge run --from-cube` re-runs cells by their
# coordinates and by their index; check_rerun.py compares each run file's maxima, residuals,
# corner travel and impacts with the cube's stored responses bit for bit (at least one cell with
# impacts), and the ground acceleration the runs applied with the AT2 files parsed by numpy.
# `run --record FILE.AT2 --scale F` (F the cube's scale_factor) and `run --record-set --label
# --target-sa-g` give the cell again. Cells of a subsystem sweep under pulses and of a
# pilot-bridge sweep under synthetic records equal their cubes the same way, and so do cells of a
# sweep under policies of its own, of either integrator. Bad coordinates, a
# changed input and a multi-span cube are refused with one line, status 2, no output. The report
# draws a re-run's histories.
# usage: rerun_cell_test.sh SKEWBRIDGE SOURCE_DIR WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe src work -- "$@"
fresh_dir "$work"

# Local copies of the inputs, so that the test may change them.
mkdir -p recs
cp "$test_data/records/NIS090.AT2" "$test_data/records/RSN763_LOMAP_GIL067.AT2" \
  "$test_data/records/two-records.toml" recs/
cp "$test_data/models/one-deck-records.toml" deck.toml
cat > spec.toml <<'TOML'
[sweep]
name = "cells"
family = "model-file"
model = "deck.toml"
[records]
set = "recs/two-records.toml"
scale_to = { measure = "Sa", period = "T1", xi = 0.05 }
[limit_states]
joint_closing = true
seat_displacement = { above_m = 0.05 }
[axes]
record = "*"
im_g = [0.05, 1.1]
k_factor = [1, 2]
TOML
"$exe" sweep spec.toml --out cube.h5 --quiet 2> sweep.err || { cat sweep.err; fail "sweep"; }

# Four cells by coordinates (a linspace-free axis typed with its own digits, and one typed
# with more digits than it needs), two by index.
"$exe" run --from-cube cube.h5 --cell "record=NIS090.AT2,im_g=1.1,k_factor=1" --out c_a.h5 \
  > a.txt || fail "re-run by coordinates"
grep -q "^cube cube.h5, sweep cells, cell 2 (record=NIS090.AT2, im_g=1.1, k_factor=1)" a.txt ||
  { cat a.txt; fail "the summary's first line"; }
"$exe" run --from-cube cube.h5 --cell " k_factor=2 , record=RSN763_LOMAP_GIL067.AT2, im_g=1.10000" \
  --out c_b.h5 > b.txt || fail "re-run, axes in another order"
"$exe" run --from-cube cube.h5 --cell "record=RSN763_LOMAP_GIL067.AT2,im_g=0.05,k_factor=1" \
  --out c_c.h5 > c.txt || fail "re-run at the low stripe"
"$exe" run --from-cube cube.h5 --cell-index 3 --out c_d.h5 --output-interval 0.002 > d.txt ||
  fail "re-run by index"
"$exe" run --from-cube cube.h5 --cell-index 0 --out c_e.h5 --csv c_e.csv > e.txt ||
  fail "re-run by index with a CSV"

# The cell again from the model file: the record file itself at the cube's factor (printed with
# every digit), and the set's record scaled to the cell's stripe.
factor=$(/usr/bin/python3 -c '
import h5py
g = h5py.File("cube.h5", "r")["sweeps/cells"]
print(repr(float(g["responses/scale_factor"][0, 1, 0])))')
"$exe" run deck.toml --record recs/NIS090.AT2 --scale "$factor" --out r_file.h5 --output-interval 0.01 > rf.txt ||
  fail "run --record FILE.AT2 --scale"
"$exe" run deck.toml --record-set recs/two-records.toml --label NIS090.AT2 --target-sa-g 1.1 --output-interval 0.01 \
  --out r_set.h5 > rs.txt || fail "run --record-set --label --target-sa-g"

/usr/bin/python3 "$src/tests/app/check_rerun.py" cube.h5 recs \
  c_a.h5 c_b.h5 c_c.h5 c_d.h5 c_e.h5 -- r_file.h5 r_set.h5 ||
  fail "re-runs against the cube"

# Bad input: one line, status 2, no output file.
bad() {
  local pattern=$1
  shift
  set +e; err=$("$exe" run "$@" --out bad.h5 2>&1 >/dev/null); status=$?; set -e
  [ "$status" = 2 ] || fail "$*: status $status ($err)"
  [ "$(printf '%s\n' "$err" | wc -l)" = 1 ] || fail "$*: not one line: $err"
  printf '%s\n' "$err" | grep -qF -- "$pattern" || fail "$*: '$err' lacks '$pattern'"
  [ ! -e bad.h5 ] && [ ! -e bad.h5.partial ] || fail "$*: output left"
}
bad "--cell: im_g: 0.7 is not a coordinate of the axis; allowed: 0.05, 1.1" \
  --from-cube cube.h5 --cell "record=NIS090.AT2,im_g=0.7,k_factor=1"
bad "--cell: record: NIS09.AT2 is not a coordinate of the axis; allowed: NIS090.AT2, RSN763_LOMAP_GIL067.AT2" \
  --from-cube cube.h5 --cell "record=NIS09.AT2,im_g=0.05,k_factor=1"
bad "--cell: k_factor: missing: name its coordinate, one of 1, 2" \
  --from-cube cube.h5 --cell "record=NIS090.AT2,im_g=0.05"
bad "--cell: seat_m: not an axis of the sweep; its axes: record, im_g, k_factor" \
  --from-cube cube.h5 --cell "record=NIS090.AT2,im_g=0.05,k_factor=1,seat_m=0.3"
bad "--cell-index: 8: sweep 'cells' has 8 cells: allowed 0 to 7" --from-cube cube.h5 --cell-index 8
bad "--from-cube: cube.h5: needs --cell AXIS=VALUE,... or --cell-index N" --from-cube cube.h5
bad "--label: NIS091.AT2: not a record of recs/two-records.toml; its labels: NIS090.AT2, RSN763_LOMAP_GIL067.AT2" \
  deck.toml --record-set recs/two-records.toml --label NIS091.AT2
bad "--scale: scales a record" deck.toml --scale 2
bad "--scale: 0: must be a number > 0" deck.toml --record recs/NIS090.AT2 --scale 0
bad "--scale: -2: must be a number > 0" deck.toml --record recs/NIS090.AT2 --scale -2

# A result never outlives its inputs: a changed model file or record is named, then restored.
cp deck.toml deck.keep
echo "# a comment changes the bytes" >> deck.toml
bad "cube.h5: cannot re-run a cell of sweep 'cells': deck.toml (model) has changed since the cube was computed from it" \
  --from-cube cube.h5 --cell-index 0
mv deck.keep deck.toml
cp recs/NIS090.AT2 nis.keep
sed -i '5s/0.233833E-06/0.233834E-06/' recs/NIS090.AT2
bad "recs/NIS090.AT2 (record) has changed since the cube was computed from it" \
  --from-cube cube.h5 --cell-index 0
mv nis.keep recs/NIS090.AT2
"$exe" run --from-cube cube.h5 --cell-index 0 > /dev/null || fail "restored inputs refused"

# The subsystem under pulses (with limit states, so the exact travel is stored) and the pilot
# bridge under two synthetic records: cells re-run equal the cube too.
cat > pulse.toml <<'TOML'
[sweep]
name = "pulse"
family = "subsystem"
[fixed]
eta0 = 1.0
[limit_states]
joint_closing = true
[axes]
a_deg = [20, 45]
Pi_delta = [0.5, 4.0]
w0_over_wg = [0.5, 3.0]
TOML
"$exe" sweep pulse.toml --out pulse.h5 --quiet 2> pulse.err || { cat pulse.err; fail "sweep pulse"; }
cat > pilot.toml <<'TOML'
[sweep]
name = "pilot"
family = "pilot-bridge"
[records]
synthetic = {count = 2, seed = 2011}
[axes]
record = "*"
Pi_delta = [0.5, 2.0]
TOML
"$exe" sweep pilot.toml --out pilot.h5 --quiet 2> pilot.err || { cat pilot.err; fail "sweep pilot"; }
for i in 0 3 5; do
  "$exe" run --from-cube pulse.h5 --cell-index "$i" --out "p_$i.h5" > /dev/null ||
    fail "re-run subsystem cell $i"
done
"$exe" run --from-cube pilot.h5 --cell "record=synth-2011-001,Pi_delta=0.5" --out q_1.h5 > /dev/null ||
  fail "re-run pilot cell"
"$exe" run --from-cube pilot.h5 --cell-index 0 --out q_0.h5 > /dev/null || fail "re-run pilot cell 0"
/usr/bin/python3 "$src/tests/app/check_rerun.py" --spectra pulse.h5 p_0.h5 p_3.h5 p_5.h5 ||
  fail "subsystem re-runs against the cube"
/usr/bin/python3 "$src/tests/app/check_rerun.py" --spectra pilot.h5 q_0.h5 q_1.h5 ||
  fail "pilot-bridge re-runs against the cube"

# A sweep under policies of its own for both integrators ([event_policy], [time_stepping_policy]):
# cells of either method re-run equal the cube, each run file storing the cube's policy of its
# method (check_rerun.py), which is the sweep's.
cat > policy.toml <<'TOML'
[sweep]
name = "policy"
family = "subsystem"
[fixed]
eta0 = 1.0
a_deg = 30
[limit_states]
joint_closing = true
[axes]
method = ["event-driven", "time-stepping"]
Pi_delta = [0.5, 4.0]
w0_over_wg = [0.5, 3.0]
[event_policy]
steps_per_period = 7.5
jam = false
[time_stepping_policy]
active_set_lookahead = 1.0
normal_compliance = 1e-6
TOML
"$exe" sweep policy.toml --out policy.h5 --quiet 2> policy.err || { cat policy.err; fail "sweep policy"; }
for i in 0 1 4 7; do  # 0, 1: both methods at the cell with impacts
  "$exe" run --from-cube policy.h5 --cell-index "$i" --out "e_$i.h5" > /dev/null ||
    fail "re-run policy cell $i"
done
/usr/bin/python3 "$src/tests/app/check_rerun.py" --spectra policy.h5 e_0.h5 e_1.h5 e_4.h5 e_7.h5 ||
  fail "re-runs under the sweep's policies against the cube"
# The same sweep under the integrators' defaults: the cells with impacts move with either policy.
sed '/^\[event_policy\]/,$d' policy.toml > defaults.toml
"$exe" sweep defaults.toml --out defaults.h5 --quiet 2> defaults.err || { cat defaults.err; fail "sweep defaults"; }
/usr/bin/python3 - <<'PY' || fail "the policies stored"
import h5py
g = h5py.File("policy.h5", "r")["sweeps/policy"]
d = h5py.File("defaults.h5", "r")["sweeps/policy"]
moved = (g["responses/x_m"][()] != d["responses/x_m"][()]).ravel()
impacts = g["responses/impacts"][()].ravel()
assert moved[0] and moved[1] and impacts[0] > 0 and impacts[1] > 0, (moved, impacts)
assert "event_policy.steps_per_period = 7.5" in g.attrs["spec_canonical"]
assert g.attrs["spec_hash"] != d.attrs["spec_hash"]
assert g["event_policy"].attrs["steps_per_period"] == 7.5
assert g["event_policy"].attrs["jam"] == 0
assert g["time_stepping_policy"].attrs["active_set_lookahead"] == 1.0
assert h5py.File("e_0.h5", "r")["event_policy"].attrs["steps_per_period"] == 7.5
assert h5py.File("e_1.h5", "r")["time_stepping_policy"].attrs["normal_compliance"] == 1e-6
PY

# The multi-span family is refused by name.
cat > spans.toml <<'TOML'
[sweep]
name = "spans"
family = "multi-span"
[axes]
spans = [1, 2]
[fixed]
W_over_L = 0.3
w0_over_wg = 1.0
TOML
"$exe" sweep spans.toml --out spans.h5 --quiet 2> spans.err || { cat spans.err; fail "sweep spans"; }
bad "spans.h5: sweep 'spans' is of family multi-span; a cell is re-run for the model-file, subsystem and pilot-bridge families" \
  --from-cube spans.h5 --cell-index 0

# The report draws a re-run's histories, the ground acceleration from the run file.
"$src/scripts/report" --run c_a.h5 --out report > report.txt 2>&1 || { cat report.txt; fail "report"; }
[ -s report/history_c_a.png ] || fail "report: no history_c_a.png"
grep -qF "Ran sweep 'cells' of cube.h5, cell 2 (record=NIS090.AT2, im_g=1.1, k_factor=1)" report/summary.md ||
  { cat report/summary.md; fail "report: the run's origin"; }
echo "rerun_cell_test: ok"
