#!/usr/bin/env bash
# scripts/report end to end: four small cubes from `skewbridge sweep` on 2 ranks (subsystem
# spectra over skew angles, a Pi_delta family, rotation against eta0, the pilot bridge over an
# 8-record synthetic suite; 24-48 cells each) and two run files (separate impacts; impacts
# ending in persistent contact, tests/report/push.toml); check_report.py then checks the
# figures, tables and statistics; bad inputs must exit with status 2 and one line.
# usage: report_test.sh SKEWBRIDGE MPIEXEC SOURCE_ROOT WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec root work -- "$@"
fresh_dir "$work"
sweep() { on_ranks 2 "$exe" sweep "$@" --quiet; }
report="$root/scripts/report"

cat > spectra.toml <<'TOML'
[sweep]
name = "spectra"
family = "subsystem"
[axes]
pulse = ["cosine", "sine"]
a_deg = [20, 50]
w0_over_wg = {logspace = [0.3, 3.0, 12]}
[fixed]
eta0 = 2.0
TOML
cat > pidelta.toml <<'TOML'
[sweep]
name = "pidelta"
family = "subsystem"
[axes]
Pi_delta = [0.5, 2.0]
w0_over_wg = {logspace = [0.3, 3.0, 12]}
[fixed]
pulse = "cosine"
a_deg = 20.0
eta0 = 1.48
TOML
cat > eta0.toml <<'TOML'
[sweep]
name = "eta0"
family = "subsystem"
[axes]
eta0 = [0.5, 1.5, 3.0]
W0_over_w0 = [1.0, 2.0]
w0_over_wg = {logspace = [0.3, 3.0, 6]}
[fixed]
pulse = "cosine"
a_deg = 30.0
TOML
cat > many.toml <<'TOML'
[sweep]
name = "many"
family = "subsystem"
[axes]
a_deg = [5, 10, 15, 20, 25, 30, 35, 40, 45, 50, 55, 60]
w0_over_wg = {logspace = [0.3, 3.0, 4]}
[fixed]
pulse = "cosine"
eta0 = 2.0
TOML
"$exe" records synth --count 8 --seed 7 --duration-s 10 --out set >/dev/null
cat > records.toml <<'TOML'
[sweep]
name = "records"
family = "pilot-bridge"
[records]
set = "set/set.toml"
[axes]
record = ["synth-7-000", "synth-7-001", "synth-7-002", "synth-7-003", "synth-7-004",
          "synth-7-005", "synth-7-006", "synth-7-007"]
Pi_delta = [0.5, 1.0, 2.0]
TOML
for s in spectra pidelta eta0 records many; do sweep $s.toml --out $s.h5; done
"$exe" run "$root/docs/examples/subsystem.toml" --out run.h5 >/dev/null
"$exe" run "$root/tests/report/push.toml" --out push.h5 >/dev/null

"$report" spectra.h5 pidelta.h5 eta0.h5 records.h5 --run run.h5 --run push.h5 --out out --pdf \
  >report.log ||
  fail "report exited with status $? ($(cat report.log))"
/usr/bin/python3 "$root/tests/report/check_report.py" out report.log spectra.h5 pidelta.h5 \
  eta0.h5 records.h5 run.h5 push.h5 || fail "figures or tables"

# xarray's h5netcdf engine opens every sweep, coordinates and units included.
/usr/bin/python3 "$root/tests/report/check_xarray.py" spectra.h5 records.h5 eta0.h5 ||
  fail "xarray"

# Readability, checked on the figures themselves: legends, log ticks, symbols, captions, a
# colour bar for 12 curves, "no data" on the empty column of a cube whose sine cells are not
# done, gamma_T against finite differences.
cp spectra.h5 holes.h5
/usr/bin/python3 -c "import h5py; g = h5py.File('holes.h5', 'r+')['sweeps/spectra']; g.attrs['complete'] = 0; d = g['done'][()]; d[1] = 0; g['done'][...] = d"
/usr/bin/python3 "$root/tests/report/check_readability.py" "$root" readable spectra.h5 pidelta.h5 \
  eta0.h5 records.h5 many.h5 holes.h5 --run run.h5 --run push.h5 || fail "readability"

# expect_error NAME PATTERN ARGS...: exit status 2, one line on stderr matching PATTERN,
# no output folder made.
expect_error() {
  local name=$1 pattern=$2; shift 2
  set +e
  "$report" "$@" --out "bad-$name" >/dev/null 2>"err-$name"
  local status=$?
  set -e
  [ $status -eq 2 ] || fail "$name: exit status $status, expected 2"
  [ "$(wc -l <"err-$name")" -eq 1 ] || fail "$name: not one line: $(cat "err-$name")"
  grep -q -- "$pattern" "err-$name" || fail "$name: '$(cat "err-$name")' lacks '$pattern'"
  [ ! -e "bad-$name" ] || fail "$name: output folder made"
}
echo "not hdf5" >text.h5
/usr/bin/python3 -c "import h5py; h5py.File('foreign.h5', 'w').attrs['format'] = 'other'"
cp spectra.h5 partial.h5
/usr/bin/python3 -c "import h5py; h5py.File('partial.h5', 'r+')['sweeps/spectra'].attrs['complete'] = 0"
expect_error missing "missing.h5: no such file" missing.h5
expect_error text "text.h5: not an HDF5 file" text.h5
expect_error foreign "foreign.h5: not a skewbridge cube" foreign.h5
expect_error partial "partial.h5: sweep 'spectra' is incomplete" partial.h5
expect_error run-as-cube "run.h5: is a skewbridge run file" run.h5
expect_error cube-as-run "spectra.h5: is a skewbridge cube" --run spectra.h5
"$report" partial.h5 --allow-partial --out partial-out >/dev/null ||
  fail "--allow-partial refused an incomplete cube"
[ -s partial-out/spectra_spectra.png ] || fail "--allow-partial wrote no spectra"
echo "report_test: ok"
