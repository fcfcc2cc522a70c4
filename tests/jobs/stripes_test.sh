#!/usr/bin/env bash
# Records scaled to stripes through `skewbridge sweep` on 1 and 2 ranks: the two real records
# of tests/data/records/two-records.toml scaled to Sa(T1) stripes of a one-deck model file at
# two stiffness factors (so two T1), with a max_scale that some cells exceed. check_stripes.py
# checks the cube with h5py against scipy (T1 in closed form, Sa by scipy.signal.lsim); the
# summary line names the cells scaled too far; both cubes hold the same cells. The dry run's
# table of scale factors is checked against the 2-rank cube and `records spectrum`
# (check_dry_run_scales.py).
# usage: stripes_test.sh SKEWBRIDGE MPIEXEC RECORDS_DIR CHECK_SCRIPT WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec records check work -- "$@"
fresh_dir "$work"

cp "$test_data/models/one-deck-records.toml" deck.toml
cat > spec.toml <<TOML
[sweep]
name = "stripes"
family = "model-file"
model = "deck.toml"
[records]
set = "$records/two-records.toml"
scale_to = { measure = "Sa", period = "T1", xi = 0.05 }
max_scale = 1.5
[axes]
record = "*"
im_g = [0.2, 0.6, 1.2]
k_factor = [1, 4]
TOML
"$exe" sweep spec.toml --out one.h5 --quiet 2> one.err || { cat one.err; fail "1 rank"; }
grep -q "^sweep: [0-9]* of 12 cells scaled beyond max_scale = 1.5 (largest factor" one.err ||
  { cat one.err; fail "no max_scale line in the summary"; }
on_ranks 2 "$exe" sweep spec.toml --out two.h5 --quiet 2> two.err || { cat two.err; fail "2 ranks"; }
/usr/bin/python3 "$check" one.h5 two.h5 "$records" "$(grep -o '^sweep: [0-9]*' one.err | cut -d' ' -f2)"

# inspect prints the cube's inputs table: each file's role, size and SHA-256 as the cube's
# inputs/ stores them (h5py), equal to the files' own (os.path.getsize, hashlib).
"$exe" inspect one.h5 > inspect.txt || fail "inspect"
/usr/bin/python3 - one.h5 inspect.txt <<'PY' || { cat inspect.txt; fail "inspect: the inputs"; }
import hashlib
import sys
import h5py
g = h5py.File(sys.argv[1], "r")["sweeps/stripes/inputs"]
rows = [line.split() for line in open(sys.argv[2]).read().splitlines()]
roles = []
for role, name, sha, n in zip(g["role"][()], g["file"][()], g["sha256"][()], g["bytes"][()]):
    role, name, sha = role.decode(), name.decode(), sha.decode()
    data = open(name, "rb").read()  # relative to the spec's folder, which is here
    assert sha == hashlib.sha256(data).hexdigest() and n == len(data), name
    assert [role, str(n), sha, name] in rows, (role, name)
    roles.append(role)
assert sorted(roles) == ["model", "record", "record", "record-set", "spec"], roles
PY

# The dry run's record x stripe table of scale factors against the 2-rank cube and against
# `records spectrum` at both T1 = 2 pi / (10 sqrt(k_factor)) s.
"$exe" sweep --dry-run spec.toml > dry.txt || fail "dry run"
"$exe" records spectrum "$records/two-records.toml" --xi 0.05 \
  --periods "$(/usr/bin/python3 -c 'import math; print(repr(2*math.pi/10), repr(2*math.pi/20), sep=",")')" \
  > spectrum.csv || fail "records spectrum"
/usr/bin/python3 "$(dirname "$check")/check_dry_run_scales.py" dry.txt two.h5 spectrum.csv ||
  { cat dry.txt; fail "dry run's scale factors"; }

# A set file here naming its records by absolute paths: the dry run's record table and the
# cube's records/file give each record's file relative to the set's folder (os.path.relpath),
# under a header that says so.
mkdir -p sets
printf 'name = "abs"\n[[record]]\nfile = "%s"\n[[record]]\nfile = "%s"\n' \
  "$records/NIS090.AT2" "$records/RSN763_LOMAP_GIL067.AT2" > sets/abs.toml
sed -e 's|^set = .*|set = "sets/abs.toml"|' -e 's/^name = "stripes"/name = "abs"/' \
  spec.toml > abs.toml
"$exe" sweep --dry-run abs.toml > absdry.txt || fail "dry run of a set of absolute paths"
grep -q "  file (from the set's folder)$" absdry.txt ||
  { cat absdry.txt; fail "dry run: the file column's header"; }
"$exe" sweep abs.toml --out abs.h5 --quiet 2> abs.err || { cat abs.err; fail "sweep abs.toml"; }
for f in NIS090.AT2 RSN763_LOMAP_GIL067.AT2; do
  rel=$(/usr/bin/python3 -c 'import os, sys; print(os.path.relpath(*sys.argv[1:]))' \
    "$records/$f" "$(pwd -P)/sets")
  awk -v f="$f" -v r="$rel" '$1 == f && $NF == r { n++ } END { exit n != 1 }' absdry.txt ||
    { cat absdry.txt; fail "dry run: $f is not shown as $rel"; }
  /usr/bin/python3 - "$f" "$rel" <<'PY' || fail "cube: $f is not stored as $rel"
import sys
import h5py
g = h5py.File("abs.h5", "r")["sweeps/abs/records"]
files = dict(zip((x.decode() for x in g["label"][()]), (x.decode() for x in g["file"][()])))
assert files[sys.argv[1]] == sys.argv[2], files
PY
done

# Bad keys: one line, status 2, no output.
bad() {
  local edit=$1 pattern=$2
  sed "$edit" spec.toml > bad.toml
  set +e; err=$("$exe" sweep bad.toml --out bad.h5 2>&1); status=$?; set -e
  [ "$status" = 2 ] || fail "$edit: status $status"
  [ "$(printf '%s\n' "$err" | wc -l)" = 1 ] || fail "$edit: not one line: $err"
  printf '%s\n' "$err" | grep -q "$pattern" || fail "$edit: '$err' lacks '$pattern'"
  [ ! -e bad.h5 ] && [ ! -e bad.h5.partial ] || fail "$edit: output left"
}
bad 's/measure = "Sa"/measure = "SA"/' "^skewbridge: error: bad.toml:7: records.scale_to.measure: unknown measure 'SA'"
bad 's/period = "T1"/period = -0.5/' "records.scale_to.period: must be a period > 0 s"
bad '/^im_g/d' "axes.im_g: missing: records.scale_to needs an intensity axis"
bad 's/^max_scale = 1.5/max_scale = -1/' "records.max_scale: must be a number > 0"
echo "stripes_test: ok"
