#!/usr/bin/env bash
# The cost of [limit_states] in a family that computes the corner travel beside its maxima: the
# pilot bridge under the three real records of tests/data/records at a = 20 and 40 deg
# (Pi_delta = 0.5, seat/L = 0.001, 6 cells), with and without the five limit states, counted in
# instructions by callgrind (one process: repeatable on a shared machine), printed as a Markdown
# table for docs/fragility.md.
#
#   bash scripts/bench/limit_states_cost.sh [BUILD_DIR] [--work DIR]
#
# BUILD_DIR defaults to build/release and needs the target skewbridge. "cells" is the inclusive
# count of the outermost evaluator (LimitStateEvaluator::Evaluate with, SpectraEvaluator::Evaluate
# without): the runs, the corner travels, the demands and exceedances; "final cube" is
# WriteFinalCube, which fits the fragility functions once per sweep on rank 0.
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
build=$src/build/release
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
while [ $# -gt 0 ]; do
  case $1 in
    --work) work=$2; mkdir -p "$work"; shift 2 ;;
    *) build=$1; shift ;;
  esac
done
exe=$build/skewbridge
cd "$work"
mkdir -p rec
cp "$src/tests/data/records/NIS090.AT2" "$src/tests/data/records/RSN763_LOMAP_GIL067.AT2" \
   "$src/tests/data/records/0111a.smc" rec/
cat > with.toml <<'TOML'
[sweep]
name = "cost"
family = "pilot-bridge"
[records]
folder = "rec"
pattern = "*"
[axes]
record = "*"
a_deg = [20, 40]
[fixed]
Pi_delta = 0.5
seat_over_L = 0.001
[limit_states]
unseating = true
rotation = {above_rad = 0.0005}
seat_displacement = {above_m = 0.05}
residual = {above_m = 0.005}
joint_closing = true
TOML
sed '/^\[limit_states\]/,$d' with.toml > without.toml
inclusive() {  # inclusive FILE FUNCTION: the inclusive Ir of FUNCTION in a callgrind output
  callgrind_annotate --inclusive=yes "$1" 2>/dev/null |
    awk -v f="$2" '!done && index($0, f) { gsub(",", "", $1); print $1; done = 1 }'
}
declare -A cells cube total
for s in with without; do
  valgrind --tool=callgrind --callgrind-out-file="$s.out" "$exe" sweep "$s.toml" --out "$s.h5" \
    --quiet > /dev/null 2> "$s.log"
  outer=$([ "$s" = with ] && echo "LimitStateEvaluator::Evaluate(" ||
          echo "SpectraEvaluator::Evaluate(")
  cells[$s]=$(inclusive "$s.out" "$outer")
  cube[$s]=$(inclusive "$s.out" "WriteFinalCube(")
  total[$s]=$(awk '/Collected/ { gsub(",", "", $4); print $4 }' "$s.log")
done
n=6
echo "| instructions (callgrind) | with limit states | without | difference |"
echo "|---|---|---|---|"
awk -v a="${cells[with]}" -v b="${cells[without]}" -v n=$n 'BEGIN {
  printf "| cells, inclusive (%d cells) | %d | %d | %+d (%+.4f %%) |\n", n, a, b, a - b, 100 * (a - b) / b
  printf "| per cell | %.0f | %.0f | %+.0f |\n", a / n, b / n, (a - b) / n }'
awk -v a="${cube[with]}" -v b="${cube[without]}" 'BEGIN {
  printf "| final cube (WriteFinalCube, once) | %d | %d | %+d |\n", a, b, a - b }'
awk -v a="${total[with]}" -v b="${total[without]}" 'BEGIN {
  printf "| whole command | %d | %d | %+d |\n", a, b, a - b }'
