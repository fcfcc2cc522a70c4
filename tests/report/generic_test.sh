#!/usr/bin/env bash
# Every sweep of one's own bridge is seen: three real sweeps on 2 ranks (a model-file sweep of
# the pilot bridge's model file over the skew angle and the pulse period, the README's
# three-span example, a model-file sweep over 6 synthetic records and Pi_delta) go through
# scripts/report, whose figures and tables check_generic.py checks against the cubes read by
# h5py; `skewbridge inspect` must print the specification's fixed values with their units and
# a limit-state sweep's exceedances and fragility fits as the cube holds them;
# `skewbridge sweep --dry-run` must count the cells, time a sample and write no file.
# usage: generic_test.sh SKEWBRIDGE MPIEXEC SOURCE_ROOT WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec root work -- "$@"
fresh_dir "$work"
sweep() { on_ranks 2 "$exe" sweep "$@" --quiet; }
report="$root/scripts/report"

cat > own.toml <<TOML
[sweep]
name = "own"
family = "model-file"
model = "$root/docs/examples/pilot-bridge.toml"
[axes]
a_deg = [10, 20, 30, 40]
T_g = [0.3, 0.5, 0.8, 1.2, 2.0]
[fixed]
pulse = "cosine"
a_g_g = 0.4
seat_over_L = 0.01
TOML
cat > rec.toml <<TOML
[sweep]
name = "rec"
family = "model-file"
model = "$root/docs/examples/pilot-bridge.toml"
[records]
synthetic = {count = 6, seed = 5}
[axes]
record = "*"
Pi_delta = [0.5, 1.0, 2.0]
[fixed]
a_deg = 30.0
TOML

# --dry-run: the cell count is the product of the axis lengths, the estimate names the rank
# count and how it is made, and no file is written (not even with --out).
before=$(ls -A)
"$exe" sweep --dry-run own.toml --ranks 4 --out dry.h5 >../dry.txt || fail "--dry-run exit status $?"
mv ../dry.txt .
[ "$(ls -A | grep -v '^dry.txt$')" = "$before" ] || fail "--dry-run wrote files: $(ls -A)"
grep -q '^cells: 20 = T_g 5 x a_deg 4$' dry.txt || fail "dry run cell count: $(head -3 dry.txt)"
grep -q '^estimate on 4 rank(s): ' dry.txt || fail "dry run estimate: $(cat dry.txt)"
grep -q 'computing rank(s)' dry.txt || fail "dry run does not say how it estimates"
[ "$(grep -c '^  cell ' dry.txt)" -eq 8 ] || fail "dry run did not time 8 cells"
on_ranks 2 "$exe" sweep --dry-run "$root/jobs/specs/model-file-three-span.toml" \
  >dry3.txt || fail "--dry-run on 2 ranks"
grep -q '^cells: 72 = pulse 2 x a_deg 4 x Pi_delta 3 x k_factor 3$' dry3.txt ||
  fail "three-span dry run: $(head -2 dry3.txt)"
grep -q '^estimate on 2 rank(s)' dry3.txt || fail "the dry run under mpiexec -n 2 estimates for 2 ranks"
"$exe" sweep --dry-run rec.toml --sample-cells 3 >dryrec.txt || fail "record dry run"
grep -q '^cells: 18 = record 6 x Pi_delta 3$' dryrec.txt || fail "record dry run: $(head -2 dryrec.txt)"
grep -q '^records: 6 from synthetic count=6 seed=5$' dryrec.txt || fail "dry run records"
[ "$(grep -c '^  synth-5-00' dryrec.txt)" -eq 6 ] || fail "dry run does not list the 6 records"
set +e
"$exe" sweep own.toml >/dev/null 2>noout.txt
status=$?
set -e
[ $status -ne 0 ] && grep -q -- "--out" noout.txt || fail "a real run without --out: status $status"

sweep own.toml --out own.h5
sweep "$root/jobs/specs/model-file-three-span.toml" --out three.h5
sweep rec.toml --out rec.h5

# inspect: each fixed value of the specification with its unit.
"$exe" inspect own.h5 >inspect.txt
grep -Eq '^    pulse +cosine ' inspect.txt || fail "inspect: pulse: $(cat inspect.txt)"
grep -Eq '^    a_g_g +0\.4 g ' inspect.txt || fail "inspect: a_g_g with its unit"
grep -Eq '^    seat_over_L +0\.01 ' inspect.txt || fail "inspect: seat_over_L"
grep -Eq '^    a_deg +4  10 \.\. 40 \[deg\]' inspect.txt || fail "inspect: the a_deg axis"
grep -q '^  limit states: none declared$' inspect.txt || fail "inspect: limit states line"
"$exe" inspect three.h5 | grep -Eq '^    seat_over_L +0\.02 ' || fail "inspect three-span"

# inspect on a sweep with limit states: the exceedances, the largest demands and the fitted
# medians and betas it prints equal the cube's (h5py).
cat > ls.toml <<TOML
[sweep]
name = "ls"
family = "model-file"
model = "$root/docs/examples/pilot-bridge.toml"
[records]
synthetic = {count = 6, seed = 5}
[axes]
record = "*"
scale = {logspace = [0.25, 6.0, 4]}
a_deg = [20, 40]
[fixed]
gap_m = 0.02
[limit_states]
rotation = {above_rad = 0.0005}
joint_closing = true
TOML
sweep ls.toml --out ls.h5
"$exe" inspect ls.h5 >inspect-ls.txt
/usr/bin/python3 - ls.h5 inspect-ls.txt <<'PY' || fail "inspect's limit states differ from the cube"
import re, sys, h5py, numpy as np
g = h5py.File(sys.argv[1], "r")["sweeps/ls"]
text = open(sys.argv[2], encoding="utf-8").read()
for name in ("rotation", "joint_closing"):
    e = g["responses/ls_" + name][()]
    d = g["responses/ls_" + name + "_demand"][()]
    m = re.search(r"^    %s +exceeded in (\d+) of (\d+) cells; demand up to (\S+)" % name, text, re.M)
    assert m, (name, text)
    assert int(m.group(1)) == int((e == 1).sum()) and int(m.group(2)) == int(np.isfinite(e).sum()), m.groups()
    assert float(m.group(3)) == float("%.6g" % np.nanmax(d)), (m.group(3), np.nanmax(d))
    f = g["fragility/" + name]
    for k, a in enumerate(g["axes/a_deg"][()]):
        row = re.search(r"^    %s +%g +(\d+) +(\d+) +(.*)$" % (name, a), text, re.M)
        assert row, (name, a)
        assert int(row.group(1)) == f["n_cells"][k] and int(row.group(2)) == f["n_exceeded"][k]
        if np.isfinite(f["theta"][k]):
            theta, beta = (float(v) for v in row.group(3).split()[:2])
            assert theta == float("%.6g" % f["theta"][k]) and beta == float("%.6g" % f["beta"][k])
        else:
            reason = f["reason"][k].decode()
            assert reason and row.group(3) == "no fit: " + reason, (row.group(3), reason)
print("inspect: limit states and fragility fits agree with the cube")
PY

# A fragility panel without fits names each combination's own reason, once when they share it.
/usr/bin/python3 - "$root/scripts" <<'PY' || fail "the no-fit text of a fragility panel"
import sys
sys.path.insert(0, sys.argv[1])
from skewbridge_report.fragility import _no_fit_text
same = _no_fit_text([("20 mm", "exceeded in all 228 cells: the median lies below"),
                     ("40 mm", "exceeded in all 228 cells: the median lies below")], 2)
assert same == "no fit for 2 of 2:\nexceeded in all 228 cells", same
own = _no_fit_text([("20 mm", "exceeded in all 228 cells: the median lies below"),
                    ("40 mm", "the stripes separate at IM = 1.2 (10 of 19 exceeded there)")], 2)
assert own == ("no fit for 2 of 2:\n20 mm: exceeded in all 228 cells\n"
               "40 mm: the stripes separate at IM = 1.2"), own
PY

"$report" own.h5 three.h5 rec.h5 --out out >report.log || fail "report exited with $?"
/usr/bin/python3 "$root/tests/report/check_generic.py" out report.log own.h5 three.h5 rec.h5 ||
  fail "figures or tables"
/usr/bin/python3 "$root/tests/report/check_readability.py" "$root" readable own.h5 three.h5 \
  rec.h5 || fail "readability"
echo "generic_test: ok"
