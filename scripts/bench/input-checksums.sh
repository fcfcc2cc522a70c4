#!/usr/bin/env bash
# The cost of the input checksums on a 62-record study: jobs/specs/pilot-records.toml over the
# 62-record synthetic suite written as files (`records synth`, 2.8 MB of .AT2), swept on 2
# ranks, every record file checksummed (SHA-256) once per rank when the specification is loaded.
#
#   bash scripts/bench/input-checksums.sh [BUILD_DIR] [--repeat N] [--against OTHER_SKEWBRIDGE]
#
# Prints the wall time and the CPU time of all ranks of each sweep (with --against, the other
# program's sweep alternates with this one's, so both see the same load), and the instructions
# (valgrind callgrind) of loading the specification alone (a run refused by --max-cells 1 just
# after the load) and of ChecksumFile in it. Under valgrind OpenSSL takes its portable SHA-256
# (valgrind hides the CPU's SHA extensions), so that count bounds the native one from above.
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=build/release
repeat=5
other=""
while [ $# -gt 0 ]; do
  case "$1" in
    --repeat) repeat=$2; shift 2 ;;
    --against) other=$2; shift 2 ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    *) build=$1; shift ;;
  esac
done
exe=$(cd "$build" && pwd)/skewbridge
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
"$exe" records synth --count 62 --seed 2011 --out synth62 > /dev/null
cp "$here/jobs/specs/pilot-records.toml" .
echo "$(du -cb synth62/*.AT2 | tail -1 | cut -f1) bytes of record files;" \
  "load $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
set -a && source "$here/scripts/openmpi.env" && set +a  # Open MPI as root, more ranks than cores
sweep() {  # sweep LABEL PROGRAM: one sweep on 2 ranks, one line of times
  local t0 t1
  t0=$(date +%s.%N)
  /usr/bin/time -f "%U %S" -o time.txt mpiexec -n 2 "$2" sweep pilot-records.toml \
    --out "$1.h5" --force --quiet 2> sweep.err
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" -v l="$1" '{printf "%s: wall %.3f s, CPU %.2f s\n", l, b - a, $1 + $2}' \
    time.txt
}
for i in $(seq "$repeat"); do
  sweep this "$exe"
  [ -z "$other" ] || sweep other "$other"
done
load() {  # load LABEL PROGRAM: instructions of loading the specification
  valgrind --tool=callgrind --callgrind-out-file="cg.$1" "$2" sweep pilot-records.toml \
    --out cg.h5 --max-cells 1 > /dev/null 2>&1 || true
  local total sums
  total=$(callgrind_annotate "cg.$1" 2> /dev/null | awk '/PROGRAM TOTALS/ {print $1}')
  sums=$(callgrind_annotate --inclusive=yes "cg.$1" 2> /dev/null |
    awk '/jobs::ChecksumFile/ && !n++ {print $1}')
  echo "$1: loading the specification ${total} instructions, ChecksumFile ${sums:-0}"
}
load this "$exe"
[ -z "$other" ] || load other "$other"
if [ -n "$other" ]; then
  /usr/bin/python3 "$here/scripts/bench/same_cube.py" other.h5 this.h5
fi
