#!/usr/bin/env bash
# Incremental dynamic analysis ([ida]) through `skewbridge sweep`, end to end:
#  1. the two real records of tests/data/records/two-records.toml x two stiffness factors,
#     hunt-and-fill on 1 and 2 ranks: the same cells; check_ida.py compares each record's
#     joint-closing capacity with a brute-force stripe sweep of the same bridge at 0.005 g
#     steps (the first impact is monotone in the scale factor: the motion is linear until
#     it), and the cube's fragility (theta, beta) with numpy's over the capacities;
#  2. a synthetic suite of 40 records on 2 ranks (80 cells) stopped by SIGTERM at a checkpoint
#     with cells done (interrupt_at_checkpoint), then --resume: the cube equals the
#     uninterrupted one and the cells done before the signal are not recomputed;
#  3. bad [ida] input: one line, status 2, no output.
# usage: ida_test.sh SKEWBRIDGE MPIEXEC RECORDS_DIR CHECK_SCRIPT WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec records check work -- "$@"
fresh_dir "$work"

cp "$test_data/models/one-deck-records.toml" deck.toml
cat > ida.toml <<TOML
[sweep]
name = "ida"
family = "model-file"
model = "deck.toml"
[records]
set = "$records/two-records.toml"
scale_to = { measure = "Sa", period = "T1", xi = 0.05 }
[limit_states]
joint_closing = true
rotation = { above_rad = 0.002 }
[ida]
start = 0.1
step = 0.2
step_increase = 0.1
tolerance = 0.01
max_im = 6
max_runs = 30
[axes]
record = "*"
k_factor = [1, 4]
TOML
# The brute force: the same bridge and records at stripes 0.005 g apart.
sed -e '/^\[ida\]/,/^max_runs/d' -e 's/^k_factor = \[1, 4\]/k_factor = [1, 4]\nim_g = {linspace = [0.15, 1.2, 211]}/' \
    -e 's/name = "ida"/name = "brute"/' -e '/^rotation =/d' ida.toml > brute.toml
"$exe" sweep ida.toml --out one.h5 --quiet 2> one.err || { cat one.err; fail "1 rank"; }
on_ranks 2 "$exe" sweep ida.toml --out two.h5 --quiet 2> two.err || { cat two.err; fail "2 ranks"; }
on_ranks 2 "$exe" sweep brute.toml --out brute.h5 --quiet 2> brute.err ||
  { cat brute.err; fail "brute-force stripes"; }
/usr/bin/python3 "$check" one.h5 two.h5 brute.h5
# The report draws the IDA curves and the fragility from the capacities, with theta and beta
# of the cube in its table.
/usr/bin/python3 "$(dirname "$check")/../../scripts/report" two.h5 --out report > report.log 2>&1 ||
  { cat report.log; fail "report"; }
[ -s report/ida_curves_ida.png ] && [ -s report/fragility_ida.png ] || fail "report: no IDA figures"
/usr/bin/python3 - two.h5 report/summary.md <<'PY' || fail "report's table of the IDA fits"
import sys
import h5py
g = h5py.File(sys.argv[1])["sweeps/ida/fragility"]
text = open(sys.argv[2]).read()
for ls in g.attrs["limit_states"]:
    for k, kf in enumerate((1, 4)):
        theta, beta = g[ls]["theta"][k], g[ls]["beta"][k]
        row = f"| {ls} | k_factor = {kf} | 2 | 0 | 0 | {theta:.3g} | {beta:.3g} |"
        assert row in text, (row, text)
PY

# The report names the measure of [records] scale_to on its intensity axes, and draws every
# combination: more than ida.COLUMNS of them (here 1) as one figure per limit state.
mkdir -p multiples
scripts=$(cd "$(dirname "$check")/../../scripts" && pwd)
/usr/bin/python3 - two.h5 "$scripts" <<'PY' || fail "report: IM name or IDA figures"
import os
import sys
sys.path.insert(0, sys.argv[2])
from skewbridge_report import common, data, ida
sweep = data.load_cube(sys.argv[1])[0]
assert common.im_name(sweep) == "Sa(T1, 5 %)", common.im_name(sweep)
ida.COLUMNS = 1
paths = ida.curves(sweep, "multiples", "c", False)
names = [n.decode() if isinstance(n, bytes) else n
         for n in sweep.extra["fragility"]["attrs"]["limit_states"]]
assert [os.path.basename(p) for p in paths] == [f"c_{n}.png" for n in names], paths
assert all(os.path.getsize(p) > 0 for p in paths)
PY
# inspect prints each limit state's fit per k_factor with the cube's theta and beta.
"$exe" inspect two.h5 > inspect.txt || fail "inspect"
/usr/bin/python3 - two.h5 inspect.txt <<'PY' || { cat inspect.txt; fail "inspect's IDA fits"; }
import sys
import h5py
g = h5py.File(sys.argv[1])["sweeps/ida/fragility"]
lines = open(sys.argv[2]).read().splitlines()
for ls in g.attrs["limit_states"]:
    for k, kf in enumerate((1, 4)):
        theta, beta = g[ls]["theta"][k], g[ls]["beta"][k]
        want = [ls, str(kf), "2", "0", "0", f"{theta:.6g}", f"{beta:.6g}"]
        assert any(line.split() == want for line in lines), (want, lines[-8:])
PY

echo "== max_scale: capacities reached beyond it are flagged, counted and censored at it"
sed -e 's/^scale_to = \(.*\)$/scale_to = \1\nmax_scale = 4/' -e 's/name = "ida"/name = "idafar"/' \
    ida.toml > far.toml
grep -q '^max_scale = 4' far.toml || fail "far.toml: no max_scale"
"$exe" sweep far.toml --out far.h5 --quiet 2> far.err || { cat far.err; fail "max_scale sweep"; }
"$exe" inspect far.h5 > far.txt || fail "inspect max_scale"
/usr/bin/python3 - far.h5 far.txt "$(dirname "$check")" <<'PY' || { cat far.txt; fail "max_scale"; }
import sys
import h5py
import numpy as np
sys.path.insert(0, sys.argv[3])
from check_ida import censored_mle
g = h5py.File(sys.argv[1])["sweeps/idafar"]
r, fr = g["responses"], g["fragility"]
order = list(fr.attrs["axis_order"])
assert order == ["k_factor"], order
lines = [line.split() for line in open(sys.argv[2]).read().splitlines()]
flagged = 0
for ls in fr.attrs["limit_states"]:
    cap = r[f"ida_capacity_{ls}"][()]
    below = r[f"ida_capacity_below_{ls}"][()]
    trusted = 4.0 * r["im_unscaled"][()]
    flag = np.isfinite(cap) & (cap > trusted)
    assert np.array_equal(r[f"ida_scaled_too_far_{ls}"][()] == 1, flag), ls
    assert np.allclose(r[f"ida_capacity_scale_{ls}"][()][flag] > 4.0, True)
    flagged += int(flag.sum())
    for k in range(cap.shape[1]):
        c, f = cap[:, k], flag[:, k]
        cens = ~np.isfinite(c) | f
        assert fr[ls]["n_scaled_too_far"][k] == f.sum() and fr[ls]["n_censored"][k] == cens.sum()
        theta, beta = fr[ls]["theta"][k], fr[ls]["beta"][k]
        y = np.log(c[~cens])
        if y.size < 2:
            assert np.isnan(theta) and b"a fit needs 2" in fr[ls]["reason"][k], (ls, k)
        elif not cens.any():
            assert abs(theta - np.exp(y.mean())) <= 1e-12 * theta
        else:
            u = np.log(np.minimum(below[:, k], trusted[:, k])[cens])
            t, b = censored_mle(y, u)
            assert abs(theta - t) <= 1e-6 * t and abs(beta - b) <= 1e-6 * b, (theta, t, beta, b)
        row = [x for x in lines if x[:2] == [ls, str([1, 4][k])]]
        assert row and row[0][4] == str(int(f.sum())), (ls, k, row)
assert flagged >= 1, "max_scale = 4 flags no capacity: the test checks nothing"
print(f"max_scale: {flagged} capacities flagged beyond it")
PY

echo "== beyond_max_scale = exclude: the flagged capacities are left out of the fit, counted"
sed -e 's/^max_scale = 4$/max_scale = 4\nbeyond_max_scale = "exclude"/' \
    -e 's/name = "idafar"/name = "idaout"/' far.toml > out.toml
grep -q '^beyond_max_scale = "exclude"' out.toml || fail "out.toml: no beyond_max_scale"
"$exe" sweep out.toml --out out.h5 --quiet 2> out.err || { cat out.err; fail "exclude sweep"; }
"$exe" inspect out.h5 > out.txt || fail "inspect exclude"
grep -q 'left out of the fit (records.beyond_max_scale = "exclude")' out.txt ||
  { cat out.txt; fail "inspect: no exclusion line"; }
/usr/bin/python3 - out.h5 far.h5 "$(dirname "$check")" <<'PY' || fail "beyond_max_scale = exclude"
import sys
import h5py
import numpy as np
sys.path.insert(0, sys.argv[3])
from check_ida import censored_mle
g = h5py.File(sys.argv[1])["sweeps/idaout"]
keep = h5py.File(sys.argv[2])["sweeps/idafar"]
assert g.attrs["beyond_max_scale"] == "exclude" and keep.attrs["beyond_max_scale"] == "keep"
r, fr = g["responses"], g["fragility"]
left = 0
for ls in fr.attrs["limit_states"]:
    # The same cells as the sweep that keeps them; the fit of those cells without the flagged.
    cap = r[f"ida_capacity_{ls}"][()]
    assert np.array_equal(cap, keep["responses"][f"ida_capacity_{ls}"][()], equal_nan=True)
    below = r[f"ida_capacity_below_{ls}"][()]
    trusted = 4.0 * r["im_unscaled"][()]
    flag = np.isfinite(cap) & (cap > trusted)
    for k in range(cap.shape[1]):
        c, f, b = cap[~flag[:, k], k], flag[:, k], below[~flag[:, k], k]
        t_k = trusted[~flag[:, k], k]
        assert fr[ls]["n_excluded_beyond_max_scale"][k] == f.sum() == fr[ls]["n_scaled_too_far"][k]
        left += int(f.sum())
        cens = ~np.isfinite(c)
        assert fr[ls]["n_records"][k] == (~cens).sum() and fr[ls]["n_censored"][k] == cens.sum()
        theta, beta = fr[ls]["theta"][k], fr[ls]["beta"][k]
        y = np.log(c[~cens])
        if y.size < 2:
            assert np.isnan(theta), (ls, k)
        elif not cens.any():
            assert abs(theta - np.exp(y.mean())) <= 1e-12 * theta
            assert abs(beta - np.std(y, ddof=1)) <= 1e-12 * beta
        else:
            t, bb = censored_mle(y, np.log(np.minimum(b, t_k)[cens]))
            assert abs(theta - t) <= 1e-6 * t and abs(beta - bb) <= 1e-6 * bb, (theta, t, beta, bb)
        if f.any():
            assert b"left out (beyond_max_scale" in fr[ls]["note"][k], fr[ls]["note"][k]
assert left >= 1, "no capacity left out: the test checks nothing"
print(f"beyond_max_scale = exclude: {left} capacities left out, fits as numpy/scipy refit them")
PY

echo "== SIGTERM and --resume"
sed -e 's/^set = .*/synthetic = { count = 40, seed = 7 }/' -e 's/name = "ida"/name = "idakill"/' \
    -e 's/^max_runs = 30/max_runs = 12/' ida.toml > kill.toml
on_ranks 2 "$exe" sweep kill.toml --out ref.h5 --quiet 2> ref.err || { cat ref.err; fail "reference"; }
py() { /usr/bin/python3 -c "import h5py,numpy as np,sys; g=h5py.File(sys.argv[1],'r')['sweeps/idakill']; $2" "$1"; }
"$mpiexec" -n 2 "$exe" sweep kill.toml --out cut.h5 --quiet --checkpoint-cells 1 2> cut.err &
pid=$!
interrupt_at_checkpoint "$pid" cut.h5.partial
set +e; wait "$pid"; status=$?; set -e
[ "$status" != 0 ] || fail "the sweep finished before SIGTERM reached it (status 0)"
[ -f cut.h5.partial ] && [ ! -e cut.h5 ] || fail "SIGTERM left no partial cube (or a final one)"
before=$(py cut.h5.partial "print(int(g['done'][()].sum()))")
on_ranks 2 "$exe" sweep kill.toml --out cut.h5 --quiet --resume 2> resume.err ||
  { cat resume.err; fail "--resume"; }
/usr/bin/python3 - ref.h5 cut.h5 "$before" <<'PY'
import sys
import h5py
import numpy as np
ref, cut, before = h5py.File(sys.argv[1])["sweeps/idakill"], h5py.File(sys.argv[2])["sweeps/idakill"], int(sys.argv[3])
for name in ref["responses"]:
    assert np.array_equal(ref["responses"][name][()], cut["responses"][name][()], equal_nan=True), name
for ls in ref["fragility"].attrs["limit_states"]:
    for k in ("theta", "beta", "n_records", "n_censored"):
        assert np.array_equal(ref["fragility"][ls][k][()], cut["fragility"][ls][k][()], equal_nan=True), (ls, k)
runs = cut["stats/run"][()]
assert np.all(cut["status"][()] == 0) and np.all(cut["done"][()] == 1)
kept = int((runs == 1).sum())
assert 0 < before < runs.size, (before, runs.size)
assert kept == before and int((runs == 2).sum()) == runs.size - before, (kept, before)
print(f"resume: equal to the uninterrupted cube; {before} of {runs.size} cells done before SIGTERM, {kept} of them from run 1")
PY

echo "== bad input"
bad() {
  local edit=$1 pattern=$2
  sed "$edit" ida.toml > bad.toml
  set +e; err=$("$exe" sweep bad.toml --out bad.h5 2>&1); status=$?; set -e
  [ "$status" = 2 ] || fail "$edit: status $status ($err)"
  [ "$(printf '%s\n' "$err" | wc -l)" = 1 ] || fail "$edit: not one line: $err"
  printf '%s\n' "$err" | grep -q "$pattern" || fail "$edit: '$err' lacks '$pattern'"
  [ ! -e bad.h5 ] && [ ! -e bad.h5.partial ] || fail "$edit: output left"
}
bad 's/^tolerance = 0.01/tolerence = 0.01/' "^skewbridge: error: bad.toml:15: ida.tolerence: unknown key; allowed: start, step, step_increase, tolerance, max_im, max_runs; did you mean .tolerance.?$"
bad 's/^max_runs = 30/max_runs = 1/' "bad.toml:17: ida.max_runs: must be a whole number of runs from 2 to 200"
bad 's/^step = 0.2/step = -0.2/' "ida.step: must be a number > 0 (g, or m/s for PGV)"
bad 's/^max_im = 6/max_im = 0.05/' "ida.max_im: must exceed ida.start"
bad 's/^k_factor = \[1, 4\]/k_factor = [1, 4]\nim_g = [0.5]/' "im_g: not with \[ida\]: the hunt-and-fill search chooses each record's intensities"
bad '/^scale_to/d' "ida: needs \[records\] scale_to"
bad '/^joint_closing/d; /^rotation/d' "ida: needs \[limit_states\]"
echo "ida_test: ok"
