#!/usr/bin/env bash
# Record pairs scaled to RotD50 stripes through `skewbridge sweep` (1 rank): the two real pairs
# of tests/data/records/pairs (RSN107, whose H2 is 225 samples shorter, and RSN430) scaled to
# RotD50(T1) of a one-deck model file. The cube's record table states the pairs, their files,
# the zero padding and RotD50, RotD100 (with its angle) and GM at T1, each against scipy and a
# numpy rotation (tests/records/rotd_check.py, no code shared); every cell's factor is its
# stripe over its pair's RotD50; both files of each pair are inputs of the cube. A
# one-component measure of a pair, and a pair measure of a single record, are refused with one
# line naming the field and the record.
# usage: pair_stripes_test.sh SKEWBRIDGE RECORDS_DIR ROTD_CHECK WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe records rotd_check work -- "$@"
fresh_dir "$work"

cp "$test_data/models/one-deck-records.toml" deck.toml
cat > pairs.toml <<TOML
[[record]]
label = "RSN107"
h1 = "$records/pairs/RSN107_OROVILLE_B-OAP180.AT2"
h2 = "$records/pairs/RSN107_OROVILLE_B-OAP270.AT2"
[[record]]
label = "RSN430"
h1 = "$records/pairs/RSN430_SMART1.25_25M01EW.AT2"
h2 = "$records/pairs/RSN430_SMART1.25_25M01NS.AT2"
TOML
spec() {  # spec MEASURE SET
  cat <<TOML
[sweep]
name = "pairs"
family = "model-file"
model = "deck.toml"
[records]
set = "$2"
scale_to = { measure = "$1", period = "T1", xi = 0.05 }
[axes]
record = "*"
im_g = [0.1, 0.3]
TOML
}
spec RotD50 pairs.toml > spec.toml
"$exe" sweep spec.toml --out pairs.h5 --quiet 2> sweep.err || { cat sweep.err; fail "sweep"; }
/usr/bin/python3 - pairs.h5 "$rotd_check" "$records/pairs" <<'PY' || fail "the cube's pair table"
import hashlib
import importlib.util
import os
import sys

import h5py
import numpy as np

cube, check, folder = sys.argv[1:4]
spec = importlib.util.spec_from_file_location("rotd_check", check)
rotd = importlib.util.module_from_spec(spec)
spec.loader.exec_module(rotd)
pairs = rotd.read_pairs(folder)
g = h5py.File(cube, "r")["sweeps/pairs"]
t = g["records"]
text = lambda name: [s.decode() for s in t[name][()]]
assert text("label") == ["RSN107", "RSN430"], text("label")
assert list(t["pair"][()]) == [1, 1]
assert [os.path.basename(f) for f in text("file_h2")] == [
    "RSN107_OROVILLE_B-OAP270.AT2", "RSN430_SMART1.25_25M01NS.AT2"], text("file_h2")
assert text("component") == ["180", "EW"] and text("component_h2") == ["270", "NS"]
assert list(t["npts"][()]) == [2630, 1179]
assert list(t["padded_samples_h1"][()]) == [0, 0]
assert list(t["padded_samples_h2"][()]) == [225, 0]
t1, xi = t.attrs["T1_s"], t.attrs["spectral_xi"]
assert abs(t1 - 2 * np.pi / 10) < 1e-12, t1  # one deck of k/m = 100 (s^-2)
worst = 0.0
for r, label in enumerate(["RSN107", "RSN430"]):
    a1, a2, dt = pairs[label]
    values, peaks, angle = rotd.oracle(a1, a2, dt, t1, xi)
    for name, expected in (("GM_T1_mps2", values[2]), ("RotD50_T1_mps2", values[4]),
                           ("RotD100_T1_mps2", values[5]), ("Sa_T1_mps2", values[0])):
        error = abs(t[name][r] - expected) / expected
        worst = max(worst, error)
        assert error < 1e-6, (label, name, t[name][r], expected)
    assert rotd.angle_matches(t["RotD100_angle_T1_deg"][r], angle, peaks)
    assert abs(t["pga_h2_mps2"][r] - np.abs(a2).max()) <= 1e-12 * np.abs(a2).max()
# Each cell: factor = stripe / the pair's RotD50 (in g), one factor per pair.
rec = list(g["axes/record"][()])
im = g["axes/im_g"][()]
factor = g["responses/scale_factor"][()]
unscaled = g["responses/im_unscaled"][()]
dims = [d.decode() if isinstance(d, bytes) else d for d in g.attrs["axis_order"]]
assert dims == ["record", "im_g"], dims
for r in range(2):
    own = t["RotD50_T1_mps2"][r] / 9.80665
    for s in range(2):
        assert unscaled[r, s] == own, (r, s, unscaled[r, s], own)
        assert abs(factor[r, s] - im[s] / own) <= 1e-12 * factor[r, s], (r, s)
# The inputs: both files of each pair, with their SHA-256.
inputs = g["inputs"]
files = {os.path.basename(f.decode()): (role.decode(), sha.decode())
         for role, f, sha in zip(inputs["role"][()], inputs["file"][()], inputs["sha256"][()])}
for name in ["RSN107_OROVILLE_B-OAP180.AT2", "RSN107_OROVILLE_B-OAP270.AT2",
             "RSN430_SMART1.25_25M01EW.AT2", "RSN430_SMART1.25_25M01NS.AT2"]:
    role, sha = files[name]
    assert role == "record", (name, role)
    assert sha == hashlib.sha256(open(os.path.join(folder, name), "rb").read()).hexdigest()
print(f"pair table and factors: largest relative difference {worst:.2e}")
PY

# A measure of one component on pairs, and a pair measure on single records: one line each.
spec Sa pairs.toml > sa.toml
status=0
"$exe" sweep sa.toml --out sa.h5 2> sa.err || status=$?
[ "$status" = 2 ] && [ "$(wc -l < sa.err)" = 1 ] && [ ! -e sa.h5 ] &&
  grep -q "sa.toml: records.scale_to.measure: record 'RSN107' is a pair of horizontal components and Sa is a measure of one component" sa.err ||
  { cat sa.err; fail "Sa of a pair not refused as expected (status $status)"; }
spec RotD50 "$records/two-records.toml" > single.toml
status=0
"$exe" sweep single.toml --out single.h5 2> single.err || status=$?
[ "$status" = 2 ] && [ "$(wc -l < single.err)" = 1 ] && [ ! -e single.h5 ] &&
  grep -q "single.toml: records.scale_to.measure: record 'NIS090.AT2' is a single component and RotD50 is a measure of a pair" single.err ||
  { cat single.err; fail "RotD50 of a single record not refused as expected (status $status)"; }
echo "pair_stripes: ok"
