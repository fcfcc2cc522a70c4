#!/usr/bin/env bash
# `skewbridge modes` and `skewbridge run` of a substructure from elements: the frequencies,
# principal axes and centre of rigidity printed for docs/examples/pilot-elements.toml against a
# hand calculation (ten bearings on the ground in parallel with two columns built into the deck,
# along the columns' axes at 20 and 110 deg) and against the paper's pilot bridge (18 / 19 rad/s,
# e = (-0.24, 0.01) m); a bad model gives exit 2 and one line naming the key.
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe root -- "$@"
temp_dir
model="$root/docs/examples/pilot-elements.toml"

"$exe" modes "$model" >"$work/out" 2>"$work/err" || fail "modes: exit $? ($(cat "$work/err"))"
# Hand calculation (kN/m -> N/m): principal stiffnesses K = 10 k_b + 2 k_column per column axis;
# the modes, coupled by the small eccentricity, stay within 0.1 % of sqrt(K / m).
read -r k_weak k_strong w_weak w_strong < <(awk 'BEGIN {
  kb = 34776e3; ks = 111199e3; kw = 81990e3; m = 1547e3;
  printf "%.6e %.6e %.6g %.6g\n", 10 * kb + 2 * kw, 10 * kb + 2 * ks,
                                 sqrt((10 * kb + 2 * kw) / m), sqrt((10 * kb + 2 * ks) / m) }')
grep -q "k1 = $k_weak N/m at 20.0000 deg from x, k2 = $k_strong N/m" "$work/out" ||
  fail "modes: no 'k1 = $k_weak N/m at 20.0000 deg from x, k2 = $k_strong N/m' in: $(cat "$work/out")"
for k in 1 2; do
  want=$([ $k -eq 1 ] && echo "$w_weak" || echo "$w_strong")
  got=$(awk -v k="mode $k:" 'index($0, k) { print $5 }' "$work/out")
  awk -v a="$got" -v b="$want" 'BEGIN { d = a / b - 1; exit !(d < 1e-3 && d > -1e-3) }' ||
    fail "modes: mode $k at '$got' rad/s, expected about $want"
  f_want=$(awk -v w="$got" 'BEGIN { printf "%.6g", w / (2 * 3.14159265358979) }')
  grep -q "mode $k: w = $got rad/s, f = $f_want Hz" "$work/out" || fail "modes: no f = $f_want Hz"
done
grep -q "at 20.0000 deg from x" "$work/out" || fail "modes: weak principal axis not at 20 deg"
grep -q "at 110.0000 deg" "$work/out" || fail "modes: strong principal axis not at 110 deg"
# The paper's centre of rigidity, to its 0.01 m.
awk '/^centre of rigidity/ { ex = $6; ey = $10 }
     END { exit !(ex + 0.24 < 5e-3 && ex + 0.24 > -5e-3 && ey - 0.01 < 5e-3 && ey - 0.01 > -5e-3) }' \
  "$work/out" || fail "modes: centre of rigidity not (-0.24, 0.01) m: $(grep centre "$work/out")"
grep -q "rho theta" "$work/out" || fail "modes: no mode shapes"

"$exe" run "$model" >"$work/run" 2>&1 || fail "run: exit $? ($(cat "$work/run"))"
grep -q "status ok" "$work/run" || fail "run: no 'status ok'"
grep -q "mode 1: w = 18.18" "$work/run" || fail "run: frequencies not printed"
grep -q "centre of rigidity: e_x = -0.2" "$work/run" || fail "run: centre of rigidity not printed"

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
status=0
"$exe" modes "$work/bad.toml" >"$work/out3" 2>"$work/err3" || status=$?
[ $status -eq 2 ] || fail "bad model: exit status $status, expected 2"
[ "$(wc -l <"$work/err3")" -eq 1 ] || fail "bad model: message is not one line: $(cat "$work/err3")"
grep -q "bad.toml:[0-9]*: substructure.bearing\[0\].k_weak_Npm: must be >= 0" "$work/err3" ||
  fail "bad model: message does not name the key: $(cat "$work/err3")"
echo "ok"
