#!/usr/bin/env bash
# The incidence angle through `skewbridge sweep`: a model-file sweep of the two real records with
# incidence_deg = 30 gives every dataset of the same sweep on the model file written with
# excitation.angle_deg = 30, byte for byte (docs/theory.md §2: one rounding of the angle); a
# pilot-bridge sweep with incidence_deg = 0 is the sweep without it, byte for byte, and one at
# 90 deg moves the responses; the subsystem refuses the key with one line, exit 2, no cube.
# usage: incidence_test.sh SKEWBRIDGE MPIEXEC RECORDS_DIR CHECK_PY WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec records check work -- "$@"
fresh_dir "$work"
cp "$test_data/models/one-deck-records.toml" deck.toml
sed 's/^T_g = 0.6$/T_g = 0.6\nangle_deg = 30.0/' deck.toml > deck30.toml
grep -q '^angle_deg = 30.0$' deck30.toml || fail "deck30.toml: no angle_deg line written"

# sweep NAME MODEL FIXED_LINES: the two records at two scales on a model file.
records_sweep() {
  printf '[sweep]\nname = "inc"\nfamily = "model-file"\nmodel = "%s"\n[records]\nset = "%s"\n[axes]\nrecord = "*"\nscale = [0.5, 1.5]\n%b' \
    "$2" "$records/two-records.toml" "$3" > "$1.toml"
  on_ranks 2 "$exe" sweep "$1.toml" --out "$1.h5" --quiet 2> "$1.err" || {
    cat "$1.err" >&2
    fail "$1: the sweep failed"
  }
}
records_sweep turned deck.toml '[fixed]\nincidence_deg = 30.0\n'
records_sweep file30 deck30.toml ''
/usr/bin/python3 "$check" same turned.h5 file30.h5 || fail "incidence_deg = 30 differs from angle_deg = 30"

# sweep NAME FIXED_LINES: the pilot bridge under a sine pulse at two gaps.
pilot_sweep() {
  printf '[sweep]\nname = "inc"\nfamily = "pilot-bridge"\n[axes]\nPi_delta = [0.05, 0.5]\n[fixed]\npulse = "sine"\n%b' \
    "$2" > "$1.toml"
  on_ranks 1 "$exe" sweep "$1.toml" --out "$1.h5" --quiet 2> "$1.err" || {
    cat "$1.err" >&2
    fail "$1: the sweep failed"
  }
}
pilot_sweep along-x ''
pilot_sweep zero 'incidence_deg = 0.0\n'
pilot_sweep across 'incidence_deg = 90.0\n'
/usr/bin/python3 "$check" same zero.h5 along-x.h5 || fail "incidence_deg = 0 differs from no incidence"
/usr/bin/python3 "$check" moved across.h5 along-x.h5 || fail "incidence_deg = 90 moved nothing"

# A pair drives both columns: the pilot bridge under the pairs of tests/data/records/pairs and
# under a set naming only their H1 files, at incidence 0: the single record's cells are the same
# bytes, the pairs' transverse responses differ (H2 acts along y).
pairs="$records/pairs"
printf 'name = "h1"\n[[record]]\nlabel = "RSN107"\nfile = "%s/RSN107_OROVILLE_B-OAP180.AT2"\n[[record]]\nfile = "%s/../NIS090.AT2"\n' \
  "$pairs" "$pairs" > h1.toml
for set in "$pairs/pairs.toml" h1.toml; do
  name=$(basename "$set" .toml)
  printf '[sweep]\nname = "inc"\nfamily = "pilot-bridge"\n[records]\nset = "%s"\n[axes]\nrecord = ["RSN107", "NIS090.AT2"]\nPi_delta = [0.5]\n[fixed]\nincidence_deg = 0.0\n' \
    "$set" > "p-$name.toml"
  on_ranks 1 "$exe" sweep "p-$name.toml" --out "p-$name.h5" --quiet 2> "p-$name.err" || {
    cat "p-$name.err" >&2
    fail "p-$name: the sweep failed"
  }
done
/usr/bin/python3 - p-pairs.h5 p-h1.h5 <<'PY' || fail "pairs: H2 not applied, or the single record moved"
import sys
import h5py
import numpy as np
a, b = (h5py.File(p, "r")["sweeps/inc"] for p in sys.argv[1:3])
labels = [x.decode() if isinstance(x, bytes) else x for x in a["axes/record"][()]]
i, j = labels.index("RSN107"), labels.index("NIS090.AT2")
ya, yb = a["y_m"][()], b["y_m"][()]
assert ya[i].tobytes() != yb[i].tobytes(), "the pair's y_m is H1's alone"
assert ya[j].tobytes() == yb[j].tobytes(), "the single record's y_m moved"
assert a["x_m"][()][j].tobytes() == b["x_m"][()][j].tobytes()
PY

# The subsystem's dimensionless pulse has one component along x: refused in one line.
printf '[sweep]\nname = "inc"\nfamily = "subsystem"\n[axes]\nincidence_deg = [0, 90]\n' > sub.toml
status=0
"$exe" sweep sub.toml --out sub.h5 > sub.log 2>&1 || status=$?
[ "$status" -eq 2 ] || fail "subsystem: exit status $status, not 2"
[ "$(wc -l < sub.log)" -eq 1 ] || fail "subsystem: not one line: $(cat sub.log)"
grep -q 'incidence_deg' sub.log || fail "subsystem: the line does not name the key: $(cat sub.log)"
[ ! -e sub.h5 ] || fail "subsystem: a cube was written"
echo "incidence_test: ok"
