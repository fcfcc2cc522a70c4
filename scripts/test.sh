#!/usr/bin/env bash
# Builds and runs the whole test suite: the release preset (unit, cross-check, MPI and lint
# tests), then the unit tests under AddressSanitizer + UndefinedBehaviorSanitizer (built beside
# the release tests), then each record reader under libFuzzer for 12 s, one per core at a time. Each step's output goes to build/test-logs/ (the
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

# cpu_of FILE: the user + sys seconds of the children in FILE, the output of `times` (its
# second line).
cpu_of() {
  awk 'NR == 2 { s = 0; for (i = 1; i <= 2; i++) { split($i, p, "m"); sub("s", "", p[2])
       s += p[1] * 60 + p[2] } printf "%.0f", s }' "$1"
}
# cpu_now: sets cpu to the user + sys seconds of every child this shell has waited for (`times`
# run in this shell: a command substitution would time its own subshell), through a file of
# this shell's own, since a background subshell keeps its clock at the same time.
cpu_now() {
  local file="$logs/.times.$BASHPID"
  times >"$file"
  cpu=$(cpu_of "$file")
}
# record NAME WALL CPU: one stage's line, printed and kept for the table at the end.
record() {
  local line
  line=$(printf '%-37s %5d s wall %6d s CPU' "$1" "$2" "$3")
  echo "   $line"
  timings+=("$line")
}
# clock_start / clock_stop NAME: the wall and CPU seconds of a stage run in this shell.
clock_start() {
  stage_wall=$SECONDS
  cpu_now
  stage_cpu=$cpu
}
clock_stop() {
  cpu_now
  record "$1" $((SECONDS - stage_wall)) $((cpu - stage_cpu))
}

# build_preset PRESET BUILD_PRESET [SUFFIX]: configure one preset and build it with the build
# preset BUILD_PRESET (its log starts afresh), timed under the name "PRESET configure+build
# SUFFIX"; the status is cmake's.
build_preset() {
  local log="$logs/$1.log"
  : >"$log"
  clock_start
  cmake --preset "$1" >>"$log" 2>&1 && cmake --build --preset "$2" >>"$log" 2>&1
  local status=$?
  clock_stop "$1 configure+build${3:+ $3}"
  [ "$status" -eq 0 ] || echo "$1: build failed (exit $status), see $log"
  return "$status"
}

# test_preset PRESET: run one preset's tests (appended to its log), timed; add its ctest counts.
test_preset() {
  local log="$logs/$1.log" start=$SECONDS
  # In a subshell whose `times` counts ctest alone: a background build reaped while the tests
  # run would otherwise be counted in their CPU.
  (
    ctest --preset "$1" >>"$log" 2>&1
    times >"$logs/.times-$1"
  )
  record "$1 test" $((SECONDS - start)) "$(cpu_of "$logs/.times-$1")"
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
# The benchmark programs, which no test runs, are left to the build preset release (and so
# to every build a developer runs with it): release-tests builds everything else.
if build_preset release release-tests; then
  release_built=1
else
  release_built=0 failed=$((failed + 1))
fi
# The release tests leave a core idle much of the time (MPI start-up, files, waits), so the
# asan-ubsan build runs beside them at a lower priority (nice 10): the tests keep the cores
# they ask for, the build takes the rest. Its own wall and CPU time are measured in its
# subshell (whose clock starts at its fork) and printed once it is done.
echo "== asan-ubsan: build beside the release tests (MPI off; see docs/architecture.md)"
(
  renice -n 10 -p "$BASHPID" >/dev/null 2>&1 || true
  build_preset asan-ubsan asan-ubsan "(nice 10)"
) >"$logs/.asan-build.out" 2>&1 &
asan_build=$!
[ "$release_built" -eq 0 ] || test_preset release
wait "$asan_build"
asan_status=$?
cat "$logs/.asan-build.out"
timings+=("$(sed -n 's/^   //p' "$logs/.asan-build.out" | head -1)")
echo "== asan-ubsan: test"
if [ "$asan_status" -eq 0 ]; then test_preset asan-ubsan; else failed=$((failed + 1)); fi

echo "== fuzz: each record reader and the excitation-file reader under libFuzzer + ASan + UBSan for 12 s (docs/records.md)"
fuzz_log="$logs/fuzz.log"
clock_start
cmake --preset fuzz >"$fuzz_log" 2>&1 && cmake --build --preset fuzz >>"$fuzz_log" 2>&1
status=$?
clock_stop "fuzz configure+build"
if [ "$status" -eq 0 ]; then
  clock_start
  fuzz_work=$(mktemp -d)
  # One fuzzer per core at a time, each with its own corpus, artifacts and log (appended to
  # fuzz.log in order once all have run); a fuzzer's exit status is kept in its own file.
  fuzzers=(build/fuzz/records/fuzz_records_*)
  for fuzzer in "${fuzzers[@]}"; do
    while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
    name=$(basename "$fuzzer")
    corpus="$fuzz_work/$name/corpus"
    mkdir -p "$corpus"
    find tests/data/records -type f ! -name '*.md' -exec cp {} "$corpus" \;
    seeds="records/fuzz/corpus/$name"
    if [ -d "$seeds" ]; then cp "$seeds"/* "$corpus"; fi
    {
      "$fuzzer" -max_total_time=12 -timeout=10 -max_len=8192 \
        -artifact_prefix="$fuzz_work/$name/" "$corpus" >"$fuzz_work/$name.log" 2>&1
      echo $? >"$fuzz_work/$name.status"
    } &
  done
  wait
  for fuzzer in "${fuzzers[@]}"; do
    name=$(basename "$fuzzer")
    cat "$fuzz_work/$name.log" >>"$fuzz_log"
    if [ "$(cat "$fuzz_work/$name.status" 2>/dev/null)" = 0 ]; then
      passed=$((passed + 1))
    else
      failed=$((failed + 1))
      echo "$name: FAILED, see $fuzz_log"
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
