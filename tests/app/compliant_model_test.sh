#!/usr/bin/env bash
# A model file's compliant abutments ([abutments] law = "compliant",
# docs/examples/pilot-bridge-compliant.toml) through `skewbridge run --out` and through a model-file
# sweep on 2 ranks (axis scale = [1, 1.5]) give the same numbers, bit for bit, as the C++ API
# called directly with springs built by hand (compliant_direct: SimulateCompliant, WallSprings):
# the deck's maxima and residuals, the strikes and the smallest time between them, the corner
# travel, each wall's largest spring force and deformation (the cube's spring_force_px,
# backwall_def_px, ..._mx). The cube's
# responses of a rigid file hold none of the compliant ones; `run --from-cube` re-runs a compliant
# cell with its springs. With shear keys (pilot-bridge-compliant-keys.toml) the run file's group
# `joints`, the cube and a cell run again from it hold the same joint responses, the keys' break
# times among them. A law per wall (pilot-bridge-one-keyed-abutment.toml): each spring's largest
# force on its own wall's envelope. A sweep's eps_N is refused with one line and no cube.
# usage: compliant_model_test.sh SKEWBRIDGE MPIEXEC COMPLIANT_DIRECT SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec direct src -- "$@"
temp_dir

cp "$src/docs/examples/pilot-bridge-compliant.toml" "$src/docs/examples/pilot-signal.txt" "$work/"
"$direct" "$work/pilot-signal.txt" 1 >"$work/direct1" || fail "direct run: exit $?"
"$direct" "$work/pilot-signal.txt" 1.5 >"$work/direct15" || fail "direct run x 1.5: exit $?"
grep -q "status ok" "$work/direct1" || fail "direct run: $(cat "$work/direct1")"

"$exe" run "$work/pilot-bridge-compliant.toml" --out "$work/run.h5" >"$work/run.out" 2>&1 ||
  fail "run: exit $? ($(cat "$work/run.out"))"
grep -q "compliant abutments, 5 springs per wall; backfill energy" "$work/run.out" ||
  fail "no compliant line in the summary: $(cat "$work/run.out")"

cat >"$work/spec.toml" <<'TOML'
[sweep]
name = "compliant"
family = "model-file"
model = "pilot-bridge-compliant.toml"
[limit_states]
joint_closing = true
[axes]
scale = [1.0, 1.5]
TOML
on_ranks 2 "$exe" sweep "$work/spec.toml" --out "$work/cube.h5" --quiet >"$work/sweep.out" 2>&1 ||
  fail "sweep: exit $? ($(cat "$work/sweep.out"))"

/usr/bin/python3 - "$work" <<'PY' || fail "run and cube against the direct call (above)"
import sys, re, h5py
work = sys.argv[1]
def direct(name):
    return {k: float(v) for k, v in (l.split() for l in open(f"{work}/{name}") if l.split()[0] != "status")}
d1, d15 = direct("direct1"), direct("direct15")
assert d1["impacts"] > 0 and d1["spring_force_px"] > 0 and d1["spring_force_mx"] > 0, d1
assert d15["spring_force_px"] > d1["spring_force_px"], (d1, d15)
run = h5py.File(f"{work}/run.h5", "r")["summary"]
for i, n in enumerate(("x", "y", "theta")):
    assert run["max_abs_q"][i] == d1[n + "_m"], (n, run["max_abs_q"][i], d1[n + "_m"])
    assert run["q_end"][i] == d1[n + "_end"], (n, run["q_end"][i], d1[n + "_end"])
assert run.attrs["impacts"] == d1["impacts"], (run.attrs["impacts"], d1["impacts"])
# The smallest time between the starts of successive strikes: finite with two or more strikes.
assert d1["impacts"] >= 2 and 0 < d1["min_impact_separation"] < float("inf"), d1
assert run.attrs["min_impact_separation_s"] == d1["min_impact_separation"], run.attrs["min_impact_separation_s"]
# Per spring, the run file's joints group holds the direct call's maxima, bit for bit, and the
# wall's response is the largest of its springs'; no wall friction: no slip.
j = h5py.File(f"{work}/run.h5", "r")["joints"]
springs = [n.decode() if isinstance(n, bytes) else n for n in j.attrs["spring_names"]]
assert springs == [f"{w}.{k}" for w in ("+x", "-x") for k in range(1, 6)], springs
for k in range(10):
    assert j["spring_force_N"][k] == d1[f"spring_force_{k}"], (k, j["spring_force_N"][k])
    assert j["spring_deformation_m"][k] == d1[f"spring_def_{k}"], (k, j["spring_deformation_m"][k])
assert max(j["spring_force_N"][:5]) == j.attrs["spring_force_px"] == d1["spring_force_px"]
assert max(j["spring_deformation_m"][5:]) == j.attrs["backwall_def_mx"] == d1["backwall_def_mx"]
assert not j["spring_slip_m"][()].any(), j["spring_slip_m"][()]
text = open(f"{work}/run.out").read()
for wall, side in (("+x", "px"), ("-x", "mx")):
    m = re.search(re.escape(wall) + r" wall: largest spring force (\S+) N, largest deformation (\S+) m$", text, re.M)
    assert m, text
    assert abs(float(m.group(1)) - d1["spring_force_" + side]) <= 1e-6 * d1["spring_force_" + side], m.group(1)
    assert abs(float(m.group(2)) - d1["backwall_def_" + side]) <= 1e-6 * d1["backwall_def_" + side], m.group(2)
m = re.search(r"smallest strike separation (\S+) s$", text, re.M)
assert m and abs(float(m.group(1)) - d1["min_impact_separation"]) <= 1e-3 * d1["min_impact_separation"], text
g = h5py.File(f"{work}/cube.h5", "r")["sweeps/compliant"]
assert list(g["status"][()]) == [0, 0], g["status"][()]
r = g["responses"]
for cell, d in ((0, d1), (1, d15)):
    for n in ("x", "y", "theta"):
        assert r[n + "_m_d0"][cell] == d[n + "_m"], (cell, n, r[n + "_m_d0"][cell], d[n + "_m"])
        assert r[n + "_end_d0"][cell] == d[n + "_end"], (cell, n)
    assert r["impacts"][cell] == d["impacts"], (cell, r["impacts"][cell], d["impacts"])
    assert r["min_impact_separation"][cell] == d["min_impact_separation"], (cell, r["min_impact_separation"][cell])
    assert r["travel_m_d0"][cell] == d["travel_m"], (cell, r["travel_m_d0"][cell], d["travel_m"])
    for k in ("spring_force_px", "backwall_def_px", "spring_force_mx", "backwall_def_mx"):
        assert r[k][cell] == d[k], (cell, k, r[k][cell], d[k])
        assert r[k].attrs.get("units", b"") in (b"N", b"m", "N", "m"), dict(r[k].attrs)
PY

# The cube's cell at scale 1.5 run again (`run --from-cube`) runs the springs again: the same bits.
"$exe" run --from-cube "$work/cube.h5" --cell-index 1 --out "$work/rerun.h5" >"$work/rerun.out" 2>&1 ||
  fail "run --from-cube: exit $? ($(cat "$work/rerun.out"))"
grep -q "compliant abutments, 5 springs per wall" "$work/rerun.out" ||
  fail "run --from-cube ran no springs: $(cat "$work/rerun.out")"
/usr/bin/python3 - "$work" <<'PY' || fail "run --from-cube against the direct call (above)"
import sys, h5py
work = sys.argv[1]
d = {k: float(v) for k, v in (l.split() for l in open(f"{work}/direct15") if l.split()[0] != "status")}
s = h5py.File(f"{work}/rerun.h5", "r")["summary"]
for i, n in enumerate(("x", "y", "theta")):
    assert s["max_abs_q"][i] == d[n + "_m"], (n, s["max_abs_q"][i], d[n + "_m"])
assert s.attrs["impacts"] == d["impacts"], (s.attrs["impacts"], d["impacts"])
assert s.attrs["min_impact_separation_s"] == d["min_impact_separation"], s.attrs["min_impact_separation_s"]
PY

# Shear keys (docs/examples/pilot-bridge-compliant-keys.toml with weaker keys the signal breaks:
# gap 5 mm, V_n = 0.5 MN at D3 = 2 mm, DD = 8 mm; the signal at 60 deg from x): `run --out` and a
# 2-rank sweep (scale 1 and 3) store the same joint responses, bit for bit, in the run file's
# group `joints` and the cube; the cell whose keys broke, run again from the cube, has the cube's
# break times; the summary prints each key as the run file holds it.
awk '/^\[abutments.shear_keys.details\]/ { skip = 1 } /^\[excitation\]/ { skip = 0 } !skip' \
  "$src/docs/examples/pilot-bridge-compliant-keys.toml" |
  sed -e 's/^gap_m = 0.0254.*/gap_m = 0.005\nv_n_N = 0.5e6/' -e 's/^d3_m = .*/d3_m = 0.002/' \
    -e 's/^dd_m = .*/dd_m = 0.008/' -e 's/^direction = "x"/angle_deg = 60.0/' >"$work/keys.toml"
grep -q "^v_n_N = 0.5e6" "$work/keys.toml" || fail "keys.toml: $(cat "$work/keys.toml")"
"$exe" run "$work/keys.toml" --out "$work/keys-run.h5" >"$work/keys-run.out" 2>&1 ||
  fail "run with keys: exit $? ($(cat "$work/keys-run.out"))"
sed -e 's/pilot-bridge-compliant.toml/keys.toml/' -e 's/^scale = .*/scale = [1.0, 3.0]/' \
  "$work/spec.toml" >"$work/keys-spec.toml"
on_ranks 2 "$exe" sweep "$work/keys-spec.toml" --out "$work/keys.h5" --quiet >"$work/sweep.out" 2>&1 ||
  fail "sweep with keys: exit $? ($(cat "$work/sweep.out"))"
"$exe" run --from-cube "$work/keys.h5" --cell-index 1 --out "$work/keys-rerun.h5" \
  >"$work/keys-rerun.out" 2>&1 || fail "run --from-cube with keys: exit $? ($(cat "$work/keys-rerun.out"))"
/usr/bin/python3 - "$work" <<'PY' || fail "the keys' responses of the run, the cube and the rerun (above)"
import sys, re, math, h5py
work = sys.argv[1]
r = h5py.File(f"{work}/keys.h5", "r")["sweeps/compliant/responses"]
names = ["spring_force_px", "backwall_def_px", "spring_force_mx", "backwall_def_mx",
         "key_force_px", "key_def_px", "key_break_time_px", "key_force_mx", "key_def_mx",
         "key_break_time_mx", "keys_broken"]
for cell, run in ((0, "keys-run"), (1, "keys-rerun")):
    j = h5py.File(f"{work}/{run}.h5", "r")["joints"]
    assert [n.decode() if isinstance(n, bytes) else n for n in j.attrs["response_names"]] == names, j.attrs["response_names"]
    for n in names:
        assert r[n][cell] == j.attrs[n], (cell, n, r[n][cell], j.attrs[n])
    # Per abutment: the largest and the earliest over its two keys, the count over all four.
    keys = [k.decode() if isinstance(k, bytes) else k for k in j.attrs["key_names"]]
    assert keys == ["+x.key+y", "+x.key-y", "-x.key+y", "-x.key-y"], keys
    t, f = j["key_break_time_s"][()], j["key_force_N"][()]
    for a, side in ((0, "px"), (2, "mx")):
        assert r["key_break_time_" + side][cell] == min(t[a], t[a + 1]), (cell, side, t)
        assert r["key_force_" + side][cell] == max(f[a], f[a + 1]), (cell, side, f)
    assert r["keys_broken"][cell] == sum(math.isfinite(x) for x in t), (cell, t)
    text = open(f"{work}/{run}.out").read()
    for k, name in enumerate(keys):
        m = re.search(r"shear key " + re.escape(name) + r": largest force (\S+) N, largest deformation (\S+) m, (intact|broke at (\S+) s)$", text, re.M)
        assert m, text
        assert abs(float(m.group(1)) - f[k]) <= 1e-6 * f[k], (name, m.group(1), f[k])
        assert (m.group(3) == "intact") == math.isinf(t[k]), (name, m.group(3), t[k])
        if m.group(4):
            assert abs(float(m.group(4)) - t[k]) <= 1e-6, (name, m.group(4), t[k])
# At scale 3 a key breaks: a finite break time; at scale 1 the keys hold (inf, stored as such).
assert r["keys_broken"][1] > 0 and math.isfinite(min(r["key_break_time_px"][1], r["key_break_time_mx"][1])), r["keys_broken"][()]
assert r["key_break_time_px"].attrs["units"] in (b"s", "s"), dict(r["key_break_time_px"].attrs)
PY

# The keys' cube read back: `inspect` lists the break times with their unit, and the report's table
# of responses counts a cell whose keys held (inf) as a cell with a value and prints "inf", the
# finite break of the other cell as its min (docs/compliant.md §4, Shear keys in the model file).
"$exe" inspect "$work/keys.h5" >"$work/inspect.out" 2>&1 || fail "inspect: exit $? ($(cat "$work/inspect.out"))"
grep -Eq "key_break_time_px +\[s\]" "$work/inspect.out" || fail "inspect: $(cat "$work/inspect.out")"
/usr/bin/python3 "$src/scripts/report" "$work/keys.h5" --out "$work/report" >"$work/report.out" 2>&1 ||
  fail "report of the keys' cube: exit $? ($(cat "$work/report.out"))"
/usr/bin/python3 - "$work" <<'PY' || fail "the report's rows of the break times (above)"
import sys, math, h5py
work = sys.argv[1]
r = h5py.File(f"{work}/keys.h5", "r")["sweeps/compliant/responses"]
rows = {l.split("|")[1].strip(): [c.strip() for c in l.split("|")[1:-1]]
        for l in open(f"{work}/report/summary.md") if l.startswith("| key_break_time")}
for side in ("px", "mx"):
    t = r["key_break_time_" + side][()]
    row = rows["key_break_time_" + side]
    assert row[2] == "2", row  # both cells have a value, inf included
    finite = [x for x in t if math.isfinite(x)]
    assert row[3] == (f"{min(finite):.4g}" if finite else "inf"), (row, t)
    assert row[5] == ("inf" if any(math.isinf(x) for x in t) else f"{max(t):.4g}"), (row, t)
assert any("inf" in row[3:6] for row in rows.values()), rows  # at scale 1 the keys hold
PY

# A law per wall (docs/examples/pilot-bridge-one-keyed-abutment.toml): `skewbridge run` names each
# wall's springs and the keyed abutment; the run file holds 5 springs at +x and 7 at -x, keys at +x
# only (the -x abutment's key responses 0 and inf), and each spring's largest force is its own
# wall's envelope F = d / (1/K_max + R_f d / F_ult) at its largest deformation d, with each wall's
# constants worked here by hand (+x: Wilson and Elgamal per metre over W / cos a; -x: the Caltrans
# rules for w = 19.36 m, h = 3.0 m at 20 deg), an n-th per spring; the other wall's law misses.
cp "$src/docs/examples/pilot-bridge-one-keyed-abutment.toml" "$work/"
"$exe" run "$work/pilot-bridge-one-keyed-abutment.toml" --out "$work/one-keyed.h5" \
  >"$work/one-keyed.out" 2>&1 || fail "run one-keyed: exit $? ($(cat "$work/one-keyed.out"))"
grep -q "compliant abutments, 5 springs on the +x wall, 7 on the -x wall and two shear keys at the +x abutment; backfill and keys' energy" \
  "$work/one-keyed.out" || fail "one-keyed summary: $(cat "$work/one-keyed.out")"
/usr/bin/python3 - "$work" <<'PY' || fail "a law per wall: the run file against the walls' envelopes (above)"
import sys, math, h5py
work = sys.argv[1]
j = h5py.File(f"{work}/one-keyed.h5", "r")["joints"]
text = lambda v: [n.decode() if isinstance(n, bytes) else n for n in v]
names = text(j.attrs["spring_names"])
assert names == [f"+x.{k}" for k in range(1, 6)] + [f"-x.{k}" for k in range(1, 8)], names
assert text(j.attrs["key_names"]) == ["+x.key+y", "+x.key-y"], j.attrs["key_names"]
assert j.attrs["key_force_px"] > 0 and j.attrs["key_force_mx"] == 0, dict(j.attrs)
assert math.isinf(j.attrs["key_break_time_mx"]), j.attrs["key_break_time_mx"]
kip_per_in, kip, ft = 4448.2216152605 / 0.0254, 4448.2216152605, 0.3048
wall_m = 19.36 / math.cos(math.radians(20.0))
w, h, r_sk = 19.36 / ft, 3.0 / ft, math.exp(-20.0 / 45.0)
k_c, p_c = w * (5.5 * h + 20.0) * r_sk * kip_per_in, w * 5.5 * h**2.5 / (1.0 + 2.37 * h) * r_sk * kip
laws = {"+x": (20.3e6 * wall_m / 5, 0.7, 326e3 * wall_m / 5),
        "-x": (k_c / 7, 1.0 - p_c / (k_c * 0.05 * 3.0), p_c / 7)}
envelope = lambda law, d: d / (1.0 / law[0] + law[1] * d / law[2])
force, deformation = j["spring_force_N"][()], j["spring_deformation_m"][()]
for name, f, d in zip(names, force, deformation):
    own, other = (("+x", "-x") if name[:2] == "+x" else ("-x", "+x"))
    assert d > 0, (name, d)
    assert abs(f - envelope(laws[own], d)) <= 1e-12 * f, (name, f, envelope(laws[own], d))
    assert abs(f - envelope(laws[other], d)) > 0.03 * f, (name, f, envelope(laws[other], d))
assert j.attrs["spring_force_mx"] == max(force[5:]) and j.attrs["backwall_def_mx"] == max(deformation[5:])
PY

# A rigid file's cube holds no compliant response.
cp "$src/docs/examples/pilot-bridge.toml" "$work/"
sed 's/pilot-bridge-compliant.toml/pilot-bridge.toml/' "$work/spec.toml" >"$work/rigid.toml"
on_ranks 2 "$exe" sweep "$work/rigid.toml" --out "$work/rigid.h5" --quiet >"$work/sweep.out" 2>&1 ||
  fail "rigid sweep: exit $? ($(cat "$work/sweep.out"))"
/usr/bin/python3 -c "
import h5py, sys
r = h5py.File('$work/rigid.h5', 'r')['sweeps/compliant/responses']
assert not any(k.startswith(('spring_force', 'backwall_def', 'key')) for k in r), list(r)
" || fail "a rigid cube stores compliant responses"

# A sweep's mu is the compliant walls' friction (abutments.mu): each cell of a 2-rank sweep over
# mu equals `skewbridge run` of the model file with that mu written in, bit for bit (the deck's
# maxima, residuals and strikes, the joints' responses), and mu = 0 the frictionless run, also
# over a file whose own mu and stick stiffness the sweep replaces. The signal at 45 deg from x,
# doubled, presses the deck into both walls and slides it along them: the friction changes the
# response (5.6 kJ of friction at mu = 0.3).
sed 's/^direction = "x"/angle_deg = 45.0\nscale = 2.0/' "$work/pilot-bridge-compliant.toml" >"$work/wall.toml"
sed 's/^law = "compliant"$/&\nmu = 0.3/' "$work/wall.toml" >"$work/wall-mu.toml"
sed 's/^law = "compliant"$/&\nmu = 0.1\nstick_stiffness_Npm = 2e8/' "$work/wall.toml" >"$work/wall-kt.toml"
sed 's/^mu = 0.1$/mu = 0.3/' "$work/wall-kt.toml" >"$work/wall-kt-mu.toml"
grep -q "^mu = 0.3" "$work/wall-kt-mu.toml" || fail "wall-kt-mu.toml: $(cat "$work/wall-kt-mu.toml")"
for model in wall wall-mu wall-kt-mu; do
  "$exe" run "$work/$model.toml" --out "$work/$model.h5" >"$work/$model.out" 2>&1 ||
    fail "run $model.toml: exit $? ($(cat "$work/$model.out"))"
done
for model in wall wall-kt; do
  printf '[sweep]\nname = "mu"\nfamily = "model-file"\nmodel = "%s.toml"\n[axes]\nmu = [0.0, 0.3]\n' \
    "$model" >"$work/$model-spec.toml"
  on_ranks 2 "$exe" sweep "$work/$model-spec.toml" --out "$work/$model-cube.h5" --quiet \
    >"$work/sweep.out" 2>&1 || fail "sweep of mu over $model.toml: exit $? ($(cat "$work/sweep.out"))"
done
/usr/bin/python3 - "$work" <<'PY' || fail "a sweep's mu against run with mu written in (above)"
import sys, h5py
work = sys.argv[1]
def run(name):
    f = h5py.File(f"{work}/{name}.h5", "r")
    s, j = f["summary"], f["joints"]
    out = {"impacts": s.attrs["impacts"]}
    for i, n in enumerate(("x", "y", "theta")):
        out[n + "_m_d0"], out[n + "_end_d0"] = s["max_abs_q"][i], s["q_end"][i]
    for n in j.attrs["response_names"]:
        n = n.decode() if isinstance(n, bytes) else n
        out[n] = j.attrs[n]
    return out
frictionless, runs = run("wall"), {"wall": run("wall-mu"), "wall-kt": run("wall-kt-mu")}
changed = [n for n in frictionless if runs["wall"][n] != frictionless[n]]
assert "y_m_d0" in changed and "x_end_d0" in changed, ("mu = 0.3 changes too little", changed)
# The springs slip along the walls with friction, none without.
slip = {m: h5py.File(f"{work}/{m}.h5", "r")["joints/spring_slip_m"][()] for m in ("wall", "wall-mu")}
assert not slip["wall"].any() and slip["wall-mu"].max() > 0 and (slip["wall-mu"] >= 0).all(), slip
for model in ("wall", "wall-kt"):
    g = h5py.File(f"{work}/{model}-cube.h5", "r")["sweeps/mu"]
    assert list(g["mu"][()]) == [0.0, 0.3], g["mu"][()]
    r = g["responses"]
    for cell, want in ((0, frictionless), (1, runs[model])):
        for n, v in want.items():
            assert r[n][cell] == v, (model, cell, n, r[n][cell], v)
PY

# A row of decks with compliant joints (docs/examples/three-span-compliant.toml): a 2-rank sweep
# over mu (the backwalls' friction) equals `skewbridge run` of the file with that mu written in, bit
# for bit, the joints' responses (joint_force_j0, ...) among them.
cp "$src/docs/examples/three-span-compliant.toml" "$work/"
sed 's/^law = "compliant"$/&\nmu = 0.3/' "$work/three-span-compliant.toml" |
  awk '/^\[abutments\]/ { a = 1 } a || !/^mu = 0.3$/' >"$work/span-mu.toml"
[ "$(grep -c '^mu = 0.3' "$work/span-mu.toml")" -eq 1 ] || fail "span-mu.toml: $(cat "$work/span-mu.toml")"
for model in three-span-compliant span-mu; do
  "$exe" run "$work/$model.toml" --out "$work/$model.h5" >"$work/$model.out" 2>&1 ||
    fail "run $model.toml: exit $? ($(cat "$work/$model.out"))"
done
grep -q "deck-deck joint J1: largest spring force" "$work/three-span-compliant.out" ||
  fail "no joint line: $(cat "$work/three-span-compliant.out")"
printf '[sweep]\nname = "mu"\nfamily = "model-file"\nmodel = "three-span-compliant.toml"\n[axes]\nmu = [0.0, 0.3]\n' \
  >"$work/span-spec.toml"
on_ranks 2 "$exe" sweep "$work/span-spec.toml" --out "$work/span-cube.h5" --quiet \
  >"$work/sweep.out" 2>&1 || fail "sweep over three-span-compliant.toml: exit $? ($(cat "$work/sweep.out"))"
/usr/bin/python3 - "$work" <<'PY' || fail "a row of compliant decks: the sweep against run (above)"
import sys, h5py
work = sys.argv[1]
r = h5py.File(f"{work}/span-cube.h5", "r")["sweeps/mu/responses"]
for cell, name in ((0, "three-span-compliant"), (1, "span-mu")):
    f = h5py.File(f"{work}/{name}.h5", "r")
    s, j = f["summary"], f["joints"]
    names = [n.decode() if isinstance(n, bytes) else n for n in j.attrs["response_names"]]
    assert names[4:] == ["joint_force_j0", "joint_def_j0", "joint_force_j1", "joint_def_j1"], names
    for n in names:
        assert r[n][cell] == j.attrs[n], (cell, n, r[n][cell], j.attrs[n])
    assert j.attrs["joint_force_j0"] > 0 and j.attrs["joint_force_j1"] > 0, dict(j.attrs)
    for d in range(3):
        for i, q in enumerate(("x", "y", "theta")):
            assert r[f"{q}_m_d{d}"][cell] == s["max_abs_q"][3 * d + i], (cell, q, d)
            assert r[f"{q}_end_d{d}"][cell] == s["q_end"][3 * d + i], (cell, q, d)
    assert r["impacts"][cell] == s.attrs["impacts"], cell
assert r["x_end_d0"][0] != r["x_end_d0"][1], "mu changed nothing"
PY

# eps_N means nothing to the springs: one line, status 2, no cube.
printf 'eps_N = [0.3, 0.6]\n' >>"$work/spec.toml"
status=0
on_ranks 1 "$exe" sweep "$work/spec.toml" --out "$work/bad.h5" --quiet >"$work/bad.out" 2>&1 || status=$?
[ "$status" -eq 2 ] || fail "a sweep of eps_N on compliant abutments: exit $status, expected 2"
grep -q "spec.toml:9: axes.eps_N: the abutments of pilot-bridge-compliant.toml are compliant" "$work/bad.out" ||
  fail "no eps_N refusal: $(cat "$work/bad.out")"
[ ! -e "$work/bad.h5" ] || fail "a refused sweep left a cube"
echo "ok"
