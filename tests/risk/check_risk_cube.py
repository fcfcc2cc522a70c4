"""Checks the risk/ group `skewbridge risk` wrote into a cube against an independent
computation: every stored lambda_LS against scipy.integrate.quad of Phi(ln(x/theta)/beta)
|d lambda/dx| over the log-log interpolated hazard and its power-law tail (read from the hazard
file itself, not from the cube), P in 1 and 50 years, the return period, the deaggregation
summing to 1, no number where the fragility has no fit, and the hazard file's SHA-256 and size
in risk/ and inputs/.

usage: check_risk_cube.py CUBE SWEEP HAZARD_FILE [RATE_TOLERANCE]"""
import hashlib
import math
import os
import sys

import h5py
import numpy as np
from scipy import integrate
from scipy.stats import norm


def read_two_column(path):
    xs, rs = [], []
    for line in open(path, encoding="utf-8"):
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        x, r = line.replace(",", " ").split()
        xs.append(float(x))
        rs.append(float(r))
    return np.array(xs), np.array(rs)


def rate(xs, rs, theta, beta):
    """int F |d lambda| with log-log interpolation and the last interval's power law beyond."""
    total = 0.0
    n = len(xs)
    for i in range(n):
        if i < n - 1:
            a, b = xs[i], xs[i + 1]
            k = math.log(rs[i] / rs[i + 1]) / math.log(b / a)
        else:
            a, b = xs[-1], math.inf
            k = math.log(rs[-2] / rs[-1]) / math.log(xs[-1] / xs[-2])
        la = rs[i]

        def f(u, a=a, la=la, k=k):  # u = ln x
            x = math.exp(u)
            return norm.cdf(math.log(x / theta) / beta) * k * la * (x / a) ** (-k)
        hi = math.log(b) if math.isfinite(b) else math.log(a) + 60.0 / max(k, 1e-3)
        val, _ = integrate.quad(f, math.log(a), hi, epsabs=0.0, epsrel=1e-11, limit=200)
        total += val
    return total


def main():
    cube, sweep, hazard = sys.argv[1], sys.argv[2], sys.argv[3]
    tol = float(sys.argv[4]) if len(sys.argv) > 4 else 1e-6
    xs, rs = read_two_column(hazard)
    g = h5py.File(cube, "r")["sweeps/" + sweep]
    r = g["risk"]
    data = open(hazard, "rb").read()
    sha = hashlib.sha256(data).hexdigest()
    assert r.attrs["hazard_sha256"] == sha, "risk/ hazard_sha256"
    assert r.attrs["hazard_bytes"] == len(data), "risk/ hazard_bytes"
    roles = list(g["inputs/role"].asstr()[()])
    assert roles.count("hazard") == 1, roles
    k = roles.index("hazard")
    assert g["inputs/sha256"].asstr()[k] == sha and g["inputs/bytes"][k] == len(data)
    assert np.allclose(r["hazard_im"][()], xs, rtol=0, atol=0), "hazard_im"
    assert np.allclose(r["hazard_rate"][()], rs, rtol=0, atol=0), "hazard_rate"
    checked = 0
    for ls in r.attrs["limit_states"]:
        fr = g["fragility"][ls]
        theta = fr["theta"][()].ravel()
        beta = fr["beta"][()].ravel()
        lam = r[ls]["rate_per_yr"][()].ravel()
        reason = list(r[ls]["reason"].asstr()[()])
        deagg = r[ls]["deaggregation"][()].reshape(len(lam), -1)
        for c in range(len(lam)):
            if not (math.isfinite(theta[c]) and math.isfinite(beta[c])):
                assert math.isnan(lam[c]) and reason[c], (ls, c, lam[c], reason[c])
                continue
            expect = rate(xs, rs, theta[c], beta[c])
            assert abs(lam[c] / expect - 1.0) < tol, (ls, c, lam[c], expect)
            assert abs(r[ls]["p_50yr"][()].ravel()[c] - (1 - math.exp(-50 * lam[c]))) < 1e-15
            assert abs(r[ls]["p_1yr"][()].ravel()[c] - (1 - math.exp(-lam[c]))) < 1e-15
            assert abs(r[ls]["return_period_yr"][()].ravel()[c] * lam[c] - 1) < 1e-14
            assert abs(deagg[c].sum() - 1.0) < 1e-12, deagg[c].sum()
            p16 = r[ls]["rate_p16"][()].ravel()[c]
            p84 = r[ls]["rate_p84"][()].ravel()[c]
            assert p16 < p84, (p16, p84)
            checked += 1
    assert checked > 0, "no fitted combination to check"
    print(f"{os.path.basename(cube)}: {checked} rates agree with scipy's quadrature to {tol:g}")


if __name__ == "__main__":
    main()
