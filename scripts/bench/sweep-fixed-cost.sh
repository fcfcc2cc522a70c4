#!/usr/bin/env bash
# A sweep's fixed cost: one cell of the fragility study of fragility-floor.sh (one synthetic
# record, one Sa(T1) stripe, one skew, one seat width of the pilot bridge, its limit states),
# run without mpiexec, with `mpiexec -n 1` and with `mpiexec -n 2`.
#
#   bash scripts/bench/sweep-fixed-cost.sh [BUILD_DIR] [--repeat N] [--against OTHER_SKEWBRIDGE]
#
# Prints, best of N (default 5) for each way of starting it, the wall time of the whole command,
# then the same runs under `strace -f --seccomp-bpf -ttt -T`, split into phases by the first
# system call of each:
#   start     from the command's start to the sweep specification's first opening (Open MPI's
#             start: with mpiexec its launcher and daemon, without it the singleton's daemon);
#   inputs    from there to the checkpoint file's creation (specification, model file, records,
#             checksums, the evaluator's checks of every cell);
#   cells     from there to the final cube's rename (the cell, the fits, the final cube);
#   end       from there to the command's end (Open MPI's finalize, the daemon's exit);
# and the time spent in fsync (the checkpoint file's creation, the final cube's write).
# strace slows the system calls, so the phases add up to more than the plain wall time; they
# show where the time goes, the plain runs what it costs. With --against, the other program
# runs the same, alternating, so both see the same load. When mpicc is found, a bare MPI program
# (MPI_Init, then MPI_Finalize, nothing else) runs the same three ways beside them: its wall
# time is what Open MPI's start and end cost on this machine, whatever the program.
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=build/release
repeat=5
other=""
while [ $# -gt 0 ]; do
  case "$1" in
    --repeat) repeat=$2; shift 2 ;;
    --against) other=$(cd "$(dirname "$2")" && pwd)/$(basename "$2"); shift 2 ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) build=$1; shift ;;
  esac
done
exe=$(cd "$build" && pwd)/skewbridge
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
"$exe" records synth --count 1 --seed 2011 --out synth1 > /dev/null
cp "$here/docs/examples/pilot-bridge.toml" "$here/docs/examples/pilot-signal.txt" .
cat > one.toml <<'TOML'
[sweep]
name = "fixed-cost"
family = "model-file"
model = "pilot-bridge.toml"

[records]
set = "synth1/set.toml"
scale_to = { measure = "Sa", period = "T1", xi = 0.05 }
max_scale = 10.0

[axes]
record = "*"
im_g = [1.0]
a_deg = [30]
seat_over_L = [0.001]

[limit_states]
unseating = true
rotation = {above_rad = 0.0005}
joint_closing = true
TOML
set -a && source "$here/scripts/openmpi.env" && set +a  # Open MPI as root, more ranks than cores

bare=""
if command -v mpicc > /dev/null; then
  printf '#include <mpi.h>\nint main(int c, char** v) { MPI_Init(&c, &v); MPI_Finalize(); return 0; }\n' > bare.c
  mpicc -O2 bare.c -o bare && bare=$work/bare
fi
run_bare() {  # run_bare MODE: the bare MPI program once; prints its wall time [s]
  local t0 t1 cmd
  case "$1" in
    plain) cmd=("$bare") ;;
    n1) cmd=(mpiexec -n 1 "$bare") ;;
    n2) cmd=(mpiexec -n 2 "$bare") ;;
  esac
  t0=$(date +%s.%N)
  "${cmd[@]}" > /dev/null 2>&1 || { echo "the bare MPI program failed" >&2; return 1; }
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.3f\n", b - a}'
}

run() {  # run MODE PROGRAM [strace]: one 1-cell sweep; prints its wall time [s]
  local mode=$1 program=$2 trace=${3:-} t0 t1 cmd
  case "$mode" in
    plain) cmd=("$program") ;;
    n1) cmd=(mpiexec -n 1 "$program") ;;
    n2) cmd=(mpiexec -n 2 "$program") ;;
  esac
  if [ -n "$trace" ]; then
    cmd=(strace -f --seccomp-bpf -ttt -T -qq -o "$trace"
      -e trace=execve,openat,rename,fsync,exit_group "${cmd[@]}")
  fi
  t0=$(date +%s.%N)
  "${cmd[@]}" sweep one.toml --out one.h5 --force --quiet > run.out 2> run.err ||
    { cat run.err >&2; return 1; }
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.3f\n", b - a}'
}
phases() {  # phases TRACE: start inputs cells end fsync [s] from one strace -f -ttt -T log
  awk '
    NR == 1 { t0 = $2 }
    /openat\(.*"one\.toml"/ && !spec { spec = $2 }
    /openat\(.*one\.h5\.partial.*O_CREAT/ && !ckpt { ckpt = $2 }
    /rename\(.*one\.h5"/ { fin = $2 }
    /fsync\(/ { d = $NF; gsub(/[<>]/, "", d); sync += d }
    { last = $2 }
    END { printf "%.3f %.3f %.3f %.3f %.4f\n", spec - t0, ckpt - spec, fin - ckpt, last - fin, sync }' "$1"
}
labels="this"
[ -z "$other" ] || labels="other this"
echo "load $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
for mode in plain n1 n2; do
  for label in $labels; do : > "$label.$mode.wall"; : > "$label.$mode.phases"; done
  : > "bare.$mode.wall"
  for i in $(seq "$repeat"); do
    [ -z "$bare" ] || run_bare "$mode" >> "bare.$mode.wall"
    for label in $labels; do
      program=$exe
      [ "$label" = this ] || program=$other
      run "$mode" "$program" >> "$label.$mode.wall"
      run "$mode" "$program" trace.log > /dev/null
      phases trace.log >> "$label.$mode.phases"
    done
  done
done
for label in $labels; do
  name="this tree ($("$exe" version 2> /dev/null | head -1))"
  [ "$label" = this ] || name="$other"
  echo "$name, best of $repeat (wall [s]; under strace: start, inputs, cells, end, and the" \
    "fsync calls within them [s], the best of each):"
  for mode in plain n1 n2; do
    case "$mode" in plain) m="without mpiexec" ;; n1) m="mpiexec -n 1  " ;; n2) m="mpiexec -n 2  " ;; esac
    w=$(sort -g "$label.$mode.wall" | head -1)
    p=$(for k in 1 2 3 4 5; do cut -d' ' -f$k "$label.$mode.phases" | sort -g | head -1; done | paste -sd' ')
    echo "  $m  wall $w   phases $p"
  done
done
if [ -n "$bare" ]; then
  echo "a bare MPI program (MPI_Init, MPI_Finalize: Open MPI's start and end alone), best of $repeat:"
  for mode in plain n1 n2; do
    case "$mode" in plain) m="without mpiexec" ;; n1) m="mpiexec -n 1  " ;; n2) m="mpiexec -n 2  " ;; esac
    echo "  $m  wall $(sort -g "bare.$mode.wall" | head -1)"
  done
fi
echo "load at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
