#!/usr/bin/env bash
# Limit states in every family, through `skewbridge sweep` on 2 ranks into real cubes:
#  1. the subsystem and the pilot bridge under real records (tests/data/records), the multi-span
#     row under pulses, each with gaps and seats larger than any response (no cell exceeds any
#     limit state, the fits say why they give no number) and with zero gaps and zero seats
#     (every cell closes a joint and unseats);
#  2. the stored bound of the corner travel of every deck against a brute-force search from the
#     stored maxima (the corners of the parallelogram turned through a fine grid of angles in
#     [-theta_m, theta_m] by numpy), the exact travel between the residual travel and that bound,
#     the margin against seat - travel and each demand against the responses it is made of;
#  3. a three-span row as a multi-span cell and as a model file written with the same values:
#     the same travel, margin, rotation and limit states per deck;
#  4. `skewbridge inspect` of these cubes: the fits per combination without the stripe axis;
#  5. bad [limit_states] in these families: one line naming the key, status 2, no cube.
# usage: families_test.sh SKEWBRIDGE MPIEXEC SOURCE_DIR WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec src work -- "$@"
fresh_dir "$work"
mkdir rec
cp "$src/tests/data/records/NIS090.AT2" "$src/tests/data/records/RSN763_LOMAP_GIL067.AT2" \
   "$src/tests/data/records/0111a.smc" rec/
sweep() {  # sweep SPEC OUT: on 2 ranks
  on_ranks 2 "$exe" sweep "$1" --out "$2" --quiet || fail "$1: sweep failed"
}

# spec FAMILY NAME GAP_KIND: the family's axes, then [limit_states] for wide or tight gaps.
spec() {
  local family=$1 name=$2 kind=$3
  printf '[sweep]\nname = "%s"\nfamily = "%s"\n' "$name" "$family"
  if [ "$family" = multi-span ]; then
    printf '[axes]\nspans = [1, 2, 3]\na_deg = [20, 40]\nw0_over_wg = [0.5, 1.0]\n'
    printf 'a_g_g = [0.3, 0.6]\n[fixed]\neta0 = 1.5\nmu = 0.1\n'
  else
    printf '[records]\nfolder = "rec"\npattern = "*"\n[axes]\nrecord = "*"\na_deg = [20, 40]\n'
    printf '[fixed]\n'
  fi
  if [ "$kind" = wide ]; then
    # Gaps of 1000 L_e and seats of 10 L: no response of a linear run comes near either.
    printf 'Pi_delta = 1000.0\nseat_over_L = 10.0\n[limit_states]\nunseating = true\n'
    printf 'seat_displacement = {above_m = 1000.0}\nresidual = {above_m = 1000.0}\n'
    printf 'rotation = {above_rad = 1.0}\njoint_closing = true\n'
  else
    printf 'Pi_delta = 0.0\n[limit_states]\nunseating = {seat_m = 0.0}\n'
    printf 'seat_displacement = {above_m = 0.0}\nrotation = {above_rad = 0.0}\n'
    printf 'joint_closing = true\nresidual = {above_m = 1000.0}\n'
  fi
}
for family in subsystem pilot-bridge multi-span; do
  for kind in wide tight; do
    spec "$family" "$kind" "$kind" > "$family-$kind.toml"
    sweep "$family-$kind.toml" "$family-$kind.h5"
  done
done

/usr/bin/python3 - <<'PY' || fail "bounding bridges or corner travels"
import math
import h5py
import numpy as np

G = 9.80665


def plan(family, a_deg, r):
    """(L, W) of the deck of a cell, from the family's definition (docs/sweep-format.md)."""
    a = math.radians(a_deg)
    if family == "pilot-bridge":
        if a_deg == 20:
            return np.full_like(r["L_e"], 89.14), np.full_like(r["L_e"], 19.36)
        w_over_l = 19.36 / 89.14
        L = math.sqrt(12.0 * (1079100.0 / 1547.0) / (1.0 + w_over_l**2 / math.cos(a) ** 2))
        return np.full_like(r["L_e"], L), np.full_like(r["L_e"], w_over_l * L)
    L = 250.0 * r["L_e"]  # L_over_Le's default
    return L, L * math.sin(2 * a) / (2 * 1.5 if family == "multi-span" else 2 * 1.0)


def brute_travel(L, W, a, x, y, th):
    """Largest corner travel normal to the end line over a grid of rotations in [-th, th]."""
    n = np.array([math.cos(a), -math.sin(a)])
    s = 0.5 * W * math.tan(a)
    corners = np.array([[L / 2 + s, W / 2], [L / 2 - s, -W / 2], [-L / 2 - s, -W / 2],
                        [-L / 2 + s, W / 2]])
    t = np.linspace(-th, th, 4001)
    c, sn = np.cos(t)[:, None], np.sin(t)[:, None]
    moved_x = c * corners[:, 0] - sn * corners[:, 1] - corners[:, 0]
    moved_y = sn * corners[:, 0] + c * corners[:, 1] - corners[:, 1]
    return n[0] * x - n[1] * y + np.abs(n[0] * moved_x + n[1] * moved_y).max()


checked = 0
for family in ("subsystem", "pilot-bridge", "multi-span"):
    for kind in ("wide", "tight"):
        g = h5py.File(f"{family}-{kind}.h5", "r")["sweeps/" + kind]
        assert (g["status"][()] == 0).all() and (g["done"][()] == 1).all(), (family, kind)
        r = {k: g["responses/" + k][()] for k in g["responses"]}
        names = ("unseating", "seat_displacement", "rotation", "joint_closing")
        if kind == "wide":
            assert (r["impacts"] == 0).all(), (family, "impacts with gaps of 1000 L_e")
            for name in names + ("residual",):
                assert (r["ls_" + name] == 0).all(), (family, name, "exceeded")
                f = g["fragility/" + name]
                assert (f["n_exceeded"][()] == 0).all() and np.isnan(f["theta"][()]).all()
                assert all(s.decode().startswith("no exceedance") for s in f["reason"][()])
                if family == "multi-span":  # a_g_g: two stripes of one cell per combination
                    assert f["stripe_n"][()].shape == (3, 2, 2, 2)
                    assert (f["stripe_n"][()] == 1).all() and (f["stripe_exceeded"][()] == 0).all()
        else:
            for name in names:
                z = r["ls_" + name]
                assert (z == 1).all(), (family, name, "not exceeded in", int((z != 1).sum()))
                f = g["fragility/" + name]
                if name == "rotation":
                    # A rotation below the round-off floor is 0 for the fits: not above 0 rad.
                    floor = g.attrs["round_off_floor_rad"]
                    assert floor == f.attrs["round_off_floor"] == 1e-12
                    d = r["ls_rotation_demand"]
                    assert f["n_exceeded"][()].sum() == (d >= floor).sum(), family
                    continue
                assert (f["n_exceeded"][()] == f["n_cells"][()]).all()
                assert all(s.decode().startswith("exceeded in all") for s in f["reason"][()])
                if family == "multi-span":
                    assert (f["stripe_exceeded"][()] == f["stripe_n"][()]).all()
        # The travel of every deck against the brute force, and the demands of the limit states.
        decks = [""] if "travel_m" in r else [f"_d{d}" for d in range(3)]
        a_axis = list(g["axes/a_deg"][()])
        a_dim = [k.decode() if isinstance(k, bytes) else k for k in g.attrs["axis_order"]].index("a_deg")
        travel_max = np.full(r["impacts"].shape, -np.inf)
        for s in decks:
            if family == "multi-span":
                x, y = r["x_norm" + s] * r["L_e"], r["y_norm" + s] * r["L_e"]
                th = r["theta_m" + s]
            else:
                x, y, th = r["x_m"], r["y_m"], r["theta_m"]
            for ia, a_deg in enumerate(a_axis):
                L, W = plan(family, a_deg, r)
                for idx in np.ndindex(x.shape):
                    if idx[a_dim] != ia or np.isnan(x[idx]):
                        continue
                    want = brute_travel(L[idx], W[idx], math.radians(a_deg), x[idx], y[idx], th[idx])
                    bound = r["travel_bound_m" + s][idx]
                    # The grid misses the exact ends by nothing (they are on it): 1e-12 m.
                    assert abs(bound - want) <= 1e-12 + 1e-9 * want, (family, kind, s, idx, bound, want)
                    got = r["travel_m" + s][idx]
                    assert got <= bound * (1 + 1e-12), (family, kind, s, idx, "travel > bound")
                    assert r["travel_end_m" + s][idx] <= got + 1e-12, (family, s, "residual > max")
                    if kind == "wide":  # seat_over_L = 10
                        seat = 10.0 * L[idx]
                        assert abs(r["margin_m" + s][idx] - (seat - got)) <= 1e-12 * seat
                    checked += 1
            travel_max = np.fmax(travel_max, r["travel_m" + s])
        np.testing.assert_array_equal(r["ls_seat_displacement_demand"], travel_max)
        np.testing.assert_array_equal(r["ls_joint_closing_demand"], r["impacts"])
        if kind == "tight":
            assert np.isinf(r["ls_unseating_demand"]).all()  # any travel over a zero seat
print("bounding bridges: P = 0 and P = 1 in three families;", checked, "deck travels by brute force")
PY

# inspect names the combinations without the stripe axis a_g_g, and a zero seat's demand as inf.
"$exe" inspect multi-span-wide.h5 > inspect.txt
grep -qF "theta [g], per spans,a_deg,w0_over_wg" inspect.txt || fail "inspect: combinations of multi-span"
grep -Eq '^    unseating +1,20,0.5 +2 +0 ' inspect.txt || fail "inspect: a multi-span combination row"
"$exe" inspect subsystem-tight.h5 > inspect.txt
grep -Eq '^    unseating +exceeded in 6 of 6 cells; demand up to inf$' inspect.txt \
  || fail "inspect: the demand of a zero seat"

# A three-span row as a multi-span cell and as a model file with the same values.
cat > ms.toml <<'TOML'
[sweep]
name = "row"
family = "multi-span"
[axes]
Pi_delta = [0.5, 1.0, 2.0]
[fixed]
spans = 3
a_deg = 30.0
eta0 = 1.5
w0_over_wg = 1.0
W0_over_w0 = 1.2
mu = 0.2
seat_over_L = 0.02
[limit_states]
unseating = true
rotation = {above_rad = 0.001}
seat_displacement = {above_m = 0.05}
residual = {above_m = 0.001}
joint_closing = true
TOML
/usr/bin/python3 - <<'PY'
import math
# The multi-span cell's bridge (spectra/multispan_evaluator.cpp): w_g = 2 pi, a_g = 0.5 g,
# L = 250 L_e, m = 1e6 kg per deck, uniform I_m, k = m w0^2, k_theta = I_m W0^2, xi = 0.05,
# eps_N = 0.5, run to the pulse's end plus two periods, abs_tol = 1e-11 L_e.
w_g = 2.0 * math.pi
L_e = 0.5 * 9.80665 / (w_g * w_g)
L = 250.0 * L_e
a = 30.0 * math.pi / 180.0
W = L * math.sin(2 * a) / (2 * 1.5)
m = (1e6 / L) * L
I = m * (L * L + W * W / math.cos(a) ** 2) / 12.0
w0, W0 = w_g, 1.2 * w_g
out = []
for d in range(3):
    out += ["[[deck]]", f"m = {m!r}", 'I_m = "uniform"', f"L = {L!r}", "eta0 = 1.5",
            "skew_deg = 30.0", ""]
for j in range(2):
    out += ["[[joint]]", "gap_m = 0.1", "eps_N = 0.5", "mu = 0.2", ""]
out += ["[abutments]", "gap_m = 0.1", "eps_N = 0.5", "mu = 0.2", ""]
for d in range(3):
    out += ["[[support]]", f"deck = {d}", f"k_x = {m * w0 * w0!r}", f"k_y = {m * w0 * w0!r}",
            f"k_theta = {I * W0 * W0!r}", "xi = 0.05", ""]
out += ["[excitation]", 'kind = "pulse"', 'shape = "cosine"', "a_g_g = 0.5", "T_g = 1.0",
        'direction = "x"', "", "[run]", "end_time_s = 3.0", f"abs_tol = {1e-11 * L_e!r}"]
open("row.toml", "w").write("\n".join(out) + "\n")
PY
sed -e 's/^family = "multi-span"/family = "model-file"\nmodel = "row.toml"/' \
    -e '/^spans = /d' -e '/^a_deg = /d' -e '/^eta0 = /d' -e '/^w0_over_wg = /d' \
    -e '/^W0_over_w0 = /d' -e '/^mu = /d' ms.toml > mf.toml
sweep ms.toml ms.h5
sweep mf.toml mf.h5
/usr/bin/python3 - <<'PY' || fail "the multi-span cells differ from the model file's"
import h5py, numpy as np
a = h5py.File("ms.h5", "r")["sweeps/row"]["responses"]
b = h5py.File("mf.h5", "r")["sweeps/row"]["responses"]
assert (a["impacts"][()] > 0).all(), "the row does not pound"
for d in range(3):
    for name in ("travel_m", "travel_bound_m", "travel_end_m", "margin_m", "theta_m"):
        np.testing.assert_allclose(a[f"{name}_d{d}"][()], b[f"{name}_d{d}"][()], rtol=1e-6,
                                   atol=1e-12, err_msg=f"{name}_d{d}")
for name in ("unseating", "rotation", "seat_displacement", "residual", "joint_closing"):
    np.testing.assert_allclose(a[f"ls_{name}_demand"][()], b[f"ls_{name}_demand"][()], rtol=1e-6)
    np.testing.assert_array_equal(a[f"ls_{name}"][()], b[f"ls_{name}"][()])
print("three-span row: multi-span and model-file agree; travel_m_d1 =", a["travel_m_d1"][()])
PY

# Bad keys: one line each, status 2, no cube.
# check_bad NAME FAMILY EXPECTED_TEXT < TOML: a sweep of FAMILY whose spec continues with TOML.
check_bad() {
  local name=$1 family=$2 expected=$3 status=0
  { printf '[sweep]\nname = "bad"\nfamily = "%s"\n' "$family"; cat; } > "$name.toml"
  "$exe" sweep "$name.toml" --out "$name.h5" > out.txt 2> err.txt || status=$?
  [ "$status" -eq 2 ] || fail "$name: exit status $status, expected 2"
  [ "$(wc -l < err.txt)" -eq 1 ] || fail "$name: expected one line, got: $(cat err.txt)"
  grep -qF -- "$expected" err.txt || fail "$name: expected '$expected' in: $(cat err.txt)"
  [ ! -e "$name.h5" ] && [ ! -e "$name.h5.partial" ] || fail "$name: an output file was left"
}
check_bad no_seats pilot-bridge "limit_states.unseating: needs seat widths: give seat_over_L or seat_m (axis or fixed), or unseating = {seat_m" <<TOML
[axes]
Pi_delta = [0.5, 1.0]
[limit_states]
unseating = true
TOML
check_bad seat_lines multi-span "limit_states.unseating.seat_m: one seat width per support line needs a fixed number of spans" <<TOML
[axes]
spans = [1, 2]
[fixed]
eta0 = 1.5
[limit_states]
unseating = {seat_m = [0.5, 0.4, 0.5]}
TOML
check_bad seat_count multi-span "limit_states.unseating.seat_m: give one seat width or one per support line (4 for 3 decks" <<TOML
[axes]
a_deg = [20, 40]
[fixed]
eta0 = 1.5
spans = 3
[limit_states]
unseating = {seat_m = [0.5, 0.4, 0.5]}
TOML
check_bad response subsystem "limit_states.response.theta_m_d0: unknown response; allowed: x_m, y_m, theta_m" <<TOML
[axes]
Pi_delta = [0.5, 1.0]
[limit_states]
response = {theta_m_d0 = 0.01}
TOML
echo "families_test: ok"
