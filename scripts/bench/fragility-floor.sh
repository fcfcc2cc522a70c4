#!/usr/bin/env bash
# The fragility study at the size engineers run, on 2 ranks, beside the same study at a baseline
# commit: 100 synthetic records (`records synth --count 100 --seed 2011`, written as files) x 20
# stripes of Sa(T1, 5 %) x 3 seat widths x 5 skew angles = 30 000 record cells of the pilot
# bridge (docs/examples/pilot-bridge.toml), with the limit states of
# jobs/specs/real/pilot-fragility.toml (unseating, rotation above 0.5 mrad, joint closing).
#
#   bash scripts/bench/fragility-floor.sh [BUILD_DIR] [--repeat N] [--baseline COMMIT]
#                                         [--baseline-exe PROGRAM] [--no-baseline] [--keep DIR]
#                                         [--clean]
#
# BUILD_DIR (default build/release) holds this tree's skewbridge. The baseline (default
# 350c79e) is built in a git worktree under /tmp (release preset, ccache, the skewbridge target
# only; the same path every time, so that ccache finds its objects and a second run builds
# nothing); --clean removes that worktree at the end. --baseline-exe takes a skewbridge already
# built at the baseline instead (its `version` must name the baseline commit). The two programs alternate, so that both
# see the same load; each runs the study N times (default 3) and the best is printed: the cells' time (the sweep's own
# "computed ... in S s", from the first claimed cell to the last cell gathered) and the wall
# time of the whole mpiexec command (start, input checksums, cells, fits and bootstraps, final
# cube). The load (uptime's 1, 5 and 15 minute averages) is printed with every run. At the end
# scripts/bench/same_cube.py compares the two cubes dataset by dataset (the wall-time columns
# apart), and --keep DIR keeps them there.
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=build/release
repeat=3
baseline=350c79e
base_exe=""
keep=""
clean=0
while [ $# -gt 0 ]; do
  case "$1" in
    --repeat) repeat=$2; shift 2 ;;
    --baseline) baseline=$2; shift 2 ;;
    --baseline-exe) base_exe=$(cd "$(dirname "$2")" && pwd)/$(basename "$2"); shift 2 ;;
    --no-baseline) baseline=""; shift ;;
    --keep) keep=$2; shift 2 ;;
    --clean) clean=1; shift ;;
    -h|--help) sed -n '2,24p' "$0"; exit 0 ;;
    *) build=$1; shift ;;
  esac
done
exe=$(cd "$build" && pwd)/skewbridge
work=$(mktemp -d)
base_tree=""
cleanup() {
  rm -rf "$work"
  if [ "$clean" = 1 ] && [ -n "$base_tree" ]; then
    git -C "$here" worktree remove --force "$base_tree" 2> /dev/null || true
  fi
}
trap cleanup EXIT
load() { cut -d' ' -f1-3 /proc/loadavg; }

if [ -n "$baseline" ] && [ -n "$base_exe" ]; then
  sha=$(git -C "$here" rev-parse --short=7 "$baseline^{commit}")
  "$base_exe" version | grep -q "($sha" ||
    { echo "$base_exe is not built at $sha: $("$base_exe" version | head -1)" >&2; exit 1; }
elif [ -n "$baseline" ]; then
  sha=$(git -C "$here" rev-parse --short=7 "$baseline^{commit}")
  base_tree=/tmp/skewbridge-fragility-floor-$sha
  if [ "$(git -C "$base_tree" rev-parse --short=7 HEAD 2> /dev/null)" != "$sha" ]; then
    git -C "$here" worktree remove --force "$base_tree" 2> /dev/null || rm -rf "$base_tree"
    git -C "$here" worktree add --detach "$base_tree" "$sha" > /dev/null 2>&1
  fi
  echo "building $sha in $base_tree (release preset, ccache; load $(load))"
  (cd "$base_tree" &&
    CMAKE_CXX_COMPILER_LAUNCHER=ccache CMAKE_C_COMPILER_LAUNCHER=ccache \
      cmake --preset release > "$work/base-cmake.log" 2>&1 &&
    cmake --build build/release --target skewbridge > "$work/base-build.log" 2>&1) ||
    { tail -20 "$work"/base-*.log; exit 1; }
  base_exe=$base_tree/build/release/skewbridge
fi

cd "$work"
"$exe" records synth --count 100 --seed 2011 --out synth100 > /dev/null
cp "$here/docs/examples/pilot-bridge.toml" "$here/docs/examples/pilot-signal.txt" .
cat > floor.toml <<'TOML'
[sweep]
name = "fragility-floor"
family = "model-file"
model = "pilot-bridge.toml"
description = "pilot bridge, 100 synthetic records x 20 Sa(T1) stripes x 3 seat widths x 5 skews"

[records]
set = "synth100/set.toml"
scale_to = { measure = "Sa", period = "T1", xi = 0.05 }
max_scale = 10.0

[axes]
record = "*"
im_g = {logspace = [0.2, 4.0, 20]}
a_deg = [0, 15, 30, 45, 60]
seat_over_L = [0.0005, 0.001, 0.002]

[limit_states]
unseating = true
rotation = {above_rad = 0.0005}
joint_closing = true
TOML
set -a && source "$here/scripts/openmpi.env" && set +a  # Open MPI as root, more ranks than cores
echo "study: 100 records x 20 stripes x 5 skews x 3 seat widths = 30000 cells, 2 ranks;" \
  "$(nproc) cores shared with other users"

sweep() {  # sweep LABEL PROGRAM: one study on 2 ranks; prints "cells_s wall_s"
  local t0 t1 cells
  t0=$(date +%s.%N)
  mpiexec -n 2 "$2" sweep floor.toml --out "$1.h5" --force --quiet > "$1.out" 2> "$1.err" ||
    { cat "$1.err" >&2; return 1; }
  t1=$(date +%s.%N)
  cells=$(grep -o 'computed on [0-9]* ranks in [0-9.]* s' "$1.err" | awk '{print $(NF-1)}')
  awk -v a="$t0" -v b="$t1" -v c="$cells" 'BEGIN {printf "%.3f %.3f\n", c, b - a}'
}
best() {  # best FILE: the smallest cells and wall times over the lines of FILE
  sort -g -k1,1 "$1" | head -1 | cut -d' ' -f1
  sort -g -k2,2 "$1" | head -1 | cut -d' ' -f2
}
labels="this"
[ -z "$baseline" ] || labels="base this"
for i in $(seq "$repeat"); do
  for label in $labels; do
    program=$exe
    [ "$label" = this ] || program=$base_exe
    l=$(load)
    r=$(sweep "$label" "$program")
    echo "$r" >> "$label.times"
    echo "run $i $label: cells $(echo "$r" | cut -d' ' -f1) s, whole command $(echo "$r" | cut -d' ' -f2) s (load $l)"
  done
done
for label in $labels; do
  name=$label
  [ "$label" = this ] && name="this tree ($(git -C "$here" rev-parse --short=7 HEAD))"
  [ "$label" = base ] && name="baseline $sha"
  read -r -d '' c w < <(best "$label.times") || true
  echo "best of $repeat, $name: cells $c s, whole command $w s ($(awk -v c="$c" 'BEGIN {printf "%.0f", 30000 / c}') cells/s)"
done
echo "load at the end: $(load)"
if [ -n "$baseline" ]; then
  /usr/bin/python3 "$here/scripts/bench/same_cube.py" base.h5 this.h5 || true
fi
if [ -n "$keep" ]; then
  mkdir -p "$keep"
  cp ./*.h5 "$keep"/
fi
