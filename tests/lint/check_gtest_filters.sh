#!/usr/bin/env bash
# Every GoogleTest test of a test program shared by several ctest tests runs in exactly one of
# them. Argument: a file whose first line is the program and whose other lines are
# "CTEST_NAME<TAB>FILTER" (a --gtest_filter pattern), one per ctest test of the program (the
# shards of a test share one).
set -euo pipefail
list=$1
program=$(head -n 1 "$list")

# cases ARGS...: the program's test cases (Suite.Name, Prefix/Suite.Name/0) that ARGS select.
cases() {
  "$program" --gtest_list_tests "$@" | awk '
    /^[^ ]/ { suite = $1; next }
    /^  [^ ]/ { print suite $1 }'
}

all=$(cases)
[ -n "$all" ] || { echo "$program: lists no tests"; exit 1; }
selected=""
while IFS=$'\t' read -r name filter; do
  mine=$(cases "--gtest_filter=$filter")
  [ -n "$mine" ] || { echo "$name: its filter selects no test of $program"; exit 1; }
  selected+="$mine"$'\n'
done < <(tail -n +2 "$list")

missing=$(comm -23 <(sort <<<"$all") <(sed '/^$/d' <<<"$selected" | sort -u))
twice=$(sed '/^$/d' <<<"$selected" | sort | uniq -d)
[ -z "$missing" ] || { echo "$program: tests no ctest test runs:"; echo "$missing"; }
[ -z "$twice" ] || { echo "$program: tests run by two ctest tests:"; echo "$twice"; }
[ -z "$missing$twice" ] || exit 1
echo "$program: $(wc -l <<<"$all") tests, each run by one of $(($(wc -l <"$list") - 1)) ctest tests"
