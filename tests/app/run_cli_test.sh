#!/usr/bin/env bash
# `skewbridge run`: a good model gives exit 0, a summary and a CSV whose last row reaches the end
# time; a bad model gives exit 2, one line naming the field, and no output file.
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe root -- "$@"
temp_dir

"$exe" run "$root/docs/examples/subsystem.toml" --csv "$work/run.csv" >"$work/out" 2>"$work/err" ||
  fail "good model: exit status $? ($(cat "$work/err"))"
grep -q "status ok" "$work/out" || fail "good model: no 'status ok' in the summary"
grep -q "balance error" "$work/out" || fail "good model: no energy ledger in the summary"
[ -f "$work/run.csv" ] || fail "good model: no CSV"
[ ! -e "$work/run.csv.partial" ] || fail "good model: temporary file left behind"
rows=$(($(wc -l <"$work/run.csv") - 1))
[ "$rows" -gt 100 ] || fail "good model: only $rows CSV rows"

"$exe" run "$root/docs/examples/pilot-bridge.toml" >"$work/out2" 2>&1 || fail "pilot bridge: exit $?"
grep -q "status ok" "$work/out2" || fail "pilot bridge: no 'status ok'"

sed 's/^\(m *= *\).*/\1-5.0/' "$root/docs/examples/subsystem.toml" >"$work/bad.toml"
grep -q -- "-5.0" "$work/bad.toml" || fail "could not make the bad model"
status=0
"$exe" run "$work/bad.toml" --csv "$work/bad.csv" >"$work/out3" 2>"$work/err3" || status=$?
[ $status -eq 2 ] || fail "bad model: exit status $status, expected 2"
[ "$(wc -l <"$work/err3")" -eq 1 ] || fail "bad model: message is not one line: $(cat "$work/err3")"
grep -q "deck.m" "$work/err3" || fail "bad model: message does not name deck.m: $(cat "$work/err3")"
[ ! -e "$work/bad.csv" ] && [ ! -e "$work/bad.csv.partial" ] || fail "bad model: output file left"
echo "ok"
