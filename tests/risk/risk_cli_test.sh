#!/usr/bin/env bash
# `skewbridge risk` end to end on a real cube:
#  1. a fragility sweep of the pilot bridge (10 synthetic records scaled to 8 stripes of
#     Sa(T1)), then a power-law hazard at SA(T1) as a two-column file: check_risk_cube.py
#     recomputes every stored rate with scipy's quadrature and checks the hazard's identity;
#  2. the same hazard as an OpenQuake CSV of probabilities in 1 year reads back to the same
#     rates; `inspect` prints the risk table and the hazard's SHA-256;
#     scripts/report draws the hazard, fragility and integrand (checked to integrate to the
#     stored rate) and tabulates the rates;
#  3. a RotD50 hazard is refused without --convert and accepted with it, the conversion named;
#     on a sweep of record pairs scaled to RotD50(T1) it matches with no conversion;
#  4. every refusal (another period, another measure, a malformed line, a bad option) is one
#     line naming what differs, exit status 2, and leaves the cube's bytes as they were.
# usage: risk_cli_test.sh SKEWBRIDGE SOURCE_DIR WORK_DIR
source "$(dirname "${BASH_SOURCE[0]}")/../support/prologue.sh"
args exe src work -- "$@"
fresh_dir "$work"
cp "$src/docs/examples/pilot-bridge.toml" "$src/docs/examples/pilot-signal.txt" .
cat > frag.toml <<'TOML'
[sweep]
name = "frag"
family = "model-file"
model = "pilot-bridge.toml"
[records]
synthetic = {count = 10, seed = 5}
scale_to = {measure = "Sa", period = "T1", xi = 0.05}
max_scale = 4.0
[axes]
record = "*"
im_g = {logspace = [0.5, 6.0, 8]}
a_deg = [20, 40]
[limit_states]
unseating = {seat_m = 0.06}
rotation = {above_rad = 0.0002}
joint_closing = true
response = {y_m_d0 = 0.01}
TOML
"$exe" sweep frag.toml --out frag.h5 --quiet || fail "the fragility sweep failed"

# A power-law hazard lambda = 1e-3 x^-2.5 at SA(T1, 5 %), T1 read from the cube.
/usr/bin/python3 - frag.h5 <<'PY' || fail "cannot write the hazard files"
import sys, math, h5py
g = h5py.File(sys.argv[1], "r")["sweeps/frag"]
t1 = float(g["responses/T1"][()].ravel()[0])
xs = [0.02 * 1.3 ** i for i in range(30)]
def two_column(name, component):
    with open(name, "w") as f:
        f.write(f"# a power law for the test\n# imt = SA({t1:.6g})\n# component = {component}\n")
        for x in xs:
            f.write(f"{x:.17g} {1e-3 * x ** -2.5:.17g}\n")
two_column("hazard.txt", "arbitrary")
two_column("rotd50.txt", "RotD50")
with open("hazard.csv", "w") as f:
    f.write(f"#,,,,,\"generated_by='hand', kind='mean', investigation_time=1.0, imt='SA({t1:.6g})'\"\n")
    f.write("lon,lat,depth," + ",".join(f"poe-{x:.17g}" for x in xs) + "\n")
    f.write("1.0,2.0,0.0," + ",".join(f"{-math.expm1(-1e-3 * x ** -2.5):.17g}" for x in xs) + "\n")
with open("pga.txt", "w") as f:
    f.write("# imt = PGA\n# component = arbitrary\n0.1 0.01\n0.2 0.002\n")
with open("sa1.txt", "w") as f:
    f.write("# imt = SA(1.0)\n# component = arbitrary\n0.1 0.01\n0.2 0.002\n")
with open("bad.txt", "w") as f:
    f.write(f"# imt = SA({t1:.6g})\n# component = arbitrary\n0.1 0.01\n0.2 0.02\n")
PY

"$exe" risk frag.h5 --hazard hazard.txt > risk.txt || fail "skewbridge risk failed"
grep -q "^sweep frag: lambda_LS over the hazard SA(" risk.txt || fail "no table printed"
grep -q "assumes: the records were not selected for this site's hazard" risk.txt \
  || fail "the records' flag is not printed"
grep -q "scaled beyond the limit of 4" risk.txt || fail "the scale-factor flag is not printed"
/usr/bin/python3 "$src/tests/risk/check_risk_cube.py" frag.h5 frag hazard.txt \
  || fail "the stored rates differ from scipy's"
cp frag.h5 two_column.h5

# The OpenQuake CSV of the same hazard: the same rates (poe in 1 year and back).
"$exe" risk frag.h5 --hazard hazard.csv --hazard-component arbitrary > risk_oq.txt \
  || fail "skewbridge risk on the OpenQuake CSV failed"
/usr/bin/python3 - two_column.h5 frag.h5 <<'PY' || fail "the OpenQuake CSV gives other rates"
import sys, h5py, numpy as np
a = h5py.File(sys.argv[1], "r")["sweeps/frag/risk"]
b = h5py.File(sys.argv[2], "r")["sweeps/frag/risk"]
assert b.attrs["hazard_format"] == "openquake-csv" and b.attrs["hazard_investigation_time_yr"] == 1.0
# A probability near 1 printed to 17 digits keeps about 8 of -ln(1 - poe): 1e-7.
assert np.allclose(a["hazard_rate"][()], b["hazard_rate"][()], rtol=1e-7, atol=0)
for ls in a.attrs["limit_states"]:
    x, y = a[ls]["rate_per_yr"][()], b[ls]["rate_per_yr"][()]
    ok = np.isfinite(x)
    assert (np.isfinite(y) == ok).all() and np.allclose(x[ok], y[ok], rtol=1e-9, atol=0), ls
roles = list(h5py.File(sys.argv[2], "r")["sweeps/frag/inputs/role"].asstr()[()])
assert roles.count("hazard") == 1, roles   # the second run replaced the first's row
print("the OpenQuake CSV gives the same rates")
PY
"$exe" inspect frag.h5 > inspect.txt || fail "inspect failed"
grep -q "risk (risk/, annual rates over a hazard curve)" inspect.txt || fail "inspect prints no risk"
grep -q "$(sha256sum hazard.csv | cut -c1-64)" inspect.txt || fail "inspect prints no hazard SHA-256"

# The report: per limit state with a rate, the hazard, fragility and integrand figure; the
# integrand it draws integrates over ln x to the stored rate; the table holds the stored rates.
/usr/bin/python3 "$src/scripts/report" two_column.h5 --out report > report.txt \
  || fail "scripts/report two_column.h5 failed"
[ -s report/risk_frag_rotation.png ] || fail "no risk figure for the rotation"
PYTHONPATH="$src/scripts" /usr/bin/python3 - two_column.h5 report/summary.md <<'PY' \
  || fail "the report's risk figure or table differs from the cube"
import sys, math, h5py, numpy as np
from skewbridge_report import risk
g = h5py.File(sys.argv[1], "r")["sweeps/frag"]
r = g["risk"]
xs, rs = r["hazard_im"][()], r["hazard_rate"][()]
text = open(sys.argv[2], encoding="utf-8").read()
assert "## frag: annual rates over the hazard curve" in text
for ls in r.attrs["limit_states"]:
    lam = r[ls]["rate_per_yr"][()].ravel()
    for c in np.flatnonzero(np.isfinite(lam)):
        theta, beta = g["fragility"][ls]["theta"][()].ravel()[c], g["fragility"][ls]["beta"][()].ravel()[c]
        u = np.linspace(math.log(xs[0]), math.log(xs[-1]) + 12.0, 400001)
        area = np.trapz(risk.integrand(np.exp(u), xs, rs, theta, beta, "power-law"), u)
        assert abs(area / lam[c] - 1) < 1e-5, (ls, c, area, lam[c])
        rows = [l for l in text.splitlines() if l.startswith(f"| {ls} | ") and f"| {lam[c]:.3g} |" in l]
        assert rows, (ls, f"{lam[c]:.3g}")
print("report: the integrand drawn integrates to the stored rates; the table holds them")
PY

refuse() {  # refuse PATTERN ARGS...: one line matching PATTERN, exit 2, the cube unchanged
  local pattern=$1 before after status=0
  shift
  before=$(sha256sum frag.h5)
  "$exe" risk frag.h5 "$@" > out.txt 2> err.txt || status=$?
  after=$(sha256sum frag.h5)
  [ "$status" -eq 2 ] || fail "risk $*: exit status $status, not 2"
  [ "$(wc -l < err.txt)" -eq 1 ] || fail "risk $*: not one line: $(cat err.txt)"
  grep -q -- "$pattern" err.txt || fail "risk $*: '$(cat err.txt)' does not say '$pattern'"
  [ "$before" = "$after" ] || fail "risk $*: the refused run changed the cube"
}
# The worked study's hazard (docs/fragility.md) reads, and is refused at the default tolerance.
refuse "periods 42.7 % apart" --hazard "$src/docs/examples/hazard-los-angeles-sa0.2.txt" \
  --convert gmroti50-as-arbitrary
"$exe" risk frag.h5 --hazard "$src/docs/examples/hazard-los-angeles-sa0.2.txt" \
  --convert gmroti50-as-arbitrary --period-tolerance 0.45 > risk_la.txt \
  || fail "the worked study's hazard was refused"

# A RotD50 hazard: refused without a conversion, read as an arbitrary component with one.
refuse "hazard SA(.*RotD50 component) and fragility SA(.*arbitrary component): different horizontal components; --convert rotd50-as-arbitrary" \
  --hazard rotd50.txt
"$exe" risk frag.h5 --hazard rotd50.txt --convert rotd50-as-arbitrary > risk_rotd50.txt \
  || fail "the named conversion was refused"
grep -q "assumes: the hazard's RotD50 read as arbitrary (--convert rotd50-as-arbitrary).*Boore 2010" \
  risk_rotd50.txt || fail "the conversion is not stated"
refuse "periods .* apart, beyond the tolerance of 5 %" --hazard sa1.txt
refuse "hazard PGA (arbitrary component) and fragility SA(.*different measures" --hazard pga.txt
refuse "bad.txt:4: rate 0.02 rises above the 0.01" --hazard bad.txt
refuse "unknown conversion" --hazard hazard.txt --convert rotd100
refuse "missing.txt: cannot open the hazard file" --hazard missing.txt
refuse "tail" --hazard hazard.txt --tail sideways
refuse "holds no sweep named 'other'" --hazard hazard.txt --sweep other

# Record pairs scaled to RotD50(T1): the fragility is in SA of the RotD50 component, so the
# RotD50 hazard matches with no conversion (rates against scipy's) and the arbitrary one does not.
cat > pairs.toml <<TOML
[sweep]
name = "pairs"
family = "model-file"
model = "pilot-bridge.toml"
[records]
set = "$src/tests/data/records/pairs/pairs.toml"
scale_to = {measure = "RotD50", period = "T1", xi = 0.05}
[axes]
record = ["RSN107", "RSN430_SMART1.25_25M01"]
im_g = {logspace = [0.4, 3.0, 16]}
incidence_deg = [0, 90]
[fixed]
seat_over_L = 0.0005
[limit_states]
rotation = {above_rad = 0.0002}
TOML
"$exe" sweep pairs.toml --out pairs.h5 --quiet || fail "the pair sweep failed"
"$exe" risk pairs.h5 --hazard rotd50.txt > risk_pairs.txt || fail "the RotD50 hazard was refused"
grep -q "; fragility SA(.*RotD50 component)" risk_pairs.txt \
  || fail "the pair fragility's component is not stated"
/usr/bin/python3 "$src/tests/risk/check_risk_cube.py" pairs.h5 pairs rotd50.txt \
  || fail "the pair cube's rates differ from scipy's"
before=$(sha256sum pairs.h5)
status=0
"$exe" risk pairs.h5 --hazard hazard.txt > out.txt 2> err.txt || status=$?
[ "$status" -eq 2 ] || fail "an arbitrary-component hazard on a RotD50 fragility: status $status"
grep -q "hazard SA(.*arbitrary component) and fragility SA(.*RotD50 component): different horizontal components" err.txt \
  || fail "the component refusal says '$(cat err.txt)'"
[ "$before" = "$(sha256sum pairs.h5)" ] || fail "the refused run changed the pair cube"
echo "risk_cli_test: ok"
