#!/usr/bin/env bash
# A model file's law per abutment ([abutments] law = { "+x" = "impact", "-x" = "compliant" },
# docs/examples/pilot-bridge-mixed.toml) through `skewbridge run --out` and a model-file sweep on
# 2 ranks over mu and eps_N (gaps of 4 mm, the signal at 30 deg from x so that both walls are
# struck and friction acts): every cell's status is ok and its responses are a rigid cube's (the
# same spec over the file under law = "impact") plus the compliant wall's spring_force_mx and
# backwall_def_mx only; the cells at eps_N = 0.5 equal `skewbridge run` of the file with that mu
# written as one number for both walls, bit for bit (the sweep's mu is the rigid corners' and the
# backwall's alike), and the two mu differ; `run --from-cube` re-runs a cell with the same bits;
# the run file's group `joints` holds the -x wall's springs only.
# usage: mixed_law_test.sh SKEWBRIDGE MPIEXEC SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec src -- "$@"
temp_dir

cp "$src/docs/examples/pilot-bridge-mixed.toml" "$src/docs/examples/pilot-signal.txt" "$work/"
cd "$work"
"$exe" run pilot-bridge-mixed.toml --out run.h5 >run.out 2>&1 || fail "run: exit $? ($(cat run.out))"
grep -q "compliant abutment -x (the +x abutment rigid), 5 springs; backfill energy" run.out ||
  fail "no compliant line in the summary: $(cat run.out)"
grep -q "^  -x wall: largest spring force" run.out || fail "no -x wall line: $(cat run.out)"
grep -q "^  +x wall" run.out && fail "a +x wall line for the rigid wall: $(cat run.out)"

sed 's/^gap_m = .*/gap_m = 0.004/' pilot-bridge-mixed.toml >mixed.toml
for mu in 0.0 0.3; do
  sed "s/^mu = .*/mu = $mu/" mixed.toml >"mu$mu.toml"
  "$exe" run "mu$mu.toml" --incidence-deg 30 --out "mu$mu.h5" >"mu$mu.out" 2>&1 ||
    fail "run mu = $mu: exit $? ($(cat "mu$mu.out"))"
done
# The same bridge under the rigid law at both abutments, for the responses of a rigid cube.
awk '/^\[abutments.backfill\]/ { skip = 1; next } /^\[/ { skip = 0 } !skip' mixed.toml |
  sed -e 's/^law = .*/law = "impact"/' -e 's/^mu = .*/mu = 0.3/' -e '/^springs = /d' >rigid.toml
for model in mixed rigid; do
  cat >"spec_$model.toml" <<TOML
[sweep]
name = "law"
family = "model-file"
model = "$model.toml"
[limit_states]
joint_closing = true
[fixed]
incidence_deg = 30.0
seat_over_L = 0.01
[axes]
mu = [0.0, 0.3]
eps_N = [0.5, 0.8]
TOML
  on_ranks 2 "$exe" sweep "spec_$model.toml" --out "cube_$model.h5" --quiet >"sweep_$model.out" 2>&1 ||
    fail "sweep of $model.toml: exit $? ($(cat "sweep_$model.out"))"
done

/usr/bin/python3 - <<'PY' || fail "the cube against the runs (above)"
import h5py
g = h5py.File("cube_mixed.h5", "r")["sweeps/law"]
rigid = h5py.File("cube_rigid.h5", "r")["sweeps/law"]
assert list(g["status"][()].ravel()) == [0, 0, 0, 0], g["status"][()]
r = g["responses"]
names, rigid_names = list(r.keys()), list(rigid["responses"].keys())
assert sorted(names) == sorted(rigid_names + ["spring_force_mx", "backwall_def_mx"]), (names, rigid_names)
# The cells at eps_N = 0.5 (the cube's axes in the order of their names: eps_N, then mu) against
# `run` of the file with that mu.
assert [a.decode() if isinstance(a, bytes) else a for a in g.attrs["axis_order"]] == ["eps_N", "mu"], g.attrs["axis_order"]
for i, mu in ((0, "0.0"), (1, "0.3")):
    s = h5py.File(f"mu{mu}.h5", "r")["summary"]
    j = h5py.File(f"mu{mu}.h5", "r")["joints"]
    for k, n in enumerate(("x", "y", "theta")):
        assert r[n + "_m_d0"][0, i] == s["max_abs_q"][k], (mu, n, r[n + "_m_d0"][0, i], s["max_abs_q"][k])
        assert r[n + "_end_d0"][0, i] == s["q_end"][k], (mu, n)
    assert r["impacts"][0, i] == s.attrs["impacts"], (mu, r["impacts"][0, i], s.attrs["impacts"])
    for k in ("spring_force_mx", "backwall_def_mx"):
        assert r[k][0, i] == j.attrs[k], (mu, k, r[k][0, i], j.attrs[k])
    assert r["spring_force_mx"][0, i] > 0 and r["impacts"][0, i] > 2, (mu, r["impacts"][0, i])
    springs = [n.decode() if isinstance(n, bytes) else n for n in j.attrs["spring_names"]]
    assert springs == [f"-x.{k}" for k in range(1, 6)], springs
    assert "spring_force_px" not in j.attrs, dict(j.attrs)
assert r["x_m_d0"][0, 0] != r["x_m_d0"][0, 1], "mu changes nothing"
assert r["x_m_d0"][0, 1] != r["x_m_d0"][1, 1], "eps_N changes nothing"
PY

# A cell run again from the cube (eps_N = 0.8, mu = 0.3): the same bits.
"$exe" run --from-cube cube_mixed.h5 --cell-index 3 --out rerun.h5 >rerun.out 2>&1 ||
  fail "run --from-cube: exit $? ($(cat rerun.out))"
grep -q "compliant abutment -x (the +x abutment rigid)" rerun.out ||
  fail "run --from-cube ran no springs: $(cat rerun.out)"
/usr/bin/python3 - <<'PY' || fail "run --from-cube against the cube (above)"
import h5py
r = h5py.File("cube_mixed.h5", "r")["sweeps/law/responses"]
s = h5py.File("rerun.h5", "r")["summary"]
j = h5py.File("rerun.h5", "r")["joints"]
for k, n in enumerate(("x", "y", "theta")):
    assert s["max_abs_q"][k] == r[n + "_m_d0"][1, 1], (n, s["max_abs_q"][k], r[n + "_m_d0"][1, 1])
assert s.attrs["impacts"] == r["impacts"][1, 1]
assert j.attrs["spring_force_mx"] == r["spring_force_mx"][1, 1]
PY
echo "ok"
