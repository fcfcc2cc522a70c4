#!/usr/bin/env bash
# Runs the `skewbridge records` command as a user would.
#   cli_test.sh error SKEWBRIDGE FILE PATTERN   exit status 2 and one stderr line matching PATTERN
#   cli_test.sh synth SKEWBRIDGE WORKDIR        same seed, same bytes; the suite's set loads
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
mode=${1:?usage: cli_test.sh error|synth SKEWBRIDGE ...}
exe=${2:?usage: cli_test.sh error|synth SKEWBRIDGE ...}
test_name="records cli_test $mode"
case "$mode" in
  error)
    args mode exe file pattern -- "$@"
    status=0
    stderr=$("$exe" records info "$file" 2>&1 >/dev/null) || status=$?
    [ "$status" -eq 2 ] || fail "expected exit 2, got $status: $stderr"
    [ "$(printf '%s\n' "$stderr" | wc -l)" -eq 1 ] || fail "expected one line: $stderr"
    printf '%s\n' "$stderr" | grep -Eq -- "$pattern" || fail "'$stderr' !~ '$pattern'"
    echo "ok: $stderr"
    ;;
  synth)
    args mode exe work -- "$@"
    fresh_dir "$work"
    for run in a b; do
      "$exe" records synth --count 4 --seed 9 --out "$work/$run" --duration-s 10 \
        --pga-min-g 0.2 --pga-max-g 0.3 >/dev/null || fail "synth failed"
    done
    diff -r "$work/a" "$work/b" || fail "same seed gave different bytes"
    rows=$("$exe" records info "$work/a/set.toml" --csv | tail -n +2)
    [ "$(printf '%s\n' "$rows" | wc -l)" -eq 4 ] || fail "expected 4 records: $rows"
    # PGA (column 6, g) inside the requested range for every record.
    printf '%s\n' "$rows" | awk -F, '$6 < 0.2 || $6 > 0.3 { bad = 1 } END { exit bad }' ||
      fail "PGA outside 0.2-0.3 g: $rows"
    echo "ok"
    ;;
  *)
    echo "unknown mode $mode" >&2; exit 2 ;;
esac
