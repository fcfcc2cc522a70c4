#!/usr/bin/env bash
# A multi-span sweep through `skewbridge sweep` (spans 1-3 as an axis, a = 0 and 30 deg):
# byte-identical responses, status and statistics on 1 and 2 ranks; NaN exactly for the decks a
# cell does not have; at a = 0 no deck moves transversally or rotates [docs/theory.md §4 fact 3], so
# the unseating margin is the seat width minus max |x| exactly; the skewed cells pound and rotate
# at w0/w_g <= 1 and nothing pounds at w0/w_g = 2.
# usage: multispan_sweep_test.sh SKEWBRIDGE MPIEXEC WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec work -- "$@"
fresh_dir "$work"
cat > spec.toml <<'TOML'
[sweep]
name = "ms"
family = "multi-span"
[axes]
spans = [1, 2, 3]
a_deg = [0, 30]
w0_over_wg = [0.5, 1.0, 2.0]
[fixed]
W_over_L = 0.3
Pi_delta = 1.0
delta_over_L = 0.002
mu = 0.1
seat_over_L = 0.02
TOML
for n in 1 2; do on_ranks "$n" "$exe" sweep spec.toml --out "r$n.h5" --quiet; done
/usr/bin/python3 - r1.h5 r2.h5 <<'PY' || fail "cube check"
import sys, h5py, numpy as np
a, b = (h5py.File(p, "r")["sweeps/ms"] for p in sys.argv[1:3])
for n in ["responses/" + r for r in a["responses"]] + ["status", "done", "stats/events", "stats/steps"]:
    assert a[n][()].tobytes() == b[n][()].tobytes(), f"{n} differs between 1 and 2 ranks"
assert np.all(a["status"][()] == 0), "failed cells"
r = {k: a["responses/" + k][()] for k in a["responses"]}
spans = [1, 2, 3]
for i, n in enumerate(spans):
    for d in range(3):
        for name in ("x_norm", "y_norm", "theta_norm", "margin_norm"):
            v = r[f"{name}_d{d}"][i]
            assert np.all(np.isnan(v) == (d >= n)), f"{name}_d{d} NaN pattern wrong for {n} spans"
# a = 0 (index 0 of a_deg): y and theta stay zero, margin = seat - x_max.
for i, n in enumerate(spans):
    for d in range(n):
        assert np.all(np.abs(r[f"y_norm_d{d}"][i, 0]) < 1e-9), "transverse motion at a = 0"
        assert np.all(np.abs(r[f"theta_norm_d{d}"][i, 0]) < 1e-9), "rotation at a = 0"
        seat = 0.02 * r["L"][i, 0] / r["L_e"][i, 0]
        np.testing.assert_allclose(r[f"margin_norm_d{d}"][i, 0], seat - r[f"x_norm_d{d}"][i, 0],
                                   rtol=1e-12, atol=1e-12)
# w0/w_g = 0.5 and 1 pound and rotate; at w0/w_g = 2 the bearings keep the decks off the gaps.
assert np.all(r["impacts"][:, 1, :2] > 0), "skewed cells without impacts"
assert np.all(r["theta_norm_max"][:, 1, :2] > 1e-2), "skewed cells without rotation"
assert np.all(r["impacts"][:, :, 2] == 0), "impacts with stiff bearings"
print("multi-span cube ok: theta_norm_max up to", float(np.nanmax(r["theta_norm_max"])))
PY
