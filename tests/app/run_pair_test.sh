#!/usr/bin/env bash
# `skewbridge run --record-set SET --label PAIR --incidence-deg A`: one run of a record pair of a
# set (RSN107 of tests/data/records/pairs, whose two files differ in length), H1 along A from the
# bridge's x axis and H2 at +90 deg, scaled by --target-rotd50-g to RotD50(T1) = X g, equals the
# cell (record = RSN107, incidence_deg = A, im_g = X) of a model-file sweep bit for bit (maxima,
# residuals, exact corner travel, impacts), and so does `--scale` with the cube's factor; the
# same pair at another angle, and its H1 alone along A, give other maxima. --incidence-deg turns
# a single record as the sweep's axis does. Bad input: one line, status 2, no output.
# usage: run_pair_test.sh SKEWBRIDGE WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe work -- "$@"
fresh_dir "$work"

pairs="$test_data/records/pairs"
cp "$test_data/models/one-deck-records.toml" deck.toml
cat > set.toml <<TOML
name = "pair"
[[record]]
label = "RSN107"
h1 = "$pairs/RSN107_OROVILLE_B-OAP180.AT2"
h2 = "$pairs/RSN107_OROVILLE_B-OAP270.AT2"
[[record]]
label = "H1"
file = "$pairs/RSN107_OROVILLE_B-OAP180.AT2"
TOML
cat > spec.toml <<'TOML'
[sweep]
name = "pair"
family = "model-file"
model = "deck.toml"
[records]
set = "set.toml"
scale_to = { measure = "RotD50", period = "T1", xi = 0.05 }
[limit_states]
joint_closing = true
[axes]
record = ["RSN107"]
im_g = [0.6]
incidence_deg = [30, 120]
TOML
"$exe" sweep spec.toml --out cube.h5 --quiet 2> sweep.err || { cat sweep.err; fail "sweep"; }
cat > single.toml <<'TOML'
[sweep]
name = "single"
family = "model-file"
model = "deck.toml"
[records]
set = "set.toml"
[limit_states]
joint_closing = true
[axes]
record = ["H1"]
scale = [8]
incidence_deg = [30]
TOML
"$exe" sweep single.toml --out single.h5 --quiet 2> single.err || { cat single.err; fail "sweep"; }

factor=$(/usr/bin/python3 -c '
import h5py
g = h5py.File("cube.h5", "r")["sweeps/pair"]
print(repr(float(g["responses/scale_factor"][0, 0, 0])))')
run() { "$exe" run deck.toml "$@" > /dev/null 2> run.err || { cat run.err; fail "run $*"; }; }
run --record-set set.toml --label RSN107 --target-rotd50-g 0.6 --incidence-deg 30 --out p30.h5
run --record-set set.toml --label RSN107 --scale "$factor" --incidence-deg 30 --out p30s.h5
run --record-set set.toml --label RSN107 --target-rotd50-g 0.6 --incidence-deg 120 --out p120.h5
run --record-set set.toml --label H1 --scale "$factor" --incidence-deg 30 --out h30.h5
run --record-set set.toml --label H1 --scale 8 --incidence-deg 30 --out s30.h5

/usr/bin/python3 - "$factor" <<'PY' || fail "runs against the cubes"
import sys
import h5py
import numpy as np

def maxima(path):
    with h5py.File(path, "r") as f:
        s = f["summary"]
        return {"x_m_d0": s["max_abs_q"][0], "y_m_d0": s["max_abs_q"][1],
                "theta_m_d0": s["max_abs_q"][2], "x_end_d0": s["q_end"][0],
                "y_end_d0": s["q_end"][1], "theta_end_d0": s["q_end"][2],
                "travel_m_d0": s["max_travel_m"][0], "impacts": float(s.attrs["impacts"])}

def cell(cube, sweep, index):
    with h5py.File(cube, "r") as f:
        r = f[f"sweeps/{sweep}/responses"]
        return {name: r[name][index] for name in maxima("p30.h5")}

def same(run, stored, what):
    for name, value in maxima(run).items():
        assert np.float64(value).tobytes() == np.float64(stored[name]).tobytes(), \
            (what, name, value, stored[name])

at30, at120 = cell("cube.h5", "pair", (0, 0, 0)), cell("cube.h5", "pair", (0, 1, 0))
assert at30["impacts"] > 0, at30
same("p30.h5", at30, "--target-rotd50-g at 30 deg")
same("p30s.h5", at30, "--scale at 30 deg")
same("p120.h5", at120, "--target-rotd50-g at 120 deg")
same("s30.h5", cell("single.h5", "single", (0, 0, 0)), "a single record at 30 deg")
with h5py.File("p30.h5", "r") as f:
    o = f["origin"].attrs
    assert o["kind"] in ("record-pair", b"record-pair"), o["kind"]
    assert float(o["incidence_deg"]) == 30.0 and float(o["scale_factor"]) == float(sys.argv[1])
for other in ("p120.h5", "h30.h5"):
    assert maxima(other)["y_m_d0"] != at30["y_m_d0"], other
PY

bad() {
  local pattern=$1
  shift
  set +e; err=$("$exe" run deck.toml "$@" --out bad.h5 2>&1 >/dev/null); status=$?; set -e
  [ "$status" = 2 ] || fail "$*: status $status ($err)"
  [ "$(printf '%s\n' "$err" | wc -l)" = 1 ] || fail "$*: not one line: $err"
  printf '%s\n' "$err" | grep -qF -- "$pattern" || fail "$*: '$err' lacks '$pattern'"
  [ ! -e bad.h5 ] && [ ! -e bad.h5.partial ] || fail "$*: output left"
}
bad "--target-sa-g: RSN107: is a measure of one component and 'RSN107' is a pair of horizontal components; allowed for a pair: --scale, --target-rotd50-g" \
  --record-set set.toml --label RSN107 --target-sa-g 0.6
bad "--target-rotd50-g: 0.6: RotD50 is a measure of a pair of horizontal components" \
  --record-set set.toml --label H1 --target-rotd50-g 0.6
bad "--incidence-deg: 400: must be an angle in [-360, 360] deg from the bridge's x axis" \
  --record-set set.toml --label RSN107 --scale 2 --incidence-deg 400
bad "--from-cube: cube.h5: takes the model, record, scale and incidence from the cube" \
  --from-cube cube.h5 --cell-index 0 --incidence-deg 30
echo "run_pair_test: a pair at 30 and 120 deg and a single record at 30 deg equal their cells"
