#!/usr/bin/env bash
# Builds and runs the whole test suite: the release preset (unit, cross-check, MPI and lint
# tests), then the unit tests under AddressSanitizer + UndefinedBehaviorSanitizer.
# Any failing test, sanitizer report or build error makes it exit non-zero.
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
jobs=$(nproc)
export CMAKE_BUILD_PARALLEL_LEVEL=$jobs CTEST_PARALLEL_LEVEL=$jobs

echo "== release: build and test"
cmake --workflow --preset release

echo "== asan-ubsan: build and test (MPI off; see docs/architecture.md)"
cmake --workflow --preset asan-ubsan

echo "== fuzz: each record reader under libFuzzer + ASan + UBSan for 12 s (docs/records.md)"
cmake --preset fuzz
cmake --build --preset fuzz
fuzz_work=$(mktemp -d)
for fuzzer in build/fuzz/records/fuzz_records_*; do
  corpus="$fuzz_work/$(basename "$fuzzer")"
  mkdir -p "$corpus"
  find tests/data/records -type f ! -name '*.md' -exec cp {} "$corpus" \;
  "$fuzzer" -max_total_time=12 -timeout=10 -max_len=8192 -artifact_prefix="$fuzz_work/" "$corpus"
done
rm -rf "$fuzz_work"
