#!/usr/bin/env bash
# The time scripts/report takes on the pilot fragility cube (jobs/specs/real/pilot-fragility.toml:
# 19 records x 12 stripes x 2 skews x 3 seats = 1368 cells), the cube made first on 2 ranks
# (needs ../shared/records, as the spec says) unless --cube names one already made. Prints, per
# repetition, the wall and CPU (user + sys) seconds and the figures written, then the median
# wall time and the machine's load average (a busy machine stretches the wall time, not the CPU).
#
#   bash scripts/bench/report_fragility.sh [BUILD_DIR] [--cube CUBE.h5] [--report SCRIPT]
#                                          [--repeat N] [--work DIR]
#
# BUILD_DIR defaults to build/release (the target skewbridge); --report times another
# checkout's scripts/report on the same cube (the figure before a change).
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
build=$src/build/release
report=$src/scripts/report
work=$(mktemp -d)
keep=0
cube=""
repeat=3
while [ $# -gt 0 ]; do
  case $1 in
    --cube) cube=$(realpath "$2"); shift 2 ;;
    --report) report=$(realpath "$2"); shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --work) rm -rf "$work"; work=$2; keep=1; mkdir -p "$work"; shift 2 ;;
    *) build=$1; shift ;;
  esac
done
[ "$keep" = 1 ] || trap 'rm -rf "$work"' EXIT
if [ -z "$cube" ]; then
  set -a
  # shellcheck disable=SC1091
  source "$src/scripts/openmpi.env"
  set +a
  cube=$work/fragility.h5
  mpiexec -n 2 "$build/skewbridge" sweep "$src/jobs/specs/real/pilot-fragility.toml" \
    --out "$cube" >"$work/sweep.log" 2>&1 || { cat "$work/sweep.log"; exit 1; }
fi
cells=$(/usr/bin/python3 -c "import h5py, sys; f = h5py.File(sys.argv[1], 'r'); \
print(sum(int(g.attrs['cells']) for g in f['sweeps'].values()))" "$cube")
echo "cube: $cube ($cells cells); report: $report"
walls=()
for i in $(seq "$repeat"); do
  out=$work/report-$i
  rm -rf "$out"
  start=$(date +%s.%N)
  /usr/bin/time -f "%U %S" -o "$work/time-$i.txt" /usr/bin/python3 "$report" "$cube" \
    --out "$out" >"$work/report-$i.log" 2>&1 || { cat "$work/report-$i.log"; exit 1; }
  cpu=$(tail -1 "$work/time-$i.txt")
  end=$(date +%s.%N)
  wall=$(echo "$end - $start" | bc -l)
  walls+=("$wall")
  pngs=$(find "$out" -name '*.png' | wc -l)
  printf 'run %d: wall %.2f s, cpu %.2f s, %d figures\n' "$i" "$wall" \
    "$(echo "$cpu" | awk '{print $1 + $2}')" "$pngs"
done
median=$(printf '%s\n' "${walls[@]}" | sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}')
printf 'median wall: %.2f s over %d runs; load average: %s\n' "$median" "$repeat" \
  "$(cut -d' ' -f1-3 /proc/loadavg)"
