#!/usr/bin/env bash
# The correlation-set pipeline end to end: a 6-record synthetic suite made by the sweep itself
# ([records] synthetic), Pi_delta = 0.5, 1, 2, on 2 ranks through `skewbridge sweep`; then
# check_study_cube.py compares the stored record table, L_e, delta, band and statistics with
# numpy/scipy computed from the stored columns. (Resume: tests/study/study_test.cpp.)
# usage: study_pipeline_test.sh SKEWBRIDGE MPIEXEC CHECK_SCRIPT WORK_DIR
set -euo pipefail
exe=$1 mpiexec=$2 check=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "study_pipeline_test: FAIL: $*" >&2; exit 1; }

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

"$mpiexec" -n 2 --oversubscribe "$exe" sweep study6.toml --out study6.h5 --quiet \
  || fail "the sweep failed"
/usr/bin/python3 "$check" study6.h5 study6 || fail "study6.h5 does not check"

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
