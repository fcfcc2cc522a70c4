#!/usr/bin/env bash
# Cells per second of real sweeps (every cell a new model through the evaluator, checkpoints
# and the final cube included), printed as a Markdown table for docs/performance.md.
#
#   bash scripts/bench/sweeps.sh [BUILD_DIR] [--repeat N] [--work DIR]
#
# BUILD_DIR defaults to build/release and needs the target skewbridge; simulate_benchmark and
# multispan_benchmark add the warm and multi-span figures when built.
# Grids, each beside its contact-free twin (the same grid with Pi_delta x 1e6: the gaps never
# close, so the twin costs only the free flow):
#   default      jobs/specs/default.toml (1296 cells)
#   C2-like      subsystem, a = 20 deg, eta0 = 1.07, cosine, Pi_delta = 0.5,
#                w0/w_g = 0.2 .. 5 (2000 cells)
#   pilot study  jobs/specs/pilot-study.toml (62 synthetic records x 3 Pi_delta = 186 cells)
#   multi-span   spans 1, 3, 5 x a = 0, 30 deg x w0/w_g = 0.5 .. 2 (240 cells)
# on 1 and 2 ranks. Columns: "cells/s" is the runner's rate over its cell phase (cells,
# messages, checkpoints); "end to end" divides the cells by the wall time of the whole
# command (MPI start-up, records, final cube); "per CPU s" by its CPU time over all ranks
# (steadier than wall time on a shared machine); "cell median / mean" are the cells' own
# evaluation times from the cube (stats/wall_s), from which the with-contact / twin ratios are
# taken: a rank descheduled between cells does not inflate them. Each figure is the best of N runs (default 3):
# the machine is usually shared. The warm single-run figures of simulate_benchmark (one model
# repeated, propagators cached) and the event-driven multi-span cost per simulated second
# against the span count (multispan_benchmark, 1 to 50 spans) follow the table.
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=build/release
repeat=3
work=""
while [ $# -gt 0 ]; do
  case "$1" in
    --repeat) repeat=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) build=$1; shift ;;
  esac
done
build=$(cd "$build" && pwd)
exe=$build/skewbridge
bench=$build/tests/dynamics/simulate_benchmark
spans_bench=$build/tests/multispan/multispan_benchmark
[ -x "$exe" ] || { echo "sweeps.sh: error: $exe is missing (cmake --build $build --target skewbridge)" >&2; exit 2; }
[ -n "$work" ] || work=$(mktemp -d)
mkdir -p "$work"
set -a && source "$here/scripts/openmpi.env" && set +a  # Open MPI as root, more ranks than cores
cd "$work"

# The grids. The twins replace every Pi_delta value v by v x 1e6.
cp "$here/jobs/specs/default.toml" default.toml
cp "$here/jobs/specs/pilot-study.toml" pilot.toml
cat > c2.toml <<'TOML'
[sweep]
name = "c2"
family = "subsystem"
[axes]
w0_over_wg = {logspace = [0.2, 5.0, 2000]}
[fixed]
pulse = "cosine"
a_deg = 20
eta0 = 1.07
Pi_delta = 0.5
TOML
cat > multispan.toml <<'TOML'
[sweep]
name = "multispan"
family = "multi-span"
[axes]
spans = [1, 3, 5]
a_deg = [0, 30]
w0_over_wg = {logspace = [0.5, 2.0, 40]}
[fixed]
W_over_L = 0.3
Pi_delta = 1.0
delta_over_L = 0.002
mu = 0.1
seat_over_L = 0.02
TOML
for g in default c2 pilot multispan; do
  sed -E '/^Pi_delta *=/ s/([0-9]+\.?[0-9]*)/\1e6/g' "$g.toml" > "$g-free.toml"
  grep -q '^Pi_delta = .*e6' "$g-free.toml" || { echo "sweeps.sh: error: no Pi_delta in $g.toml" >&2; exit 2; }
done

# median and mean of the cells' own evaluation times in a cube [us] (stats/wall_s: the time of
# each cell alone, so a rank descheduled between cells does not count)
cell_times() {
  /usr/bin/python3 - "$1" <<'PY'
import sys, h5py, numpy as np
with h5py.File(sys.argv[1], "r") as f:
    (name,) = list(f["sweeps"])
    w = f["sweeps"][name]["stats/wall_s"][()].ravel() * 1e6
print(f"{np.median(w):.1f} {np.mean(w):.1f}")
PY
}

# run SPEC RANKS -> "cells runner_rate end_to_end_rate per_cpu_rate median_us mean_us"
# (each the best of $repeat runs)
run() {
  local spec=$1 n=$2 best_rate=0 best_e2e=0 best_cpu=0 best_med=1e30 best_mean=1e30 cells=0
  for _ in $(seq "$repeat"); do
    local t0 t1 line cpu rate e2e per_cpu med mean
    t0=$(date +%s.%N)
    # /usr/bin/time counts the CPU of mpiexec and of every rank it waited for.
    /usr/bin/time -f "cpu %U %S" -o time.txt mpiexec -n "$n" --oversubscribe "$exe" sweep "$spec" \
      --out out.h5 --force --quiet 2> log.txt
    t1=$(date +%s.%N)
    line=$(grep '^sweep complete' log.txt) || { echo "sweeps.sh: error: $spec on $n ranks:" >&2; cat log.txt >&2; exit 1; }
    cells=$(sed -E 's/.* ([0-9]+) computed on .*/\1/' <<<"$line")
    rate=$(sed -E 's/.*\(([0-9.]+) cells\/s\).*/\1/' <<<"$line")
    cpu=$(awk '/^cpu/ {print $2 + $3}' time.txt)
    e2e=$(awk -v c="$cells" -v a="$t0" -v b="$t1" 'BEGIN{printf "%.1f", c / (b - a)}')
    per_cpu=$(awk -v c="$cells" -v t="$cpu" 'BEGIN{printf "%.1f", (t > 0 ? c / t : 0)}')
    read -r med mean < <(cell_times out.h5)
    best_rate=$(awk -v x="$rate" -v y="$best_rate" 'BEGIN{print (x > y ? x : y)}')
    best_e2e=$(awk -v x="$e2e" -v y="$best_e2e" 'BEGIN{print (x > y ? x : y)}')
    best_cpu=$(awk -v x="$per_cpu" -v y="$best_cpu" 'BEGIN{print (x > y ? x : y)}')
    best_med=$(awk -v x="$med" -v y="$best_med" 'BEGIN{print (x < y ? x : y)}')
    best_mean=$(awk -v x="$mean" -v y="$best_mean" 'BEGIN{print (x < y ? x : y)}')
  done
  echo "$cells $best_rate $best_e2e $best_cpu $best_med $best_mean"
}

k() { awk -v x="$1" 'BEGIN{ if (x >= 10000) printf "%.1fk", x / 1000; else printf "%.0f", x }'; }

echo "Sweeps measured $(date -u +%Y-%m-%dT%H:%MZ), commit $(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo '?'), $(nproc) cores, load $(cut -d' ' -f1 /proc/loadavg), best of $repeat."
echo
echo "| grid | cells | ranks | cells/s | end to end | per CPU s, end to end | cell median / mean [us] | twin cells/s | twin cell median / mean [us] | with contact / twin (median, mean) |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for g in default c2 pilot multispan; do
  case $g in
    default) label="default spec" ;;
    c2) label="C2-like subsystem" ;;
    pilot) label="pilot study (62 records)" ;;
    multispan) label="multi-span (1-5 spans)" ;;
  esac
  for n in 1 2; do
    read -r cells rate e2e cpu med mean < <(run "$g.toml" "$n")
    read -r _ frate _ _ fmed fmean < <(run "$g-free.toml" "$n")
    ratios=$(awk -v a="$med" -v b="$fmed" -v c="$mean" -v d="$fmean" 'BEGIN{printf "%.2fx, %.2fx", a / b, c / d}')
    echo "| $label | $cells | $n | $(k "$rate") | $(k "$e2e") | $(k "$cpu") | $med / $mean | $(k "$frate") | $fmed / $fmean | $ratios |"
  done
done

if [ -x "$bench" ]; then
  echo
  echo "Warm single runs (simulate_benchmark: one model repeated, propagators cached), runs per CPU second:"
  echo
  echo "| case | runs/s |"
  echo "|---|---|"
  "$bench" --benchmark_filter='BM_SubsystemCosinePulse|BM_PilotBridgeRecord' --benchmark_min_time=0.3 \
      2>/dev/null | grep -E '^BM_' |
    sed -E 's/^(BM_[^ ]+).*runs_per_s=([0-9.]+[kM]?)\/s.*/| \1 | \2 |/'
else
  echo
  echo "(warm single-run figures: build the target simulate_benchmark)"
fi

if [ -x "$spans_bench" ]; then
  echo
  echo "Event-driven multi-span runs (multispan_benchmark: 1 s simulated, CPU time per simulated second):"
  echo
  echo "| spans | ms per simulated second |"
  echo "|---|---|"
  "$spans_bench" --benchmark_filter='EventDriven/(1|5|10|20|50)$' --benchmark_min_time=0.2 2>/dev/null |
    awk '/^EventDriven\// { split($1, a, "/"); v = $4; if ($5 == "us") v /= 1000; if ($5 == "s") v *= 1000;
                              printf "| %s | %.3g |\n", a[2], v }'
else
  echo
  echo "(multi-span scaling: build the target multispan_benchmark)"
fi
