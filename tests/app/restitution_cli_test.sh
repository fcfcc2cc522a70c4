#!/usr/bin/env bash
# `skewbridge restitution`, the bridge between the compliant and the rigid joint, through the
# program as a user runs it:
#  - a linear spring-dashpot that pulls on nothing against its closed form: undamped, the half
#    period pi sqrt(m / k) and e = 1 (the textbook pi / w_d and exp(-zeta pi / sqrt(1 - zeta^2))
#    at zeta = 0); damped, the contact ends where k d + c d' = 0, before the spring's length
#    (Schwager and Poeschel 2007), on both branches of that root (zeta 0.2 and 0.8);
#  - the hyperbolic backfill over a range of approach speeds against closed forms computed here
#    with scipy (d_max from the envelope's energy, exit speed F(d_max) / sqrt(m K_ur), the
#    permanent set d_max - F(d_max) / K_ur, the contact as the envelope's loading time plus the
#    quarter period of the unloading line), with K_ur != K_max;
#  - the Caltrans SDC 2.0 form's stiffness and capacity against the hand formulas;
#  - bad input: one line naming the field, exit status 2, nothing on stdout.
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe -- "$@"
temp_dir

# A bad input: exactly the line `skewbridge: error: restitution: MESSAGE`, exit 2, empty stdout.
refuse() {
  local message=$1 status=0
  shift
  "$exe" restitution "$@" >"$work/out" 2>"$work/err" || status=$?
  [ "$status" -eq 2 ] || fail "restitution $*: exit $status, expected 2"
  [ ! -s "$work/out" ] || fail "restitution $*: wrote to stdout: $(head -3 "$work/out")"
  [ "$(wc -l <"$work/err")" -eq 1 ] || fail "restitution $*: not one line: $(cat "$work/err")"
  [ "$(cat "$work/err")" = "skewbridge: error: restitution: $message" ] ||
    fail "restitution $*: '$(cat "$work/err")', expected 'skewbridge: error: restitution: $message'"
}

# --- the linear spring-dashpot against its closed form ---
m=1547e3
k=2e9
for zeta in 0 0.2 0.8; do
  "$exe" restitution --mass-kg $m --spring-Npm $k --damping-ratio $zeta --velocity-mps 0.3 1.2 \
    --csv >"$work/lin_$zeta.csv" 2>"$work/err" || fail "spring-dashpot zeta $zeta: exit $?: $(cat "$work/err")"
done
/usr/bin/python3 - "$work" $m $k <<'PY' || fail "spring-dashpot against its closed form (above)"
import csv, math, sys
work, m, k = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
w0 = math.sqrt(k / m)
bad = []
for zeta in (0.0, 0.2, 0.8):
    rows = list(csv.DictReader(open(f"{work}/lin_{zeta:g}.csv")))
    assert [float(r["approach_mps"]) for r in rows] == [0.3, 1.2], rows
    r_ = math.sqrt(1 - zeta * zeta)
    wd = w0 * r_
    if zeta == 0:
        # The textbook Kelvin-Voigt contact: pi / w_d and exp(-zeta pi / sqrt(1 - zeta^2)) = 1.
        t, e = math.pi / wd, math.exp(-zeta * math.pi / r_)
    else:
        # The force k d + c d' reaches zero where tan(w_d t) = -2 zeta r / (1 - 2 zeta^2).
        t = (math.pi - math.atan2(2 * zeta * r_, 1 - 2 * zeta * zeta)) / wd
        e = math.exp(-zeta * w0 * t) * abs(math.cos(wd * t) - zeta / r_ * math.sin(wd * t))
    for r in rows:
        v0 = float(r["approach_mps"])
        checks = [("restitution", float(r["restitution"]), e, 1e-8),
                  ("contact", float(r["contact_duration_s"]), t, 1e-8 * t),
                  ("permanent set", float(r["permanent_set_m"]), 0.0, 1e-15),
                  ("absorbed", float(r["dissipated_J"]), 0.5 * m * v0 * v0 * (1 - e * e),
                   1e-7 * 0.5 * m * v0 * v0)]
        if zeta == 0:
            checks.append(("d_max", float(r["max_deformation_m"]), v0 / w0, 1e-8 * v0 / w0))
        for name, got, want, tol in checks:
            if not abs(got - want) <= tol:
                bad.append(f"zeta {zeta} v0 {v0}: {name} {got!r}, closed form {want!r}")
        if r["status"] != "separated":
            bad.append(f"zeta {zeta} v0 {v0}: status {r['status']}")
# The dashpot that pulls on nothing lets go before the textbook dashpot (which pulls until the
# spring's length): at zeta = 0.2 its contact is shorter than pi / w_d and its restitution is
# not exp(-zeta pi / sqrt(1 - zeta^2)) = 0.527.
rows = list(csv.DictReader(open(f"{work}/lin_0.2.csv")))
t = float(rows[0]["contact_duration_s"])
if not t < math.pi / (w0 * math.sqrt(1 - 0.04)):
    bad.append(f"zeta 0.2: contact {t} not shorter than pi / w_d")
if abs(float(rows[0]["restitution"]) - math.exp(-0.2 * math.pi / math.sqrt(0.96))) < 1e-3:
    bad.append("zeta 0.2: the restitution of a dashpot that pulls")
for b in bad:
    print(b, file=sys.stderr)
sys.exit(1 if bad else 0)
PY

# --- the hyperbolic backfill over a range of speeds, K_ur = 1.5 K_max ---
# Wilson and Elgamal's constants over a 19.36 m backwall (docs/compliant.md), the pilot deck.
kmax=393008000
kur=589512000
rf=0.7
fult=6311360
"$exe" restitution --mass-kg $m --k-max-Npm $kmax --k-ur-Npm $kur --r-f $rf --f-ult-N $fult \
  --velocities-mps 0.1:1.5:8 --csv >"$work/hyp.csv" 2>"$work/err" || fail "backfill: exit $?: $(cat "$work/err")"
/usr/bin/python3 - "$work/hyp.csv" $m $kmax $kur $rf $fult <<'PY' || fail "backfill against its closed forms (above)"
import csv, math, sys
import numpy as np
from scipy import integrate, optimize
path, m, kmax, kur, rf, fult = sys.argv[1], *map(float, sys.argv[2:])
a, b = 1 / kmax, rf / fult
F = lambda d: d / (a + b * d)
G = lambda d: d / b - a / (b * b) * math.log1p(b * d / a)  # the envelope's work to d
rows = list(csv.DictReader(open(path)))
speeds = [float(r["approach_mps"]) for r in rows]
bad = []
if not np.allclose(speeds, np.linspace(0.1, 1.5, 8), rtol=0, atol=1e-15) or speeds[-1] != 1.5:
    bad.append(f"speeds {speeds}, expected 8 from 0.1 to 1.5")
previous = 1.0
for r in rows:
    v0 = float(r["approach_mps"])
    e_in = 0.5 * m * v0 * v0
    d_max = optimize.brentq(lambda d: G(d) - e_in, 0.0, 10.0, xtol=1e-15, rtol=1e-14)
    f_max = F(d_max)
    # Loading time: d = d_max (1 - s^2) turns the root singularity at the turn into a smooth
    # integrand; the unloading along K_ur is a quarter of its period.
    speed = lambda d: math.sqrt(max(2.0 * (G(d_max) - G(d)) / m, 0.0))
    t_load, _ = integrate.quad(lambda s: 2 * d_max * s / speed(d_max * (1 - s * s)) if s > 0
                               else 2 * d_max / math.sqrt(2 * f_max / m * d_max), 0.0, 1.0,
                               epsabs=0, epsrel=1e-12, limit=200)
    want = {"restitution": f_max / (v0 * math.sqrt(m * kur)),
            "contact_duration_s": t_load + 0.5 * math.pi * math.sqrt(m / kur),
            "permanent_set_m": d_max - f_max / kur,
            "max_deformation_m": d_max, "max_force_N": f_max}
    for key, value in want.items():
        got = float(r[key])
        if not abs(got - value) <= 1e-7 * abs(value):
            bad.append(f"v0 {v0}: {key} {got!r}, closed form {value!r}")
    e = float(r["restitution"])
    if not abs(float(r["dissipated_J"]) - e_in * (1 - e * e)) <= 1e-7 * e_in:
        bad.append(f"v0 {v0}: absorbed {r['dissipated_J']}, expected {e_in * (1 - e * e)}")
    if not abs(float(r["energy_residual"])) < 1e-8:
        bad.append(f"v0 {v0}: ledger residual {r['energy_residual']}")
    if not e < previous:
        bad.append(f"v0 {v0}: restitution {e} does not fall with the speed")
    previous = e
for x in bad:
    print(x, file=sys.stderr)
sys.exit(1 if bad else 0)
PY

# The table form prints the same first row (the permanent set in mm).
"$exe" restitution --mass-kg $m --k-max-Npm $kmax --k-ur-Npm $kur --r-f $rf --f-ult-N $fult \
  --velocity-mps 0.1 >"$work/table" || fail "backfill table: exit $?"
set_mm=$(awk -F, 'NR == 2 { printf "%.4g", 1e3 * $4 }' "$work/hyp.csv")
awk -v s="$set_mm" '$1 == "0.1" && $4 == s { found = 1 } END { exit !found }' "$work/table" ||
  fail "table: no row '0.1 ... set $set_mm mm': $(cat "$work/table")"

# --- the Caltrans SDC 2.0 form: PyPBEE's Bridge_A backwall, 27.13 ft x 4.64 ft, 33 deg ---
"$exe" restitution --mass-kg 1424.5e3 --caltrans --width-m 8.269224 --height-m 1.414272 \
  --skew-deg 33 --velocity-mps 0.5 >"$work/caltrans" 2>"$work/err" || fail "caltrans: exit $?: $(cat "$work/err")"
read -r k_want p_want < <(awk 'BEGIN { w = 27.13; h = 4.64; r = exp(-33 / 45);
  kip = 4448.2216152605; inch = 0.0254;
  printf "%.6g %.6g\n", w * (5.5 * h + 20) * r * kip / inch, w * 5.5 * h ^ 2.5 / (1 + 2.37 * h) * r * kip }')
grep -q "K = $k_want N/m, P_bw = $p_want N" "$work/caltrans" ||
  fail "caltrans: no 'K = $k_want N/m, P_bw = $p_want N' in: $(cat "$work/caltrans")"

# --- bad input ---
law=(--k-max-Npm $kmax --r-f $rf --f-ult-N $fult)
refuse "--mass-kg: needed: the striking mass (> 0, kg)" "${law[@]}" --velocity-mps 1
refuse "--velocity-mps: speeds must be > 0 m/s (got 0)" --mass-kg $m "${law[@]}" --velocity-mps 0
refuse "--velocity-mps: give approach speeds (m/s, > 0) or --velocities-mps A:B:N" --mass-kg $m "${law[@]}"
refuse "--velocities-mps: '1.5:0.1:4': A:B:N needs A < B and N a whole number 2..10000" \
  --mass-kg $m "${law[@]}" --velocities-mps 1.5:0.1:4
refuse "--velocities-mps: '0.1:1.5': give A:B:N" --mass-kg $m "${law[@]}" --velocities-mps 0.1:1.5
refuse "--velocities-mps: 'x' is not a number > 0 (allowed: A:B:N, N speeds in m/s evenly from A to B)" \
  --mass-kg $m "${law[@]}" --velocities-mps x:1:3
refuse "--r-f: needed, in (0, 1] (got 1.5)" --mass-kg $m --k-max-Npm $kmax --r-f 1.5 --f-ult-N $fult --velocity-mps 1
refuse "--damping-ratio: must be in [0, 1) (got 1)" --mass-kg $m --spring-Npm $k --damping-ratio 1 --velocity-mps 1
refuse "--damping-ratio: only with --spring-Npm" --mass-kg $m "${law[@]}" --damping-ratio 0.1 --velocity-mps 1
refuse "--f-ult-N: needed, > 0 N (got 0)" --mass-kg $m --k-max-Npm $kmax --r-f $rf --velocity-mps 1
refuse "--width-m: needed with --caltrans (> 0, m)" --mass-kg $m --caltrans --height-m 1.5 --velocity-mps 1
refuse "law: give exactly one of --k-max-Npm (OpenSees constants with --r-f and --f-ult-N), --k50-Npm (Shamsabadi, with --f-ult-N and --height-m or --y-max-m), --caltrans (with --width-m and --height-m), --spring-Npm (linear spring-dashpot, with --damping-ratio)" \
  --mass-kg $m "${law[@]}" --spring-Npm $k --velocity-mps 1
echo "restitution_cli_test: ok"
