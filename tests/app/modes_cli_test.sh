#!/usr/bin/env bash
# `skewbridge modes` and `skewbridge run` of a substructure from elements: the frequencies,
# principal axes and centre of rigidity printed for docs/examples/pilot-elements.toml against a
# hand calculation (four bearings on the ground in parallel with two bearing-pier series springs,
# along the piers' axes at 20 and 110 deg); a bad model gives exit 2 and one line naming the key.
set -u
exe=${1:?usage: modes_cli_test.sh SKEWBRIDGE SOURCE_ROOT}
root=${2:?}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
model="$root/docs/examples/pilot-elements.toml"

"$exe" modes "$model" >"$work/out" 2>"$work/err" || fail "modes: exit $? ($(cat "$work/err"))"
# Hand calculation (kN/m -> N/m): s = k_b k_p / (k_b + k_p); K = 4 k_b + 2 s per pier axis;
# w = sqrt(K / m).
read -r w_weak w_strong < <(awk 'BEGIN {
  kb = 34776e3; ks = 111199e3; kw = 81990e3; m = 1547e3;
  printf "%.6g %.6g\n", sqrt((4 * kb + 2 * kb * kw / (kb + kw)) / m),
                        sqrt((4 * kb + 2 * kb * ks / (kb + ks)) / m) }')
grep -q "mode 1: w = $w_weak rad/s" "$work/out" || fail "modes: no 'mode 1: w = $w_weak rad/s' in: $(cat "$work/out")"
grep -q "mode 2: w = $w_strong rad/s" "$work/out" || fail "modes: no 'mode 2: w = $w_strong rad/s'"
f_weak=$(awk -v w="$w_weak" 'BEGIN { printf "%.4g", w / (2 * 3.14159265358979) }')
grep -q "f = ${f_weak}[0-9]* Hz" "$work/out" || fail "modes: no f = $f_weak Hz"
grep -q "at -70.0000 deg from x" "$work/out" || fail "modes: weak principal axis not at -70 deg"
grep -q "at 20.0000 deg" "$work/out" || fail "modes: strong principal axis not at 20 deg"
grep -q "centre of rigidity: e_x = 0 m, e_y = 0 m" "$work/out" || fail "modes: centre of rigidity"
grep -q "rho theta" "$work/out" || fail "modes: no mode shapes"

"$exe" run "$model" >"$work/run" 2>&1 || fail "run: exit $? ($(cat "$work/run"))"
grep -q "status ok" "$work/run" || fail "run: no 'status ok'"
grep -q "mode 1: w = $w_weak rad/s" "$work/run" || fail "run: frequencies not printed"
grep -q "centre of rigidity: e_x = 0 m, e_y = 0 m" "$work/run" || fail "run: centre of rigidity not printed"

# The principal-axes example has no elements: modes still prints its (published) frequencies.
"$exe" modes "$root/docs/examples/pilot-bridge.toml" >"$work/pilot" 2>&1 || fail "pilot: exit $?"
grep -q "centre of rigidity: e_x = -0.24 m, e_y = 0.01 m" "$work/pilot" ||
  fail "pilot: centre of rigidity not (-0.24, 0.01): $(cat "$work/pilot")"

# Several decks on their own supports: each deck's centre of rigidity is its mass centre and its
# torsion there is the k_theta the file gives that deck's [[support]].
three="$root/docs/examples/three-span.toml"
"$exe" modes "$three" >"$work/three" 2>&1 || fail "three-span: exit $?"
expected=$(awk '/^k_theta/ {printf "%.6e\n", $3}' "$three")
printed=$(awk '/^torsion about the centre of rigidity/ {print $7}' "$work/three")
[ -n "$expected" ] && [ "$printed" = "$expected" ] ||
  fail "three-span: torsion per deck '$printed', expected '$expected'"
[ "$(grep -c "centre of rigidity: e_x = 0 m, e_y = 0 m" "$work/three")" -eq 3 ] ||
  fail "three-span: not three centres at the mass centres: $(cat "$work/three")"

sed 's/^k_weak_Npm = 81990e3/k_weak_Npm = -1/' "$model" >"$work/bad.toml"
"$exe" modes "$work/bad.toml" >"$work/out3" 2>"$work/err3"
status=$?
[ $status -eq 2 ] || fail "bad model: exit status $status, expected 2"
[ "$(wc -l <"$work/err3")" -eq 1 ] || fail "bad model: message is not one line: $(cat "$work/err3")"
grep -q "bad.toml:[0-9]*: substructure.pier\[0\].k_weak_Npm: must be > 0" "$work/err3" ||
  fail "bad model: message does not name the key: $(cat "$work/err3")"
echo "ok"
