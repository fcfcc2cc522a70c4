#!/usr/bin/env bash
# Runs the `skewbridge records` command as a user would.
#   cli_test.sh error SKEWBRIDGE FILE PATTERN   exit status 2 and one stderr line matching PATTERN
#   cli_test.sh synth SKEWBRIDGE WORKDIR        same seed, same bytes; the suite's set loads
set -u
mode=${1:?mode}
exe=${2:?skewbridge}
case "$mode" in
  error)
    file=${3:?file}
    pattern=${4:?pattern}
    stderr=$("$exe" records info "$file" 2>&1 >/dev/null)
    status=$?
    [ "$status" -eq 2 ] || { echo "expected exit 2, got $status: $stderr"; exit 1; }
    [ "$(printf '%s\n' "$stderr" | wc -l)" -eq 1 ] || { echo "expected one line: $stderr"; exit 1; }
    printf '%s\n' "$stderr" | grep -Eq -- "$pattern" || { echo "'$stderr' !~ '$pattern'"; exit 1; }
    echo "ok: $stderr"
    ;;
  synth)
    work=${3:?workdir}
    rm -rf "$work" && mkdir -p "$work" || exit 1
    for run in a b; do
      "$exe" records synth --count 4 --seed 9 --out "$work/$run" --duration-s 10 \
        --pga-min-g 0.2 --pga-max-g 0.3 >/dev/null || { echo "synth failed"; exit 1; }
    done
    diff -r "$work/a" "$work/b" || { echo "same seed gave different bytes"; exit 1; }
    rows=$("$exe" records info "$work/a/set.toml" --csv | tail -n +2)
    [ "$(printf '%s\n' "$rows" | wc -l)" -eq 4 ] || { echo "expected 4 records: $rows"; exit 1; }
    # PGA (column 6, g) inside the requested range for every record.
    printf '%s\n' "$rows" | awk -F, '$6 < 0.2 || $6 > 0.3 { bad = 1 } END { exit bad }' ||
      { echo "PGA outside 0.2-0.3 g: $rows"; exit 1; }
    echo "ok"
    ;;
  *)
    echo "unknown mode $mode"; exit 2 ;;
esac
