#!/usr/bin/env bash
# Responses and fragility over the incidence angle, through `skewbridge sweep` into a real HDF5
# file: the pilot bridge's model file under the two record pairs of tests/data/records/pairs,
# scaled to stripes of RotD50 Sa(T1) at four incidence angles, on 2 ranks.
#  - check_incidence_cube.py: over_incidence/ (max, median, angle of the max of every response)
#    against numpy on the cells, read by h5py and by xarray; per stripe the worst angle's
#    fraction of exceedance >= every angle's;
#  - check_fragility_cube.py: the fits per angle (fragility/) and at the worst angle
#    (fragility_worst_incidence/, its cells reduced with numpy) against scipy.optimize;
#  - the same sweep on 1 rank gives the same cube (same_cube.py: every dataset byte for byte,
#    the bootstraps per angle and at the worst angle that the 2 ranks drew in shares included);
#  - `skewbridge inspect` lists fragility/, fragility_worst_incidence/ and over_incidence/ with
#    the stored fits and the counts numpy finds in the cube;
#  - scripts/report draws the demand against the angle and both fragilities, and its table of
#    the worst-angle fits holds the stored ones;
#  - an IDA sweep of the same two pairs and the two with H1 and H2 exchanged at three angles,
#    its search stopped at 2.6 g so that some records never unseat at some or all angles: its
#    fits per angle and at the worst angle (each record's lowest capacity over the angles,
#    censored where it is infinite at every angle) against numpy and scipy, on 2 ranks and 1.
# usage: incidence_test.sh SKEWBRIDGE MPIEXEC SOURCE_DIR WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec src work -- "$@"
fresh_dir "$work"
cp "$src/docs/examples/pilot-bridge.toml" "$src/docs/examples/pilot-signal.txt" .

cat > angles.toml <<TOML
[sweep]
name = "angles"
family = "model-file"
model = "pilot-bridge.toml"
[records]
set = "$test_data/records/pairs/pairs.toml"
scale_to = { measure = "RotD50", period = "T1", xi = 0.05 }
[axes]
record = ["RSN107", "RSN430_SMART1.25_25M01"]
im_g = {logspace = [0.5, 5.0, 8]}
incidence_deg = [0, 45, 90, 135]
[fixed]
seat_over_L = 0.0005
[limit_states]
unseating = true
rotation = {above_rad = 0.0005}
TOML
on_ranks 2 "$exe" sweep angles.toml --out angles.h5 --quiet || fail "the sweep failed"
/usr/bin/python3 "$src/tests/fragility/check_incidence_cube.py" angles.h5 angles \
  || fail "over_incidence/ or the worst-angle counts differ from numpy"
/usr/bin/python3 "$src/tests/fragility/check_fragility_cube.py" angles.h5 angles 1 \
  || fail "the per-angle fits differ from scipy's"
/usr/bin/python3 "$src/tests/fragility/check_fragility_cube.py" angles.h5 angles 1 --worst-incidence \
  || fail "the worst-angle fits differ from scipy's"
# The two ranks draw the bootstraps of both groups in shares: the same bits as one rank alone.
"$exe" sweep angles.toml --out angles-one.h5 --quiet || fail "the 1-rank sweep failed"
/usr/bin/python3 "$src/scripts/bench/same_cube.py" angles-one.h5 angles.h5 \
  || fail "angles.h5: 2 ranks and 1 rank differ"

# inspect lists every group of the fits and of the responses over the angle, with their numbers.
"$exe" inspect angles.h5 > inspect.txt || fail "inspect angles.h5"
/usr/bin/python3 "$src/tests/fragility/check_inspect_incidence.py" angles.h5 angles inspect.txt \
  || { cat inspect.txt; fail "inspect: the fits or the responses over the angle"; }
# The report draws the demand against the angle and both fragilities, and tabulates the
# worst-angle fits as the cube stores them.
/usr/bin/python3 "$src/scripts/report" angles.h5 --out report > report.txt \
  || fail "scripts/report angles.h5 failed"
[ -s report/incidence_angles.png ] && [ -s report/fragility_incidence_angles.png ] \
  || fail "no figure of the demand against the angle or of the fragility per angle"
/usr/bin/python3 - angles.h5 report/summary.md <<'PY' || fail "the report's worst-angle table differs from the cube"
import sys, h5py
w = h5py.File(sys.argv[1], "r")["sweeps/angles/fragility_worst_incidence"]
text = open(sys.argv[2], encoding="utf-8").read()
assert "## angles: fragility per incidence angle and at the worst angle" in text
for name in ("unseating", "rotation"):
    rows = [l for l in text.splitlines() if l.startswith(f"| {name} | all cells | ")]
    assert len(rows) == 1, rows
    cells = [c.strip() for c in rows[0].strip("|").split("|")]
    assert int(cells[2]) == w[name]["n_cells"][0] and int(cells[3]) == w[name]["n_exceeded"][0]
    theta = float(w[name]["theta"][0])
    assert abs(float(cells[4]) - theta) <= 5e-3 * theta, (cells, theta)
print("report: the worst-angle table holds the stored fits")
PY

# IDA at three angles: each record's capacity per angle and at its worst angle.
pairs="$test_data/records/pairs"
cat > four.toml <<TOML
name = "four"
[[record]]
label = "RSN107"
h1 = "$pairs/RSN107_OROVILLE_B-OAP180.AT2"
h2 = "$pairs/RSN107_OROVILLE_B-OAP270.AT2"
[[record]]
label = "RSN107-H2H1"
h1 = "$pairs/RSN107_OROVILLE_B-OAP270.AT2"
h2 = "$pairs/RSN107_OROVILLE_B-OAP180.AT2"
[[record]]
label = "RSN430"
h1 = "$pairs/RSN430_SMART1.25_25M01EW.AT2"
h2 = "$pairs/RSN430_SMART1.25_25M01NS.AT2"
[[record]]
label = "RSN430-H2H1"
h1 = "$pairs/RSN430_SMART1.25_25M01NS.AT2"
h2 = "$pairs/RSN430_SMART1.25_25M01EW.AT2"
TOML
cat > ida.toml <<TOML
[sweep]
name = "ida"
family = "model-file"
model = "pilot-bridge.toml"
[records]
set = "four.toml"
scale_to = { measure = "RotD50", period = "T1", xi = 0.05 }
[axes]
record = "*"
incidence_deg = [0, 60, 120]
[fixed]
seat_over_L = 0.0005
[limit_states]
unseating = true
rotation = {above_rad = 0.0005}
joint_closing = true
[ida]
start = 0.25
step = 0.5
step_increase = 0.25
tolerance = 0.1
max_im = 2.6
max_runs = 20
TOML
on_ranks 2 "$exe" sweep ida.toml --out ida.h5 --quiet || fail "the IDA sweep failed"
/usr/bin/python3 "$src/tests/fragility/check_fragility_cube.py" ida.h5 ida 7 \
  || fail "the IDA fits per angle differ from numpy's and scipy's"
/usr/bin/python3 "$src/tests/fragility/check_fragility_cube.py" ida.h5 ida 3 --worst-incidence \
  || fail "the IDA fits at the worst angle differ from numpy's and scipy's"
"$exe" sweep ida.toml --out ida-one.h5 --quiet || fail "the 1-rank IDA sweep failed"
/usr/bin/python3 "$src/scripts/bench/same_cube.py" ida-one.h5 ida.h5 \
  || fail "ida.h5: 2 ranks and 1 rank differ"
"$exe" inspect ida.h5 > inspect-ida.txt || fail "inspect ida.h5"
/usr/bin/python3 "$src/tests/fragility/check_inspect_incidence.py" ida.h5 ida inspect-ida.txt \
  || { cat inspect-ida.txt; fail "inspect: the IDA fits or the responses over the angle"; }
echo "incidence_test: ok"
