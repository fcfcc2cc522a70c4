#!/usr/bin/env bash
# Limit states and fragility end to end, through `skewbridge sweep` into real HDF5 files:
#  1. the pilot bridge's model file under a 12-record synthetic suite scaled in 8 stripes, on 2
#     ranks: check_fragility_cube.py refits every stored fragility with scipy.optimize; the
#     cube of 1 rank is the same byte for byte (the bootstraps drawn in shares on 2 ranks);
#  2. real records (tests/data/records) with gaps and seats larger than any response: no cell
#     closes a joint or unseats, P = 0 at every stripe and the fit says why it gives no number;
#  3. the same records with zero gaps and zero seats: every cell impacts and unseats (P = 1);
#  the report draws both figures and tabulates the stored fits;
#  4. a synthetic suite scaled to stripes with max_scale, the cells beyond it kept in the fits
#     or left out (beyond_max_scale = "exclude"): the same cells, fits refitted without them;
#  5. bad [limit_states] keys: one line naming the key, exit status 2, no output file.
# usage: fragility_sweep_test.sh SKEWBRIDGE MPIEXEC SOURCE_DIR WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec src work -- "$@"
fresh_dir "$work"
mkdir rec
cp "$src/docs/examples/pilot-bridge.toml" "$src/docs/examples/pilot-signal.txt" .
cp "$src/tests/data/records/NIS090.AT2" "$src/tests/data/records/RSN763_LOMAP_GIL067.AT2" \
   "$src/tests/data/records/0111a.smc" rec/

cat > stripes.toml <<'TOML'
[sweep]
name = "stripes"
family = "model-file"
model = "pilot-bridge.toml"
[records]
synthetic = {count = 12, seed = 5}
[axes]
record = "*"
scale = {logspace = [0.25, 6.0, 8]}
a_deg = [20, 40]
[fixed]
gap_m = 0.02
[limit_states]
rotation = {above_rad = 0.0005}
unseating = {seat_m = 0.1}
joint_closing = true
response = {x_m_d0 = 0.08}
TOML
on_ranks 2 "$exe" sweep stripes.toml --out stripes.h5 --quiet \
  || fail "the stripes sweep failed"
/usr/bin/python3 "$src/tests/fragility/check_fragility_cube.py" stripes.h5 stripes 3 \
  || fail "stripes.h5: the stored fits differ from scipy's"
# The two ranks draw the bootstraps in shares: the same bits as one rank drawing them all.
"$exe" sweep stripes.toml --out stripes-one.h5 --quiet || fail "the 1-rank stripes sweep failed"
/usr/bin/python3 "$src/scripts/bench/same_cube.py" stripes-one.h5 stripes.h5 \
  || fail "stripes.h5: 2 ranks and 1 rank differ"

# The report draws the curves and the cloud and tabulates the stored fits.
/usr/bin/python3 "$src/scripts/report" stripes.h5 --out report > report.txt \
  || fail "scripts/report stripes.h5 failed"
[ -s report/fragility_stripes.png ] && [ -s report/cloud_stripes.png ] \
  || fail "no fragility or cloud figure"
/usr/bin/python3 - stripes.h5 report/summary.md <<'PY' || fail "the report's table differs from the cube"
import sys, h5py
f = h5py.File(sys.argv[1], "r")["sweeps/stripes/fragility"]
text = open(sys.argv[2], encoding="utf-8").read()
assert "## stripes: fragility functions" in text
rows = [l for l in text.splitlines() if l.startswith("| rotation | α = ")]
assert len(rows) == 2, rows
for k, row in enumerate(rows):
    cells = [c.strip() for c in row.strip("|").split("|")]
    assert int(cells[2]) == f["rotation/n_cells"][k] and int(cells[3]) == f["rotation/n_exceeded"][k]
    assert abs(float(cells[4]) - f["rotation/theta"][k]) <= 5e-3 * f["rotation/theta"][k], cells
print("report: the table holds the stored fits")
PY

# Gaps and seats of 100 m: no response reaches them.
sed -e 's/^name = "stripes"/name = "wide"/' -e '/^\[records\]/,/^\[axes\]/c\[records]\nfolder = "rec"\npattern = "*"\n[axes]' \
    -e 's/^gap_m = .*/gap_m = 100.0/' -e 's/^unseating = .*/unseating = {seat_m = 100.0}/' \
    stripes.toml > wide.toml
"$exe" sweep wide.toml --out wide.h5 --quiet || fail "the wide-gap sweep failed"
# Zero gaps and zero seats: the deck touches both abutments from the start and slides off.
sed -e 's/^name = "stripes"/name = "tight"/' -e '/^\[records\]/,/^\[axes\]/c\[records]\nfolder = "rec"\npattern = "*"\n[axes]' \
    -e 's/^gap_m = .*/gap_m = 0.0/' -e 's/^unseating = .*/unseating = {seat_m = 0.0}/' \
    -e 's/^scale = .*/scale = [0.5, 1.0, 2.0]/' -e 's/^a_deg = .*/a_deg = [20]/' \
    stripes.toml > tight.toml
"$exe" sweep tight.toml --out tight.h5 --quiet || fail "the zero-gap sweep failed"
/usr/bin/python3 - wide.h5 tight.h5 <<'PY' || fail "the bounding bridges do not give P = 0 and P = 1"
import sys, h5py, numpy as np
w = h5py.File(sys.argv[1], "r")["sweeps/wide"]
t = h5py.File(sys.argv[2], "r")["sweeps/tight"]
assert len(w["axes/record"]) == 3 and w["status"][()].max() == 0
for name in ("joint_closing", "unseating"):
    z = w["responses/ls_" + name][()]
    assert z.size == 48 and (z == 0).all(), "wide gap: %s exceeded in %d cells" % (name, (z != 0).sum())
    f = w["fragility/" + name]
    assert (f["stripe_exceeded"][()] == 0).all() and (f["stripe_n"][()] == 3).all()
    assert np.isnan(f["theta"][()]).all()
    assert all(r.decode().startswith("no exceedance in 24 cells") for r in f["reason"][()]), f["reason"][()]
assert (w["responses/impacts"][()] == 0).all()
for name in ("joint_closing", "unseating"):
    z = t["responses/ls_" + name][()]
    assert (z == 1).all(), "zero gap and seat: %s not exceeded in %d cells" % (name, (z != 1).sum())
    f = t["fragility/" + name]
    assert (f["stripe_exceeded"][()] == f["stripe_n"][()]).all()
    assert all(r.decode().startswith("exceeded in all 9 cells") for r in f["reason"][()])
print("wide gap: P = 0 in all 48 cells; zero gap and seat: P = 1 in all 9 cells")
PY

# Stripes of Sa(T1) from a synthetic suite with max_scale: the cells scaled beyond it are kept
# in the fits (the default) or left out (beyond_max_scale = "exclude"). Both cubes hold the same
# cells; check_fragility_cube.py refits the excluding cube with those cells removed (found from
# scale_factor > max_scale, not from the stored flag) and checks the counts per fit and stripe.
cat > scaled.toml <<'TOML'
[sweep]
name = "scaled"
family = "model-file"
model = "pilot-bridge.toml"
[records]
synthetic = {count = 20, seed = 5}
scale_to = {measure = "Sa", period = "T1", xi = 0.05}
max_scale = 3.0
[axes]
record = "*"
im_g = {logspace = [0.2, 4.0, 8]}
a_deg = [20, 40]
[fixed]
gap_m = 0.02
[limit_states]
rotation = {above_rad = 0.0003}
response = {x_m_d0 = 0.025}
TOML
sed -e 's/^name = "scaled"/name = "kept"/' scaled.toml > kept.toml
sed -i -e 's/^max_scale = 3.0/max_scale = 3.0\nbeyond_max_scale = "exclude"/' scaled.toml
on_ranks 2 "$exe" sweep scaled.toml --out scaled.h5 --quiet || fail "the excluding sweep failed"
"$exe" sweep kept.toml --out kept.h5 --quiet || fail "the keeping sweep failed"
/usr/bin/python3 "$src/tests/fragility/check_fragility_cube.py" scaled.h5 scaled 3 \
  || fail "scaled.h5: the fits with the cells beyond max_scale left out differ from scipy's"
/usr/bin/python3 "$src/tests/fragility/check_fragility_cube.py" kept.h5 kept 1 \
  || fail "kept.h5: the stored fits differ from scipy's"
/usr/bin/python3 - scaled.h5 kept.h5 <<'PY' || fail "exclude and keep: cells or counts"
import sys, h5py, numpy as np
s, k = h5py.File(sys.argv[1], "r")["sweeps/scaled"], h5py.File(sys.argv[2], "r")["sweeps/kept"]
assert s.attrs["beyond_max_scale"] == "exclude" and k.attrs["beyond_max_scale"] == "keep"
for name in s["responses"]:
    assert np.array_equal(s["responses/" + name][()], k["responses/" + name][()], equal_nan=True), name
far = int((s["responses/scale_factor"][()] > 3.0).sum())
assert 0 < far < s["responses/scale_factor"].size, "max_scale = 3 must split the cells: %d" % far
for ls in ("rotation", "x_m_d0"):
    n_out = s["fragility/%s/n_excluded_beyond_max_scale" % ls][()]
    assert n_out.sum() == far, (ls, n_out, far)
    assert (s["fragility/%s/n_cells" % ls][()] + n_out == k["fragility/%s/n_cells" % ls][()]).all()
    assert "n_excluded_beyond_max_scale" not in k["fragility/" + ls]
print("exclude: %d of %d cells beyond max_scale left out of every fit; keep: all in"
      % (far, s["responses/scale_factor"].size))
PY
"$exe" inspect scaled.h5 > scaled.txt || fail "inspect scaled.h5"
grep -q 'cells scaled beyond records.max_scale = 3 are left out of every fit' scaled.txt ||
  { cat scaled.txt; fail "inspect: no line on the excluded cells"; }
# The report's fragility table states the count per fit; both figures are drawn.
mkdir -p scaled_report
/usr/bin/python3 - scaled.h5 "$src/scripts" <<'PY' || fail "the report's fragility table or figures"
import sys
sys.path.insert(0, sys.argv[2])
import h5py
from skewbridge_report import data, fragility
sweep = data.load_cube(sys.argv[1])[0]
path, rows = fragility.fragility_curves(sweep, "scaled_report", "fragility_scaled", False)
f = h5py.File(sys.argv[1], "r")["sweeps/scaled/fragility"]
for row in rows:
    n = f[row[0]]["n_excluded_beyond_max_scale"][()][1 if "40" in row[1] else 0]
    assert row[-1].startswith("%d cell(s) scaled beyond max_scale left out of the fits" % n), row
assert fragility.cloud(sweep, "scaled_report", "cloud_scaled", False)
print("report: the table states the cells left out per fit")
PY

# Bad keys: one line each, status 2, no cube.
check_bad() {  # check_bad NAME EXPECTED_TEXT < TOML
  cat > "$1.toml"
  set +e
  "$exe" sweep "$1.toml" --out "$1.h5" > out.txt 2> err.txt
  local status=$?
  set -e
  [ "$status" -eq 2 ] || fail "$1: exit status $status, expected 2"
  [ "$(wc -l < err.txt)" -eq 1 ] || fail "$1: expected one line, got: $(cat err.txt)"
  grep -qF -- "$2" err.txt || fail "$1: expected '$2' in: $(cat err.txt)"
  [ ! -e "$1.h5" ] && [ ! -e "$1.h5.partial" ] || fail "$1: an output file was left"
}
head_spec='[sweep]
name = "bad"
family = "model-file"
model = "pilot-bridge.toml"
[axes]
scale = [1.0, 2.0]'
check_bad unknown_key "limit_states.rotatoin: unknown key; allowed: unseating, rotation" <<TOML
$head_spec
[limit_states]
rotatoin = {above_rad = 0.01}
TOML
check_bad no_value "limit_states.rotation: must be a table {above_rad = VALUE}" <<TOML
$head_spec
[limit_states]
rotation = 0.01
TOML
check_bad negative "limit_states.seat_displacement.above_m: must be a number >= 0 (m)" <<TOML
$head_spec
[limit_states]
seat_displacement = {above_m = -1}
TOML
check_bad no_seats "limit_states.unseating: needs seat widths" <<TOML
$head_spec
[limit_states]
unseating = true
TOML
check_bad seat_count "limit_states.unseating.seat_m: give one seat width or one per support line (2 for 1 deck" <<TOML
$head_spec
[limit_states]
unseating = {seat_m = [0.5, 0.4, 0.3]}
TOML
check_bad response "limit_states.response.theta_max: unknown response; allowed: x_m_d0" <<TOML
$head_spec
[limit_states]
response = {theta_max = 0.01}
TOML
scaled_head='[sweep]
name = "bad"
family = "model-file"
model = "pilot-bridge.toml"
[axes]
record = "*"
im_g = [0.1, 0.2]
[records]
folder = "rec"
pattern = "*"
scale_to = {measure = "Sa", period = "T1", xi = 0.05}'
check_bad beyond_value 'records.beyond_max_scale: must be "keep" (the cells beyond max_scale enter the fits) or "exclude"' <<TOML
$scaled_head
max_scale = 3.0
beyond_max_scale = "drop"
TOML
check_bad beyond_alone "records.beyond_max_scale: needs records.max_scale" <<TOML
$scaled_head
beyond_max_scale = "exclude"
TOML
check_bad beyond_subset "sweep.responses: records.beyond_max_scale = \"exclude\" needs the response scaled_too_far" <<TOML
$(printf '%s\n' "$scaled_head" | sed 's/^model = .*/&\nresponses = ["x_m_d0"]/')
max_scale = 3.0
beyond_max_scale = "exclude"
TOML
echo "fragility_sweep_test: ok"
