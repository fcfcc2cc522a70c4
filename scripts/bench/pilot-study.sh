#!/usr/bin/env bash
# Wall and CPU time of the pilot study on 2 ranks (the target: the whole study under 1 s on 2
# ranks, same bytes), and, given a second program, whether both write the same cube.
#
#   bash scripts/bench/pilot-study.sh [BUILD_DIR] [--repeat N] [--against OTHER_SKEWBRIDGE]
#
# Prints one line per run (wall s, CPU s of all ranks) and the best; with --against, runs the
# other program once and compares the cubes dataset by dataset (scripts/bench/same_cube.py:
# timings and attributes excluded). The load average is printed: on a shared machine the wall
# time grows with it, the CPU time much less.
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=build/release
repeat=5
other=""
while [ $# -gt 0 ]; do
  case "$1" in
    --repeat) repeat=$2; shift 2 ;;
    --against) other=$2; shift 2 ;;
    -h|--help) sed -n '2,11p' "$0"; exit 0 ;;
    *) build=$1; shift ;;
  esac
done
exe=$(cd "$build" && pwd)/skewbridge
spec=$here/jobs/specs/pilot-study.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
set -a && source "$here/scripts/openmpi.env" && set +a  # Open MPI as root, more ranks than cores
echo "load $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
best_wall=1e9
best_cpu=1e9
for i in $(seq "$repeat"); do
  t0=$(date +%s.%N)
  /usr/bin/time -f "%U %S" -o "$work/time.txt" mpiexec -n 2 "$exe" sweep "$spec" \
    --out "$work/pilot.h5" --force --quiet
  t1=$(date +%s.%N)
  wall=$(awk -v a="$t0" -v b="$t1" 'BEGIN{printf "%.3f", b - a}')
  cpu=$(awk '{printf "%.2f", $1 + $2}' "$work/time.txt")
  echo "run $i: wall $wall s, CPU $cpu s"
  best_wall=$(awk -v x="$wall" -v y="$best_wall" 'BEGIN{print (x < y ? x : y)}')
  best_cpu=$(awk -v x="$cpu" -v y="$best_cpu" 'BEGIN{print (x < y ? x : y)}')
done
echo "best: wall $best_wall s, CPU $best_cpu s (2 ranks)"
if [ -n "$other" ]; then
  mpiexec -n 2 "$other" sweep "$spec" --out "$work/other.h5" --force --quiet
  /usr/bin/python3 "$here/scripts/bench/same_cube.py" "$work/other.h5" "$work/pilot.h5"
fi
