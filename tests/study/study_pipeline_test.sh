#!/usr/bin/env bash
# The correlation-set pipeline end to end: a 6-record synthetic suite made by the sweep itself
# ([records] synthetic), Pi_delta = 0.5, 1, 2, on 2 ranks through `skewbridge sweep`; then
# check_study_cube.py compares the stored record table, L_e, delta, band and statistics with
# numpy/scipy computed from the stored columns; `skewbridge inspect` prints the record table size
# and the statistics per Pi_delta equal to h5py's values, and on a multi-span cube prints no
# record section. (Resume: tests/study/study_test.cpp.)
# usage: study_pipeline_test.sh SKEWBRIDGE MPIEXEC CHECK_SCRIPT WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec check work -- "$@"
fresh_dir "$work"

cat > study6.toml <<'TOML'
[sweep]
name = "study6"
family = "pilot-bridge"
[records]
synthetic = {count = 6, seed = 2011}
[study]
bands = [0.5, 1.0, 2.0]
[axes]
record = ["synth-2011-000", "synth-2011-001", "synth-2011-002", "synth-2011-003",
          "synth-2011-004", "synth-2011-005"]
Pi_delta = [0.5, 1.0, 2.0]
TOML

on_ranks 2 "$exe" sweep study6.toml --out study6.h5 --quiet \
  || fail "the sweep failed"
/usr/bin/python3 "$check" study6.h5 study6 || fail "study6.h5 does not check"

"$exe" inspect study6.h5 > inspect.txt || fail "inspect study6.h5: exit status $?"
/usr/bin/python3 - study6.h5 inspect.txt <<'PY' || fail "inspect statistics differ from h5py's"
import math, re, sys, h5py
g = h5py.File(sys.argv[1], "r")["sweeps/study6"]
text = open(sys.argv[2], encoding="utf-8").read()
m = re.search(r"record table: (\d+) record", text)
assert m and int(m.group(1)) == len(g["records/label"]), "record table size: %r" % (m and m.group(0))
c = g["correlation"]
pi = list(g["axes/Pi_delta"][()])
assert "correlation of theta_m with L_e" in text, "no statistics section"
table = text.split("correlation of theta_m with L_e", 1)[1]
rows = re.findall(r"^ {4}(\S+) +(\S+) +(\S+) +(\S+) +(\S+) +(\S+) +(\S+) +(\S+)$", table, re.M)
rows = [r for r in rows if r[0] != "Pi_delta"]
assert "per Pi_delta" in text and len(rows) == len(pi), "%d statistics rows for %d Pi_delta" % (len(rows), len(pi))
names = ["n", "pearson_theta_Le", "spearman_theta_Le", "loglog_n", "loglog_slope",
         "loglog_intercept", "loglog_r2"]
for k, row in enumerate(rows):
    assert float(row[0]) == pi[k], "row %d is Pi_delta %s, expected %g" % (k, row[0], pi[k])
    for name, printed in zip(names, row[1:]):
        stored, shown = float(c[name][k]), float(printed)
        same = (math.isnan(stored) and math.isnan(shown)) or abs(shown - stored) <= 5e-6 * abs(stored) + 1e-12
        assert same, "Pi_delta %g %s: printed %s, stored %r" % (pi[k], name, printed, stored)
print("inspect agrees with h5py on %d Pi_delta rows" % len(rows))
PY

# A multi-span cube has no record axis: inspect summarises it and prints no record section.
cat > ms.toml <<'TOML'
[sweep]
name = "ms"
family = "multi-span"
[axes]
spans = [1, 2]
[fixed]
a_deg = 30
w0_over_wg = 1.0
W_over_L = 0.3
Pi_delta = 1.0
delta_over_L = 0.002
mu = 0.1
seat_over_L = 0.02
TOML
on_ranks 2 "$exe" sweep ms.toml --out ms.h5 --quiet || fail "multi-span sweep"
"$exe" inspect ms.h5 > ms_inspect.txt || fail "inspect ms.h5: exit status $?"
grep -q "sweep ms (family multi-span" ms_inspect.txt || fail "inspect ms.h5: no sweep line"
grep -q "completion: 2/2 cells done (100.0%), complete" ms_inspect.txt ||
  fail "inspect ms.h5: completion: $(cat ms_inspect.txt)"
! grep -Eq "record table|correlation of" ms_inspect.txt || fail "inspect ms.h5: a record section"

# A bad [study] key stops the command with status 2 and one line naming it, before any file.
sed 's/bands = \[0.5, 1.0, 2.0\]/bands = [1.0, 0.5]/' study6.toml > bad.toml
set +e
msg=$("$exe" sweep bad.toml --out bad.h5 2>&1)
status=$?
set -e
[[ $status -eq 2 ]] || fail "bad bands: exit status $status, not 2"
[[ $(printf '%s\n' "$msg" | wc -l) -eq 1 ]] || fail "bad bands: more than one line: $msg"
[[ $msg == *"bad.toml:"*"study.bands: must be a list of increasing"* ]] || fail "bad bands: $msg"
[[ ! -e bad.h5 && ! -e bad.h5.partial ]] || fail "bad bands: an output file was written"
echo "study_pipeline_test: ok"
