#!/usr/bin/env bash
# A 2-cell sweep with `method` as an axis: the cube stores the method axis with both labels and
# a cell per method, and the time-stepping cell's dimensionless maxima are within 1 % of the
# event-driven cell's (the canonical subsystem point w0/w_g = 0.5, Pi_delta = 0.5, a = 30 deg,
# eta0 = 2; the Moreau-Jean step is 1e-4 of the pulse period); the cube stores the policy of each
# integrator its cells ran (both here; a cube of time-stepping cells only time_stepping_policy).
# usage: sweep_method_test.sh SKEWBRIDGE MPIEXEC
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec -- "$@"
temp_dir

cat >"$work/spec.toml" <<'TOML'
[sweep]
name = "methods"
family = "subsystem"
[axes]
method = ["event-driven", "time-stepping"]
[fixed]
w0_over_wg = 0.5
Pi_delta = 0.5
a_deg = 30.0
eta0 = 2.0
delta_over_L = 0.002
TOML
on_ranks 1 "$exe" sweep "$work/spec.toml" --out "$work/cube.h5" --quiet \
  >"$work/out" 2>&1 || fail "sweep: exit $? ($(cat "$work/out"))"
/usr/bin/python3 - "$work/cube.h5" <<'PY' || fail "cube check"
import sys, h5py
g = h5py.File(sys.argv[1], "r")["sweeps/methods"]
axis = [m.decode() if isinstance(m, bytes) else m for m in g["axes/method"][()]]
assert axis == ["event-driven", "time-stepping"], axis
assert list(g["status"][()]) == [0, 0], g["status"][()]
assert int(g["responses/impacts"][0]) > 0, "no impact: not a pounding case"
for r in ("x_norm", "y_norm", "theta_norm"):
    ed, ts = g["responses/" + r][()]
    assert abs(ts - ed) <= 0.01 * abs(ed), f"{r}: time-stepping {ts} vs event-driven {ed}"
steps = g["stats/steps"][()]
assert steps[0] != steps[1], "both cells ran the same integrator"
# Both integrators ran: the cube stores both policies.
assert g["event_policy"].attrs["zeno_ratio"] == 0.9, dict(g["event_policy"].attrs)
ts = g["time_stepping_policy"].attrs
assert ts["velocity_tolerance"] == 1e-9 and ts["active_set_lookahead"] == 0.5, dict(ts)
PY
sed 's/^method = .*/method = ["time-stepping"]/' "$work/spec.toml" >"$work/ts.toml"
on_ranks 1 "$exe" sweep "$work/ts.toml" --out "$work/ts.h5" --quiet \
  >"$work/out" 2>&1 || fail "time-stepping sweep: exit $? ($(cat "$work/out"))"
/usr/bin/python3 - "$work/ts.h5" <<'PY' || fail "time-stepping cube's policy"
import sys, h5py
g = h5py.File(sys.argv[1], "r")["sweeps/methods"]
assert "event_policy" not in g, "a cube of time-stepping cells stores the event-driven policy"
assert g["time_stepping_policy"].attrs["normal_compliance"] == 1e-9
PY
echo "ok"
