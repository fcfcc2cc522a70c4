#!/usr/bin/env bash
# The cost of a compliant record cell against the rigid cell of the same record, through the sweep
# (docs/compliant.md §5): per record, a 1-rank model-file sweep of the study's stripes under the
# rigid law (a rigid model file, eps_N one value) and under the compliant law (its backfill
# twin), counted in instructions by callgrind (one process: repeatable on a shared machine). The
# count is the inclusive one of ModelFileEvaluator::Evaluate, every cell of the record (its
# stripes share the record's contact-free response); the ratio is compliant over rigid. Prints a
# Markdown table, one row per record, and the ratio of the sums.
#
#   bash scripts/bench/compliant_cost.sh [BUILD_DIR] [--bridge pilot|bridge-a] [--stripes N]
#        [--work DIR] [RECORD ...]
#
# BUILD_DIR defaults to build/release (the target skewbridge). --bridge pilot (default): the pilot
# at a = 20 deg, eps_N = 0.5 (docs/examples/pilot-bridge.toml) against
# docs/examples/pilot-bridge-backfill.toml, Sa(T1) from 0.5 to 6 g; bridge-a: Bridge_A at
# eps_N = 0.5 against docs/examples/bridge-a-backfill.toml, Sa(0.678 s) from 0.1 to 2 g. --stripes
# (default 4) stripes on the study's range. The records are names of records/sets/shared.toml
# (default three: RSN6_IMPVALL.I_I-ELC180.AT2, RSN1084_NORTHR_SCS052.AT2, NIS090.AT2); they need
# ../shared/records beside the repository, as the studies do.
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
build=$src/build/release
work=$(mktemp -d)
keep=0
bridge=pilot
stripes=4
records=()
while [ $# -gt 0 ]; do
  case $1 in
    --work) work=$2; keep=1; mkdir -p "$work"; shift 2 ;;
    --bridge) bridge=$2; shift 2 ;;
    --stripes) stripes=$2; shift 2 ;;
    -*) echo "compliant_cost.sh: unknown option $1" >&2; exit 2 ;;
    *) if [ -d "$1" ]; then build=$(cd "$1" && pwd); else records+=("$1"); fi; shift ;;
  esac
done
[ "$keep" = 1 ] || trap 'rm -rf "$work"' EXIT
[ ${#records[@]} -gt 0 ] ||
  records=(RSN6_IMPVALL.I_I-ELC180.AT2 RSN1084_NORTHR_SCS052.AT2 NIS090.AT2)
case $bridge in
  pilot) rigid=pilot-bridge.toml; compliant=pilot-bridge-backfill.toml
         im="{logspace = [0.5, 6.0, $stripes]}"; period='"T1"'; extra='a_deg = [20]' ;;
  bridge-a) rigid=bridge-a.toml; compliant=bridge-a-backfill.toml
            im="{logspace = [0.1, 2.0, $stripes]}"; period=0.678; extra='' ;;
  *) echo "compliant_cost.sh: --bridge: pilot or bridge-a, not $bridge" >&2; exit 2 ;;
esac
exe=$build/skewbridge
inclusive() {  # inclusive FILE FUNCTION: the inclusive Ir of FUNCTION in a callgrind output
  callgrind_annotate --inclusive=yes "$1" 2>/dev/null |
    awk -v f="$2" '!done && index($0, f) { gsub(",", "", $1); print $1; done = 1 }'
}
spec() {  # spec LAW MODEL RECORD: a one-record spec of the study's stripes
  local eps=""
  [ "$1" = rigid ] && eps='eps_N = [0.5]'
  cat <<TOML
[sweep]
name = "cost-$1"
family = "model-file"
model = "$src/docs/examples/$2"
[records]
set = "$src/records/sets/shared.toml"
scale_to = { measure = "Sa", period = $period, xi = 0.05 }
max_scale = 100.0
[axes]
record = ["$3"]
im_g = $im
$extra
$eps
seat_over_L = [0.001]
[limit_states]
unseating = true
rotation = {above_rad = 0.0005}
TOML
}
echo "| record | rigid (Ir) | compliant (Ir) | compliant / rigid |"
echo "|---|---|---|---|"
sum_r=0
sum_c=0
cd "$work"
for rec in "${records[@]}"; do
  declare -A ir=()
  for law in rigid compliant; do
    model=$rigid
    [ "$law" = compliant ] && model=$compliant
    spec "$law" "$model" "$rec" > "$law.toml"
    valgrind --tool=callgrind --callgrind-out-file="$law.out" "$exe" sweep "$law.toml" \
      --out "$law.h5" --force --quiet > /dev/null 2> "$law.log" ||
      { echo "compliant_cost.sh: $rec, $law: the sweep failed (see $work/$law.log)" >&2; exit 1; }
    ir[$law]=$(inclusive "$law.out" "ModelFileEvaluator::Evaluate(")
    [ -n "${ir[$law]}" ] ||
      { echo "compliant_cost.sh: no ModelFileEvaluator::Evaluate in $law.out" >&2; exit 1; }
  done
  sum_r=$((sum_r + ir[rigid]))
  sum_c=$((sum_c + ir[compliant]))
  printf "| %s | %s | %s | %.2f |\n" "$rec" "${ir[rigid]}" "${ir[compliant]}" \
    "$(echo "${ir[compliant]} / ${ir[rigid]}" | bc -l)"
  unset ir
done
printf "| all %d records | %s | %s | %.2f |\n" "${#records[@]}" "$sum_r" "$sum_c" \
  "$(echo "$sum_c / $sum_r" | bc -l)"
