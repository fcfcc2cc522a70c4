#!/usr/bin/env bash
# `skewbridge run --out`: the HDF5 file has the layout of docs/run-output.md and agrees with the
# CSV text and the printed summary (run_h5_check.py), with the root attributes method and
# time_step_s naming the integrator of run.method (event-driven: NaN step; time-stepping: the
# model's run.time_step_s) and the policy of that integrator stored (event_policy or
# time_stepping_policy); histories only when requested; a bad model
# or an unwritable path leaves neither FILE.h5 nor FILE.h5.partial.
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe root -- "$@"
python=/usr/bin/python3
temp_dir
model="$root/docs/examples/subsystem.toml"

"$exe" run "$model" --out "$work/X.h5" --csv "$work/X.csv" >"$work/summary" 2>"$work/err" ||
  fail "good model: exit status $? ($(cat "$work/err"))"
[ ! -e "$work/X.h5.partial" ] || fail "good model: temporary file left behind"
"$python" "$root/tests/app/run_h5_check.py" "$work/X.h5" "$work/X.csv" "$model" "$work/summary" ||
  fail "layout or values"

cp "$model" "$work/ts.toml"
# [run] is the file's last table: the keys appended here belong to it.
printf 'method = "time-stepping"\ntime_step_s = 2e-4\n' >>"$work/ts.toml"
"$exe" run "$work/ts.toml" --out "$work/T.h5" --csv "$work/T.csv" >"$work/tsummary" 2>"$work/err" ||
  fail "time-stepping model: exit status $? ($(cat "$work/err"))"
"$python" "$root/tests/app/run_h5_check.py" "$work/T.h5" "$work/T.csv" "$work/ts.toml" \
  "$work/tsummary" time-stepping 2e-4 || fail "time-stepping run file: layout or values"
"$python" - "$work/T.h5" <<'PY' || fail "time-stepping run file: its policy"
import sys, h5py
f = h5py.File(sys.argv[1], "r")
assert "event_policy" not in f, "a time-stepping run file stores the event-driven policy"
pol = f["time_stepping_policy"].attrs
keys = [k.decode() if isinstance(k, bytes) else str(k) for k in pol["keys"]]
assert keys == ["velocity_tolerance", "free_body_omega_floor_radps", "free_body_omega_radps",
                "ramp_horizon_s", "active_set_lookahead", "normal_compliance", "step_count_band",
                "output_time_band"], keys
assert pol["velocity_tolerance"] == 1e-9 and pol["active_set_lookahead"] == 0.5, dict(pol)
PY

sed 's/^output_interval_s.*/output_interval_s = 0.0/' "$model" >"$work/nohist.toml"
"$exe" run "$work/nohist.toml" --out "$work/N.h5" >/dev/null 2>&1 || fail "no histories: exit $?"
"$exe" run "$work/nohist.toml" --out "$work/O.h5" --output-interval 0.01 >/dev/null 2>&1 ||
  fail "--output-interval: exit $?"
"$python" - "$work/N.h5" "$work/O.h5" <<'PY' || fail "histories presence"
import sys, h5py
without, with_interval = (h5py.File(p, "r") for p in sys.argv[1:3])
assert "histories" not in without, "histories written though none were requested"
assert "time_stepping_policy" not in without, "an event-driven run file stores Moreau-Jean's"
pol = without["event_policy"].attrs
assert pol["zeno_ratio"] == 0.9 and pol["jam"] == 1, dict(pol)
assert pol["contact.tie_tolerance"] == 1e-9 and pol["contact.enumeration_unknowns"] == 14, dict(pol)
keys = [k.decode() if isinstance(k, bytes) else str(k) for k in pol["keys"]]
assert keys[-4:] == ["contact.tie_tolerance", "contact.contact_compliance",
                     "contact.impact_compliance", "contact.enumeration_unknowns"], keys
n = with_interval["histories/t_s"].shape[0]
assert n == 251, "--output-interval 0.01 over 2.5 s gave %d samples, expected 251" % n
PY

sed 's/^\(m *= *\).*/\1-5.0/' "$model" >"$work/bad.toml"
status=0
"$exe" run "$work/bad.toml" --out "$work/bad.h5" >/dev/null 2>"$work/err3" || status=$?
[ $status -eq 2 ] || fail "bad model: exit status $status, expected 2"
grep -q "deck.m" "$work/err3" || fail "bad model: message does not name deck.m: $(cat "$work/err3")"
[ ! -e "$work/bad.h5" ] && [ ! -e "$work/bad.h5.partial" ] || fail "bad model: output file left"

status=0
"$exe" run "$model" --out "$work/missing/dir/Y.h5" >/dev/null 2>"$work/err4" || status=$?
[ $status -eq 2 ] || fail "unwritable --out: exit status $status, expected 2"
[ "$(wc -l <"$work/err4")" -eq 1 ] || fail "unwritable --out: not one line: $(cat "$work/err4")"
grep -q -- "--out" "$work/err4" || fail "unwritable --out: message does not name --out"
[ ! -e "$work/missing/dir/Y.h5.partial" ] || fail "unwritable --out: temporary file left"
echo "ok"
