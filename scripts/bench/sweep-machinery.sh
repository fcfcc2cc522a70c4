#!/usr/bin/env bash
# Measures the sweep machinery with the test evaluator (not run by ctest; timings vary):
#  - cells/s on 1 and 2 ranks at about 0.5 ms of arithmetic per cell, parallel efficiency;
#  - the same with a 0.5 ms sleep per cell (scheduler efficiency without CPU contention);
#  - overhead per cell with trivial cells on 4 oversubscribed ranks (1e6 cells);
#  - final and checkpoint file size per million cells.
# usage: scripts/bench/sweep-machinery.sh BUILD_DIR [WORK_DIR]   (BUILD_DIR e.g. build/release)
set -euo pipefail
build=$(cd "$1" && pwd)
work=${2:-$(mktemp -d)}
mkdir -p "$work"
driver=$build/tests/jobs/sweep_test_driver
root=$(cd "$(dirname "$0")/../.." && pwd)
set -a && source "$root/scripts/openmpi.env" && set +a  # Open MPI as root, more ranks than cores
cd "$work"
grid() {  # grid FILE N_PI_DELTA N_W0
  cat > "$1" <<TOML
[sweep]
name = "measure"
family = "subsystem"
[axes]
pulse = ["cosine", "sine"]
a_deg = {linspace = [5, 60, 10]}
Pi_delta = {linspace = [0, 2, $2]}
w0_over_wg = {logspace = [0.1, 10.0, $3]}
[fixed]
eta0 = 1.5
TOML
}
rate() { grep -o "[0-9.]* cells/s" | head -1 | cut -d' ' -f1; }
sweep() { local n=$1; shift; mpiexec -n "$n" --oversubscribe "$driver" "$@" --force --quiet 2>&1; }
grid small.toml 1 100   # 2000 cells
grid big.toml 100 500   # 1 000 000 cells
echo "load: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
r1=$(sweep 1 small.toml --out a1.h5 --work 16500 | rate)
r2=$(sweep 2 small.toml --out a2.h5 --work 16500 | rate)
echo "arithmetic ~0.5 ms/cell: 1 rank $r1 cells/s, 2 ranks $r2 cells/s, efficiency $(awk "BEGIN{printf \"%.3f\", $r2 / (2 * $r1)}")"
s1=$(sweep 1 small.toml --out b1.h5 --work 0 --sleep-ms 0.5 | rate)
s2=$(sweep 2 small.toml --out b2.h5 --work 0 --sleep-ms 0.5 | rate)
echo "sleep 0.5 ms/cell: 1 rank $s1 cells/s, 2 ranks $s2 cells/s, efficiency $(awk "BEGIN{printf \"%.3f\", $s2 / (2 * $s1)}")"
t4=$(sweep 4 big.toml --out c4.h5 --work 0 | rate)
echo "trivial cells, 4 ranks: $t4 cells/s = $(awk "BEGIN{printf \"%.2f\", 1000000 / $t4}") us per cell through rank 0"
echo "final cube, 1e6 cells: $(stat -c %s c4.h5) bytes"
"$driver" big.toml --out d.h5 --quiet --work 0 --sleep-ms 0.01 & pid=$!
sleep 2; kill -TERM "$pid"; wait "$pid" || true
echo "checkpoint file, 1e6 cells: $(stat -c %s d.h5.partial) bytes (allocated at creation)"
