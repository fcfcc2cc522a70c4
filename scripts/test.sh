#!/usr/bin/env bash
# Builds and runs the whole test suite: the release preset (unit, cross-check, MPI and lint
# tests), then the unit tests under AddressSanitizer + UndefinedBehaviorSanitizer, then each
# record reader under libFuzzer for 12 s. Each step's output goes to build/test-logs/ (the
# fuzzers' thousands of lines too); each stage prints its wall and CPU time (user + sys of
# everything it ran), and the last line printed is exactly `N passed, N failed`, counting every
# ctest test of both presets and each fuzzer (a build that fails counts as one failure). Exit
# status 0 only when nothing failed.
set -uo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
export CMAKE_BUILD_PARALLEL_LEVEL=$jobs CTEST_PARALLEL_LEVEL=$jobs
logs=build/test-logs
mkdir -p "$logs"
passed=0 failed=0
timings=()

# cpu_now: sets cpu to the user + sys seconds of every child this shell has waited for (the
# second line of `times`, run in this shell: a command substitution would time its own
# subshell).
cpu_now() {
  times >"$logs/.times"
  cpu=$(awk 'NR == 2 { s = 0; for (i = 1; i <= 2; i++) { split($i, p, "m"); sub("s", "", p[2])
         s += p[1] * 60 + p[2] } printf "%.0f", s }' "$logs/.times")
}
# clock_start / clock_stop NAME: the wall and CPU seconds of a stage, printed and kept for the
# table at the end.
clock_start() {
  stage_wall=$SECONDS
  cpu_now
  stage_cpu=$cpu
}
clock_stop() {
  cpu_now
  local line
  line=$(printf '%-26s %5d s wall %6d s CPU' "$1" $((SECONDS - stage_wall)) $((cpu - stage_cpu)))
  echo "   $line"
  timings+=("$line")
}

# run_preset PRESET: configure, build and test one preset (the steps of its workflow preset),
# each timed; add its ctest counts.
run_preset() {
  local log="$logs/$1.log"
  : >"$log"
  clock_start
  cmake --preset "$1" >>"$log" 2>&1 && cmake --build --preset "$1" >>"$log" 2>&1
  local status=$?
  clock_stop "$1 configure+build"
  if [ "$status" -ne 0 ]; then
    echo "$1: build failed (exit $status), see $log"
    failed=$((failed + 1))
    return
  fi
  clock_start
  ctest --preset "$1" >>"$log" 2>&1
  clock_stop "$1 test"
  # ctest's summary: "97% tests passed, 2 tests failed out of 80"
  local summary
  summary=$(grep -E "tests passed, [0-9]+ tests failed out of [0-9]+" "$log" | tail -1)
  if [ -z "$summary" ]; then
    echo "$1: ctest did not finish, see $log"
    failed=$((failed + 1))
    return
  fi
  local bad total
  bad=$(sed -E 's/.* ([0-9]+) tests failed out of ([0-9]+).*/\1/' <<<"$summary")
  total=$(sed -E 's/.* out of ([0-9]+).*/\1/' <<<"$summary")
  passed=$((passed + total - bad))
  failed=$((failed + bad))
  echo "$1: $((total - bad)) passed, $bad failed (log $log)"
  [ "$bad" -eq 0 ] || grep -E "^\s+[0-9]+ - .* \((Failed|Timeout|SEGFAULT|Not Run)" "$log"
}

clock_start
all_wall=$stage_wall all_cpu=$stage_cpu
echo "== release: build and test"
run_preset release
echo "== asan-ubsan: build and test (MPI off; see docs/architecture.md)"
run_preset asan-ubsan

echo "== fuzz: each record reader and the excitation-file reader under libFuzzer + ASan + UBSan for 12 s (docs/records.md)"
fuzz_log="$logs/fuzz.log"
clock_start
cmake --preset fuzz >"$fuzz_log" 2>&1 && cmake --build --preset fuzz >>"$fuzz_log" 2>&1
status=$?
clock_stop "fuzz configure+build"
if [ "$status" -eq 0 ]; then
  clock_start
  fuzz_work=$(mktemp -d)
  for fuzzer in build/fuzz/records/fuzz_records_*; do
    corpus="$fuzz_work/$(basename "$fuzzer")"
    mkdir -p "$corpus"
    find tests/data/records -type f ! -name '*.md' -exec cp {} "$corpus" \;
    seeds="records/fuzz/corpus/$(basename "$fuzzer")"
    if [ -d "$seeds" ]; then cp "$seeds"/* "$corpus"; fi
    if "$fuzzer" -max_total_time=12 -timeout=10 -max_len=8192 -artifact_prefix="$fuzz_work/" \
      "$corpus" >>"$fuzz_log" 2>&1; then
      passed=$((passed + 1))
    else
      failed=$((failed + 1))
      echo "$(basename "$fuzzer"): FAILED, see $fuzz_log"
    fi
  done
  rm -rf "$fuzz_work"
  clock_stop "fuzzing"
else
  echo "fuzz: build failed, see $fuzz_log"
  failed=$((failed + 1))
fi

stage_wall=$all_wall stage_cpu=$all_cpu
echo "== time per stage ($jobs cores; CPU is user + sys)"
clock_stop "all stages" >/dev/null
printf '   %s\n' "${timings[@]}"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
