#!/usr/bin/env bash
# Model-file sweeps through `skewbridge sweep`: a single deck under pulses (Pi_delta, skew angle
# with the deck re-derived from eta0, stiffness factor, eps_N axes) and two decks in a row under
# records (every record of a folder set by record = "*", a scale, the skew angle, the gap in
# metres, xi), and the deck under its own excitation file (Pi_delta, scale). Each
# cube is byte-identical on 1 and 2 ranks, and every cell equals `skewbridge run` of a model file
# written with the cell's values (maxima, residuals and impacts, to the printed 7 digits).
# usage: model_file_sweep_test.sh SKEWBRIDGE MPIEXEC WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec work -- "$@"
fresh_dir "$work"

# --- the single deck: [deck] with eta0 (so a new skew angle changes W), uniform I_m -----------
cp "$test_data/models/one-deck-pulse.toml" deck.toml
cat > deck-sweep.toml <<'TOML'
[sweep]
name = "deck"
family = "model-file"
model = "deck.toml"
[axes]
Pi_delta = [0.5, 1.0]
a_deg = [20, 45]
k_factor = [1.0, 2.0]
eps_N = [0.3, 0.7]
[fixed]
mu = 0.1
pulse = "sine"
eta0 = 2.0
TOML

# --- two decks in a row under two records of a folder set (plain files, m/s^2, dt 0.01 s) -----
mkdir -p recs
/usr/bin/python3 - <<'PY'
import math
for name, amp, period in (("r1.txt", 3.0, 0.5), ("r2.txt", 4.5, 0.8)):
    with open("recs/" + name, "w") as f:
        for k in range(300):
            t = 0.01 * k
            f.write("%.17g\n" % (amp * math.sin(2 * math.pi * t / period) * math.exp(-t / 1.0)))
PY
printf 'name = "two"\nfolder = "recs"\npattern = "r?.txt"\nunits = "m/s^2"\ndt = 0.01\n' > set.toml
cat > spans.toml <<'TOML'
[[deck]]
m = 600e3
L = 30.0
W = 12.0
skew_deg = 30.0
[[deck]]
m = 800e3
L = 40.0
W = 12.0
skew_deg = 30.0
[[joint]]
gap_m = 0.04
eps_N = 0.5
mu = 0.2
[abutments]
gap_m = 0.05
eps_N = 0.5
mu = 0.2
[[support]]
deck = 0
k_x = 6.0e7
k_y = 6.0e7
k_theta = 7.8624e9
xi = 0.05
[[support]]
deck = 1
k_x = 8.0e7
k_y = 8.0e7
k_theta = 1.72032e10
xi = 0.05
[excitation]
kind = "pulse"
shape = "cosine"
a_g_g = 0.4
T_g = 0.6
direction = "x"
[run]
tail_s = 1.0
TOML
cat > spans-sweep.toml <<'TOML'
[sweep]
name = "spans"
family = "model-file"
model = "spans.toml"
[records]
set = "set.toml"
[axes]
record = "*"
scale = [0.5, 1.5]
a_deg = [15, 30]
gap_m = [0.005, 0.02]
[fixed]
xi = 0.03
seat_over_L = 0.02
TOML

# Refused before any work: one line naming the spec and the key, exit 2, no output left.
printf '[sweep]\nname = "bad"\nfamily = "model-file"\nmodel = "deck.toml"\n[axes]\na_deg = [0, 30]\n' > bad.toml
set +e
"$exe" sweep bad.toml --out bad.h5 2> bad.err
status=$?
set -e
[ "$status" -eq 2 ] || fail "bad spec: exit $status, expected 2"
[ "$(wc -l < bad.err)" -eq 1 ] || fail "bad spec: not one line: $(cat bad.err)"
grep -q "bad.toml: a_deg: needs a skew angle > 0" bad.err || fail "bad spec message: $(cat bad.err)"
! ls bad.h5* >/dev/null 2>&1 || fail "bad spec left output files"

# --- the single deck under the samples of its own excitation file, times scale ---------------
sed -e 's/^kind = "pulse"/kind = "sampled"\nfile = "recs\/r1.txt"\ndt_s = 0.01\nunits = "mps2"/' \
    -e '/^shape = /d' -e '/^a_g_g = /d' -e '/^T_g = /d' deck.toml > sampled.toml
cat > sampled-sweep.toml <<'TOML'
[sweep]
name = "sampled"
family = "model-file"
model = "sampled.toml"
[axes]
Pi_delta = [0.25, 1.0]
scale = [1.0, 2.0]
TOML

for spec in deck spans sampled; do
  for n in 1 2; do
    on_ranks "$n" "$exe" sweep "$spec-sweep.toml" --out "$spec-$n.h5" --quiet
  done
done

# --- the single deck under a synthetic suite: the record study's correlation of theta_m_d0 ------
cat > deckrec-sweep.toml <<'TOML'
[sweep]
name = "deckrec"
family = "model-file"
model = "deck.toml"
[records]
synthetic = {count = 6, seed = 5}
[axes]
record = "*"
Pi_delta = [0.5, 2.0]
TOML
"$exe" sweep deckrec-sweep.toml --out deckrec.h5 --quiet || fail "deckrec sweep"
/usr/bin/python3 - <<'PY' || fail "one-deck correlation"
import h5py, numpy as np
g = h5py.File("deckrec.h5", "r")["sweeps/deckrec"]
c = g["correlation"]
assert c.attrs["y"] == "theta_m_d0", c.attrs["y"]
assert "band_edges" not in c.attrs  # no response band in this family
theta, le, status = g["responses/theta_m_d0"][()], g["responses/L_e"][()], g["status"][()]
for p in range(2):  # record axis first, Pi_delta second
    ok = status[:, p] == 0
    r = np.corrcoef(le[ok, p], theta[ok, p])[0, 1]
    assert c["n"][p] == ok.sum() and abs(c["pearson_theta_Le"][p] - r) <= 1e-12, (p, r)
PY

/usr/bin/python3 - "$exe" <<'PY' || fail "cube check"
import itertools, math, re, subprocess, sys, h5py, numpy as np
exe = sys.argv[1]
G = 9.80665

def cube(path, name):
    return h5py.File(path, "r")["sweeps/" + name]

def same_bytes(name):
    a, b = cube(name + "-1.h5", name), cube(name + "-2.h5", name)
    for n in ["responses/" + r for r in a["responses"]] + ["status", "done"]:
        assert a[n][()].tobytes() == b[n][()].tobytes(), f"{name}: {n} differs on 1 and 2 ranks"
    assert np.all(a["status"][()] == 0), f"{name}: failed cells"
    return a

def run(text):
    with open("cell.toml", "w") as f:
        f.write(text)
    out = subprocess.run([exe, "run", "cell.toml"], capture_output=True, text=True, check=True).stdout
    maxima = {}
    for m in re.finditer(r"max\|(x|y|theta)(\d+)\| = (\S+) at \S+ s, residual (\S+)", out):
        maxima[(m.group(1), int(m.group(2)))] = (float(m.group(3)), float(m.group(4)))
    impacts = int(re.search(r"impacts (\d+)", out).group(1))
    return maxima, impacts

def close(a, b, what):
    # `run` prints 7 significant digits: agree to its rounding.
    assert abs(a - b) <= 1e-6 * abs(b) + 1e-300, f"{what}: sweep {a!r}, run {b!r}"

def compare(c, idx, maxima, impacts, decks, what):
    for d in range(decks):
        for q in ("x", "y", "theta"):
            m, r = maxima[(q, d)]
            close(float(c[f"responses/{q}_m_d{d}"][idx]), m, f"{what} {q}_m_d{d}")
            close(float(c[f"responses/{q}_end_d{d}"][idx]), r, f"{what} {q}_end_d{d}")
    assert int(c["responses/impacts"][idx]) == impacts, f"{what}: impacts differ"

# The single deck: the cell's file has the same [deck] with skew_deg = a (W from eta0 = 1.5),
# w0, W0 times sqrt(k), the gaps Pi_delta L_e, eps_N, mu = 0.1, a sine pulse.
c = same_bytes("deck")
deck = open("deck.toml").read()
order = [x.decode() if isinstance(x, bytes) else x for x in c.attrs["axis_order"]]
assert order == ["a_deg", "eps_N", "Pi_delta", "k_factor"], order
impacting = 0
for idx in itertools.product(*(range(len(c["axes/" + k])) for k in order)):
    a, e, P, f = (float(c["axes/" + k][i]) for k, i in zip(order, idx))
    a_g = 0.5 * G
    w_g = 2 * math.pi / 0.6
    gap = P * (a_g / (w_g * w_g))
    text = (deck.replace("skew_deg = 30.0", f"skew_deg = {a!r}")
            .replace("w0 = 10.0", f"w0 = {10.0 * math.sqrt(f)!r}")
            .replace("W0 = 12.0", f"W0 = {12.0 * math.sqrt(f)!r}")
            .replace("gap_m = 0.03", f"gap_m = {gap!r}")
            .replace("eps_N = 0.5", f"eps_N = {e!r}")
            .replace("mu = 0.0", "mu = 0.1")
            .replace("eta0 = 1.5", "eta0 = 2.0")
            .replace('shape = "cosine"', 'shape = "sine"'))
    maxima, impacts = run(text)
    compare(c, idx, maxima, impacts, 1, f"deck cell a={a} Pi={P} k={f} e={e}")
    impacting += impacts > 0
    close(float(c["responses/delta"][idx]), gap, "delta")
assert impacting >= 4, "too few cells pound to test the contacts"

# Two decks: the cell's file has excitation from the record file times scale, every gap the
# cell's gap_m, xi = 0.03 on both supports.
c = same_bytes("spans")
spans = open("spans.toml").read()
order = [x.decode() if isinstance(x, bytes) else x for x in c.attrs["axis_order"]]
assert order == ["record", "scale", "a_deg", "gap_m"], order
labels = [x.decode() if isinstance(x, bytes) else x for x in c["axes/record"][()]]
assert labels == ["r1.txt", "r2.txt"], f"record = \"*\" took {labels}"
impacting = 0
for idx in itertools.product(*(range(len(c["axes/" + k])) for k in order)):
    label = labels[idx[0]]
    s, a, gap = (float(c["axes/" + k][i]) for k, i in zip(order[1:], idx[1:]))
    # Both decks keep L and W at the new angle; their uniform I_m follows (the run's parser).
    text = (spans.replace("gap_m = 0.04", f"gap_m = {gap!r}")
            .replace("gap_m = 0.05", f"gap_m = {gap!r}")
            .replace("skew_deg = 30.0", f"skew_deg = {a!r}")
            .replace("xi = 0.05", "xi = 0.03"))
    text = re.sub(r"\[excitation\][^\[]*",
                  f'[excitation]\nkind = "sampled"\nfile = "recs/{label}"\ndt_s = 0.01\n'
                  f'units = "mps2"\nscale = {s!r}\ndirection = "x"\n', text)
    maxima, impacts = run(text)
    compare(c, idx, maxima, impacts, 2, f"spans cell {label} scale={s} a={a} gap={gap}")
    impacting += impacts > 0
    for d in range(2):
        assert float(c[f"responses/margin_m_d{d}"][idx]) < 0.02 * (30.0, 40.0)[d]
# The record's measures scale with it: PGA x scale, T_m unchanged.
pga = c["responses/pga"][()]
np.testing.assert_allclose(pga[:, 1] / pga[:, 0], 3.0, rtol=1e-14)
tm = c["responses/T_m"][()]
assert np.all(tm == tm[:, :1, :1, :1]), "T_m depends on the scale"
assert impacting >= 4, "too few cells pound to test the joints"
# The deck under its file's samples: the cell's file has scale and the gaps delta of the cube
# (Pi_delta L_e, with L_e of the samples' measures).
c = same_bytes("sampled")
sampled = open("sampled.toml").read()
order = [x.decode() if isinstance(x, bytes) else x for x in c.attrs["axis_order"]]
assert order == ["scale", "Pi_delta"], order
for idx in itertools.product(range(2), range(2)):
    s = float(c["axes/scale"][idx[0]])
    gap = float(c["responses/delta"][idx])
    text = (sampled.replace("gap_m = 0.03", f"gap_m = {gap!r}")
            .replace('units = "mps2"', f'units = "mps2"\nscale = {s!r}'))
    maxima, impacts = run(text)
    compare(c, idx, maxima, impacts, 1, f"sampled cell scale={s} gap={gap}")
np.testing.assert_allclose(c["responses/L_e"][1, :], 2 * c["responses/L_e"][0, :], rtol=1e-15)
print("model-file cubes ok: 16 + 4 deck cells and 16 two-deck cells equal `skewbridge run`")
PY
