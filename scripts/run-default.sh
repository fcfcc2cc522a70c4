#!/usr/bin/env bash
# The main job on its built-in default: builds the release preset, runs the default spectrum
# sweep (jobs/specs/default.toml) on 2 MPI ranks into out/default.h5, summarises the cube and
# draws its figures (out/report/: PNG spectra and summary.md).
# Re-running resumes an unfinished cube and recomputes a finished one.
set -euo pipefail
cd "$(dirname "$0")/.."
set -a && source scripts/openmpi.env && set +a  # Open MPI as root, more ranks than cores
export CMAKE_BUILD_PARALLEL_LEVEL=$(nproc)

cmake --preset release >/dev/null
cmake --build --preset release --target skewbridge

mkdir -p out
cube=out/default.h5
resume=()
if [ -f "$cube" ]; then
  if build/release/skewbridge inspect "$cube" | grep -q '%), complete,'; then
    rm -f "$cube"
  else
    resume=(--resume)
  fi
fi
mpiexec -n 2 --oversubscribe build/release/skewbridge sweep jobs/specs/default.toml \
  --out "$cube" "${resume[@]}"
build/release/skewbridge inspect "$cube"
scripts/report "$cube" --out out/report
echo "cube written to $(pwd)/$cube; figures and summary in $(pwd)/out/report"
