#!/usr/bin/env bash
# A row of decks with rigid and compliant parts (docs/examples/three-span.toml with joint[0] and
# the +x abutment rigid, joint[1] a spring-dashpot and the -x abutment a Caltrans backfill) through
# `skewbridge run --out` and a model-file sweep on 2 ranks over mu and eps_N: every cell's status
# is ok and its responses are a rigid cube's (the same spec over the row with every part rigid)
# plus the compliant wall's spring_force_mx, backwall_def_mx and the compliant joint's
# joint_force_j1, joint_def_j1 only; each cell equals `skewbridge run` of the file with that mu and
# eps_N written on the rigid abutment and the rigid joint (and mu on the backwall), bit for bit;
# the run file's group `joints` holds the -x wall's and joint[1]'s springs only; rigid corners are
# struck (impact_J > 0) and the ledger closes to 1e-6 of the input; `run --from-cube` re-runs a
# cell with the cube's bits.
# usage: mixed_row_test.sh SKEWBRIDGE MPIEXEC SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe mpiexec src -- "$@"
temp_dir

cd "$work"
# joint[0] (lines 25-28) rigid, joint[1] (30-33) a spring-dashpot, [abutments] (38-41) a law per
# abutment; EPS and MU are each run's values.
sed -e '26a law = "impact"' -e 's/^eps_N = 0.5/eps_N = EPS/' -e 's/^mu = 0.2/mu = MU/' \
  -e '32,33c law = "compliant"\n\n[joint.spring_dashpot]\nk_Npm = 1.0e9\nc_Nspm = 7.4e6' \
  -e '41a law = { "+x" = "impact", "-x" = "compliant" }\nsprings = 5\n\n[abutments.backfill]\nform = "caltrans"\nwidth_m = 12.0\nheight_m = 2.0' \
  -e 's/^gap_m = 0.05/gap_m = 0.03/' \
  "$src/docs/examples/three-span.toml" >template.toml
sed -e 's/EPS/0.5/' -e 's/MU/0.2/' template.toml >mixed.toml
# The same row with every part rigid, for the responses of a rigid cube.
sed -e 's/EPS/0.5/' -e 's/MU/0.2/' -e '32,33c eps_N = 0.5\nmu = 0.2' "$src/docs/examples/three-span.toml" |
  sed -e 's/^gap_m = 0.05/gap_m = 0.03/' >rigid.toml
for eps in 0.5 0.8; do
  for mu in 0.0 0.3; do
    sed -e "s/EPS/$eps/" -e "s/MU/$mu/" template.toml >"run_${eps}_$mu.toml"
    "$exe" run "run_${eps}_$mu.toml" --out "run_${eps}_$mu.h5" >"run_${eps}_$mu.out" 2>&1 ||
      fail "run eps_N = $eps, mu = $mu: exit $? ($(cat "run_${eps}_$mu.out"))"
  done
done
grep -q "compliant parts -x wall (5 springs), J1 (5 springs); rigid: +x wall, J0; " run_0.5_0.3.out ||
  fail "no compliant parts line in the summary: $(cat run_0.5_0.3.out)"
grep -q "^  deck-deck joint J1: largest spring force" run_0.5_0.3.out || fail "no J1 line"
grep -q "^  deck-deck joint J0" run_0.5_0.3.out && fail "a J0 line for the rigid joint"
for model in mixed rigid; do
  cat >"spec_$model.toml" <<TOML
[sweep]
name = "row"
family = "model-file"
model = "$model.toml"
[axes]
mu = [0.0, 0.3]
eps_N = [0.5, 0.8]
TOML
  on_ranks 2 "$exe" sweep "spec_$model.toml" --out "cube_$model.h5" --quiet >"sweep_$model.out" 2>&1 ||
    fail "sweep of $model.toml: exit $? ($(cat "sweep_$model.out"))"
done

/usr/bin/python3 - <<'PY' || fail "the cube against the runs (above)"
import h5py
g = h5py.File("cube_mixed.h5", "r")["sweeps/row"]
rigid = h5py.File("cube_rigid.h5", "r")["sweeps/row"]
assert list(g["status"][()].ravel()) == [0, 0, 0, 0], g["status"][()]
r = g["responses"]
names, rigid_names = list(r.keys()), list(rigid["responses"].keys())
extra = ["spring_force_mx", "backwall_def_mx", "joint_force_j1", "joint_def_j1"]
assert sorted(names) == sorted(rigid_names + extra), (names, rigid_names)
order = [a.decode() if isinstance(a, bytes) else a for a in g.attrs["axis_order"]]
assert order == ["eps_N", "mu"], order
for i, eps in enumerate(("0.5", "0.8")):
    for k, mu in enumerate(("0.0", "0.3")):
        f = h5py.File(f"run_{eps}_{mu}.h5", "r")
        s, j = f["summary"], f["joints"]
        for d in range(3):
            for c, n in enumerate(("x", "y", "theta")):
                assert r[f"{n}_m_d{d}"][i, k] == s["max_abs_q"][3 * d + c], (eps, mu, n, d)
                assert r[f"{n}_end_d{d}"][i, k] == s["q_end"][3 * d + c], (eps, mu, n, d)
        assert r["impacts"][i, k] == s.attrs["impacts"], (eps, mu, r["impacts"][i, k])
        e = f["energy"].attrs
        assert e["impact_J"] > 0, (eps, mu, "no rigid corner struck")
        assert abs(e["balance_error_J"]) < 1e-6 * e["input_J"], (eps, mu, dict(e))
        for n in extra:
            assert r[n][i, k] == j.attrs[n], (eps, mu, n, r[n][i, k], j.attrs[n])
            assert r[n][i, k] > 0, (eps, mu, n)
        springs = [n.decode() if isinstance(n, bytes) else n for n in j.attrs["spring_names"]]
        assert springs == [f"-x.{m}" for m in range(1, 6)] + [f"J1.{m}" for m in range(1, 6)], springs
        assert "spring_force_px" not in j.attrs and "joint_force_j0" not in j.attrs, dict(j.attrs)
assert r["x_m_d0"][0, 0] != r["x_m_d0"][0, 1], "mu changes nothing"
assert r["x_m_d2"][0, 1] != r["x_m_d2"][1, 1], "eps_N changes nothing"
PY

# A cell run again from the cube (eps_N = 0.8, mu = 0.3): the same bits, the same compliant parts.
"$exe" run --from-cube cube_mixed.h5 --cell-index 3 --out rerun.h5 >rerun.out 2>&1 ||
  fail "run --from-cube: exit $? ($(cat rerun.out))"
grep -q "compliant parts -x wall (5 springs), J1 (5 springs); rigid: +x wall, J0; " rerun.out ||
  fail "run --from-cube ran other parts: $(cat rerun.out)"
/usr/bin/python3 - <<'PY' || fail "run --from-cube against the cube (above)"
import h5py
r = h5py.File("cube_mixed.h5", "r")["sweeps/row/responses"]
s = h5py.File("rerun.h5", "r")["summary"]
j = h5py.File("rerun.h5", "r")["joints"]
for d in range(3):
    for c, n in enumerate(("x", "y", "theta")):
        assert s["max_abs_q"][3 * d + c] == r[f"{n}_m_d{d}"][1, 1], (n, d)
assert s.attrs["impacts"] == r["impacts"][1, 1]
assert j.attrs["joint_force_j1"] == r["joint_force_j1"][1, 1]
assert j.attrs["spring_force_mx"] == r["spring_force_mx"][1, 1]
PY
echo "ok"
