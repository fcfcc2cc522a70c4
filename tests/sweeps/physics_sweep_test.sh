#!/usr/bin/env bash
# Real-physics sweeps through `skewbridge sweep`, one check per MODE:
#  ranks      a subsystem sweep (both pulses, skew angles, frequency ratios; cells with impacts
#             and rotation) gives byte-identical responses, status and statistics on 1, 2, 3 ranks;
#  kill       SIGTERM and, separately, SIGKILL mid-way through a record-driven sweep, then
#             --resume: the cube equals the uninterrupted one and checkpointed cells keep run 1;
#  selfsim    the same sweep at a_g = 0.05, 0.5, 5 g gives the same dimensionless cube to 1e-6
#             where rotations are small (the deviation elsewhere is printed);
#  badspecs   bad specifications exit with status 2 and one line naming the key, before any
#             output file exists;
#  records    a sweep over a 3-record synthetic set stores a_g = PGA and w_g = 2 pi / T_m as
#             `skewbridge records info --csv` reports them, L_e = a_g / w_g^2, delta = Pi_delta L_e.
# usage: physics_sweep_test.sh MODE SKEWBRIDGE MPIEXEC WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args mode exe mpiexec work -- "$@"
fresh_dir "$work"
test_name="physics_sweep_test $mode"
run() { local n=$1; shift; on_ranks "$n" "$exe" sweep "$@" --quiet; }
py() { /usr/bin/python3 - "$@"; }

# same_cube A B NAME: every per-cell dataset except the wall times, byte for byte.
same_cube() {
  py "$1" "$2" "$3" <<'PY' || fail "$1 and $2 differ"
import sys, h5py
a, b = (h5py.File(p, "r")["sweeps/" + sys.argv[3]] for p in sys.argv[1:3])
names = ["responses/" + r for r in a["responses"]] + ["status", "done", "stats/events", "stats/steps"]
for n in names:
    if a[n][()].tobytes() != b[n][()].tobytes():
        sys.exit(f"{n} differs")
PY
}

subsystem_spec() {  # subsystem_spec FILE N_W0 [extra fixed lines]
  cat > "$1" <<TOML
[sweep]
name = "physics"
family = "subsystem"
[axes]
pulse = ["cosine", "sine"]
a_deg = [10, 30, 50, 70]
w0_over_wg = {logspace = [0.2, 5.0, $2]}
[fixed]
eta0 = 2.0
Pi_delta = 1.0
delta_over_L = 0.002
${3:-}
TOML
}

case $mode in
ranks)
  subsystem_spec spec.toml 12
  for n in 1 2 3; do run "$n" spec.toml --out "r$n.h5"; done
  same_cube r1.h5 r2.h5 physics
  same_cube r1.h5 r3.h5 physics
  py r1.h5 <<'PY' || fail "the sweep does not exercise impacts and rotation"
import sys, h5py, numpy as np
g = h5py.File(sys.argv[1], "r")["sweeps/physics"]
assert np.all(g["status"][()] == 0), "failed cells"
imp, th = g["responses/impacts"][()], g["responses/theta_m"][()]
print(f"{imp.size} cells, {int((imp > 0).sum())} with impacts, {int((th > 1e-6).sum())} with theta_m > 1e-6 rad")
assert (imp > 0).sum() >= imp.size // 4 and (th > 1e-6).sum() >= imp.size // 4
PY
  ;;
kill)
  # Long synthetic records (600 s) make each cell cost some milliseconds even with the closed-form
  # free flow; interrupt_at_checkpoint stops the sweep of 96 cells at its first checkpoint.
  "$exe" records synth --count 2 --seed 5 --duration-s 600 --out set >/dev/null
  cat > spec.toml <<'TOML'
[sweep]
name = "physics"
family = "subsystem"
[records]
set = "set/set.toml"
[axes]
record = ["synth-5-000", "synth-5-001"]
a_deg = [20, 45]
w0_over_wg = {logspace = [0.3, 3.0, 24]}
[fixed]
eta0 = 2.0
Pi_delta = 1.0
delta_over_L = 0.002
TOML
  cells=96
  run 2 spec.toml --out ref.h5
  checkpointed() {  # cells marked done in a partial file, all of them computed by run 1
    py "$1" <<'PY'
import sys, h5py, numpy as np
g = h5py.File(sys.argv[1], "r")["sweeps/physics"]
d, r = g["done"][()], g["stats/run"][()]
assert g.attrs["complete"] == 0 and np.all(r[d == 1] == 1)
print(int(d.sum()))
PY
  }
  for sig in TERM KILL; do
    out=$sig.h5
    "$mpiexec" -n 2 --oversubscribe "$exe" sweep spec.toml --quiet --out "$out" \
      --checkpoint-cells 1 &
    pid=$!
    # KILL: mpiexec and both ranks at once, a crash; TERM: mpiexec forwards it to the ranks.
    interrupt_at_checkpoint "$pid" "$out.partial" "$sig"
    status=0
    wait "$pid" || status=$?
    [ "$status" -ne 0 ] || fail "$sig: the interrupted sweep exited with status 0"
    [ ! -f "$out" ] || fail "$sig: $out exists although the sweep was interrupted"
    before=$(checkpointed "$out.partial") || fail "$sig: the partial file is not readable"
    [ "$before" -lt "$cells" ] || fail "$sig: killed too late ($before cells done)"
    run 2 spec.toml --out "$out" --resume || fail "$sig: --resume failed"
    same_cube ref.h5 "$out" physics
    py "$out" "$before" "$cells" <<'PY' || fail "$sig: checkpointed cells were recomputed, or others were not"
import sys, h5py
g = h5py.File(sys.argv[1], "r")["sweeps/physics"]
before, cells = int(sys.argv[2]), int(sys.argv[3])
r = g["stats/run"][()]
assert g.attrs["complete"] == 1 and g.attrs["runs"] == 2
assert int((r == 1).sum()) == before and int((r == 2).sum()) == cells - before
PY
    echo "$sig: exit status $status, $before/$cells cells checkpointed; the rest computed on resume; cube identical"
  done
  ;;
selfsim)
  for a in 0.05 0.5 5; do
    subsystem_spec "s$a.toml" 12 "a_g_g = $a"
    run 2 "s$a.toml" --out "s$a.h5"
  done
  py s0.05.h5 s0.5.h5 s5.h5 <<'PY' || fail "dimensionless cubes differ where rotations are small"
import sys, h5py, numpy as np
cubes = [h5py.File(p, "r")["sweeps/physics"] for p in sys.argv[1:]]
for c in cubes:
    assert np.all(c["status"][()] == 0), "failed cells"
theta = np.max([c["responses/theta_m"][()] for c in cubes], axis=0)
impacts = cubes[0]["responses/impacts"][()]
assert np.all([np.array_equal(c["responses/impacts"][()], impacts) for c in cubes])
dev = np.zeros(theta.shape)
for name in ["x_norm", "y_norm", "theta_norm"]:
    v = np.array([c["responses/" + name][()] for c in cubes])
    scale = np.maximum(np.max(np.abs(v), axis=0), 1e-9 * cubes[0]["responses/x_norm"][()])
    dev = np.maximum(dev, np.max(np.abs(v - v[1]), axis=0) / scale)
small = theta <= 1e-3
print(f"{int(small.sum())}/{theta.size} cells with theta_m <= 1e-3 rad at every intensity "
      f"({int((impacts[small] > 0).sum())} of them with impacts): max relative deviation {dev[small].max():.2e}")
for lo, hi in [(1e-3, 1e-2), (1e-2, 1e-1), (1e-1, np.inf)]:
    sel = (theta > lo) & (theta <= hi)
    if sel.any():
        print(f"  {lo:g} < theta_m <= {hi:g} rad: {int(sel.sum())} cells, max relative deviation {dev[sel].max():.2e}")
assert (impacts[small] > 0).sum() >= 3, "too few small-rotation cells with impacts"
assert (impacts > 0).sum() >= theta.size // 4, "too few cells with impacts"
assert dev[small].max() <= 1e-6
PY
  ;;
badspecs)
  "$exe" records synth --count 1 --seed 3 --duration-s 5 --out set >/dev/null
  expect_refused() {  # expect_refused NAME KEY: spec NAME.toml must fail naming KEY
    local status=0
    "$exe" sweep "$1.toml" --out "$1.h5" --quiet 2>"$1.err" || status=$?
    [ "$status" -eq 2 ] || fail "$1: exit status $status, expected 2"
    [ "$(wc -l <"$1.err")" -eq 1 ] || fail "$1: expected one line, got: $(cat "$1.err")"
    grep -q -- "$2" "$1.err" || fail "$1: the message does not name $2: $(cat "$1.err")"
    [ ! -e "$1.h5" ] && [ ! -e "$1.h5.partial" ] || fail "$1: an output file was created"
    echo "$1: $(cat "$1.err")"
  }
  head='[sweep]
name = "bad"'
  printf '%s\nfamily = "subsystem"\n[axes]\nskew = [10, 20]\n[fixed]\neta0 = 1.0\n' "$head" >unknown-axis.toml
  expect_refused unknown-axis "axes.skew"
  printf '%s\nfamily = "subsystem"\n[axes]\na_deg = []\n[fixed]\neta0 = 1.0\n' "$head" >empty-axis.toml
  expect_refused empty-axis "axes.a_deg"
  printf '%s\nfamily = "subsystem"\n[axes]\na_deg = [30, 0]\n[fixed]\neta0 = 1.0\n' "$head" >eta0-zero-skew.toml
  expect_refused eta0-zero-skew "eta0"
  printf '%s\nfamily = "subsystem"\n[axes]\nPi_delta = [1.0, -0.5]\n[fixed]\neta0 = 1.0\n' "$head" >negative-pi-delta.toml
  expect_refused negative-pi-delta "Pi_delta"
  printf '%s\nfamily = "pilot-bridge"\n[records]\nset = "none/set.toml"\n[axes]\nrecord = ["synth-3-000"]\n' "$head" >missing-set.toml
  expect_refused missing-set "records.set"
  printf '%s\nfamily = "pilot-bridge"\n[records]\nset = "set/set.toml"\n[axes]\nrecord = ["synth-3-000", "KALA-T"]\n' "$head" >unknown-record.toml
  expect_refused unknown-record "record"
  grep -q "KALA-T" unknown-record.err || fail "unknown-record: the message does not name the label"
  # The pilot bridge takes a_deg and eta0 (spectra::PilotBridgeDeck), not its plan's W/L.
  printf '%s\nfamily = "pilot-bridge"\n[axes]\nw0_over_wg = [0.5, 1.0]\n[fixed]\nW_over_L = 0.3\n' "$head" >pilot-width.toml
  expect_refused pilot-width "W_over_L"
  printf '%s\nfamily = "pilot-bridge"\n[axes]\neta0 = [1.2, 2.0]\n[fixed]\na_deg = 0.0\n' "$head" >pilot-eta0.toml
  expect_refused pilot-eta0 "eta0"
  # Under records the pilot bridge's w0x/w_g is an output, and a_g is each record's PGA.
  printf '%s\nfamily = "pilot-bridge"\n[records]\nset = "set/set.toml"\n[axes]\nrecord = ["synth-3-000"]\nw0_over_wg = [0.5, 1.0]\n' "$head" >pilot-record-w0.toml
  expect_refused pilot-record-w0 "w0_over_wg"
  printf '%s\nfamily = "subsystem"\n[records]\nset = "set/set.toml"\n[axes]\nrecord = ["synth-3-000"]\n[fixed]\na_g_g = 0.3\n' "$head" >record-a-g.toml
  expect_refused record-a-g "a_g_g"
  ;;
records)
  "$exe" records synth --count 3 --seed 11 --duration-s 10 --out set >/dev/null
  "$exe" records info --csv set/set.toml >info.csv
  cat > spec.toml <<'TOML'
[sweep]
name = "physics"
family = "pilot-bridge"
[records]
set = "set/set.toml"
[axes]
record = ["synth-11-002", "synth-11-000", "synth-11-001"]
Pi_delta = [0.5, 2.0]
TOML
  run 2 spec.toml --out rec.h5
  py rec.h5 info.csv <<'PY' || fail "stored excitation scales differ from records info"
import sys, csv, math, h5py, numpy as np
g = h5py.File(sys.argv[1], "r")["sweeps/physics"]
info = {row["label"]: row for row in csv.DictReader(open(sys.argv[2]))}
labels = [s.decode() if isinstance(s, bytes) else s for s in g["axes/record"][()]]
pi = g["axes/Pi_delta"][()]
assert list(g.attrs["axis_order"]) == ["record", "Pi_delta"], g.attrs["axis_order"]
assert np.all(g["status"][()] == 0)
r = {n: g["responses/" + n][()] for n in ["a_g", "w_g", "L_e", "delta", "impacts", "theta_m"]}
def close(a, b, tol=1e-12):
    return abs(a - b) <= tol * abs(b)
for i, label in enumerate(labels):
    row = info[label]
    pga = float(row["pga_g"]) * 9.80665
    wg = 2 * math.pi / float(row["tm_s"])
    for j, p in enumerate(pi):
        a, w, le, d = (r[n][i, j] for n in ["a_g", "w_g", "L_e", "delta"])
        assert close(a, pga), (label, a, pga)
        assert close(w, wg) and close(w, float(row["omega_g_radps"])), (label, w, wg)
        assert close(le, a / w**2), (label, le, a / w**2)
        assert close(d, p * a / w**2), (label, d, p * a / w**2)
    print(f"{label}: a_g = {pga:.4f} m/s^2, w_g = {wg:.3f} rad/s, impacts {r['impacts'][i].tolist()}")
PY
  ;;
*) fail "unknown mode" ;;
esac
echo "physics_sweep_test $mode: ok"
