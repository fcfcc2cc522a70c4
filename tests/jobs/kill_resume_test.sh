#!/usr/bin/env bash
# Kill and resume, end to end, through the `sweep` entry point with the test evaluator:
#  1. the cube is identical (h5diff, exact) on 1, 2 and 3 ranks;
#  2. SIGTERM mid-way: exit status non-zero, FILE.partial readable and resumable;
#  3. SIGKILL of every process mid-way (a crash): FILE.partial still readable;
#  after each, --resume completes a cube identical to the uninterrupted one, and the cells
#  that were checkpointed before the kill keep run = 1 (they were not recomputed).
# usage: kill_resume_test.sh SWEEP_DRIVER MPIEXEC WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args driver mpiexec work -- "$@"
fresh_dir "$work"
cat > spec.toml <<'TOML'
[sweep]
name = "kill"
family = "subsystem"
[axes]
pulse = ["cosine", "sine"]
a_deg = [10, 25, 40, 55]
w0_over_wg = {linspace = [0.25, 4.0, 30]}
[fixed]
eta0 = 2.0
TOML
cells=240
run() { local n=$1; shift; on_ranks "$n" "$driver" spec.toml --quiet "$@"; }
same_cube() {  # same_cube A B: responses, status and solver statistics identical
  for ds in responses/x_peak responses/theta_peak responses/cell_echo status done stats/events \
            stats/steps; do
    h5diff "$1" "$2" "/sweeps/kill/$ds" "/sweeps/kill/$ds" >/dev/null ||
      fail "$1 and $2 differ in $ds"
  done
}
py() { /usr/bin/python3 -c "import h5py,numpy as np,sys; f=h5py.File(sys.argv[1],'r'); g=f['sweeps/kill']; $2" "$1"; }

echo "== 1, 2, 3 ranks"
for n in 1 2 3; do run "$n" --out "ref$n.h5" --work 200; done
same_cube ref1.h5 ref2.h5
same_cube ref1.h5 ref3.h5
echo "identical on 1, 2, 3 ranks"

kill_and_resume() {  # kill_and_resume SIGNAL NAME
  local sig=$1 out=$2.h5
  "$mpiexec" -n 2 --oversubscribe "$driver" spec.toml --quiet --out "$out" --work 200 \
    --sleep-ms 30 --checkpoint-seconds 0.1 &
  local pid=$!
  local done_cells=0
  for _ in $(seq 1 300); do
    sleep 0.05
    if [ -f "$out.partial" ]; then
      done_cells=$(py "$out.partial" "print(int(g['done'][()].sum()))" 2>/dev/null || echo 0)
      [ "$done_cells" -ge 20 ] && break
    fi
  done
  [ "$done_cells" -ge 20 ] || fail "$sig: no checkpointed cells to kill after"
  if [ "$sig" = KILL ]; then
    # A crash: mpiexec and every rank (Open MPI puts ranks in their own process groups) die
    # at the same instant, with no chance to checkpoint.
    kill -KILL "$pid" $(pgrep -P "$pid") 2>/dev/null || true
  else
    # As Ctrl-C or a batch system would: mpiexec forwards the signal to the ranks.
    kill "-$sig" "$pid"
  fi
  local status=0
  wait "$pid" || status=$?
  [ "$status" -ne 0 ] || fail "$sig: the interrupted sweep exited with status 0"
  [ ! -f "$out" ] || fail "$sig: $out exists although the sweep was interrupted"
  local before
  before=$(py "$out.partial" "d=g['done'][()]; r=g['stats/run'][()]; assert g.attrs['complete']==0; assert np.all(r[d==1]==1); print(int(d.sum()))") ||
    fail "$sig: $out.partial is not readable after the kill"
  [ "$before" -lt "$cells" ] || fail "$sig: killed too late ($before cells done)"
  echo "$sig: exit status $status, $before/$cells cells checkpointed"
  run 2 --out "$out" --resume --work 200 || fail "$sig: --resume failed"
  same_cube ref1.h5 "$out"
  py "$out" "d=g['stats/run'][()]; assert g.attrs['complete']==1; assert int((d==1).sum())==$before, (int((d==1).sum()), $before); assert int((d==2).sum())==$cells-$before; assert g.attrs['runs']==2" ||
    fail "$sig: checkpointed cells were recomputed, or others were not"
  echo "$sig: resumed; $((cells - before)) cells computed by run 2, cube identical"
}
kill_and_resume TERM term
kill_and_resume KILL crash
echo "kill_resume_test: ok"
