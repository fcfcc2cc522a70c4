"""Checks the record table, the per-cell study columns and the correlation statistics of a
record-driven sweep cube (docs/hdf5-layout.md) against a direct numpy/scipy computation from
the stored columns. usage: check_study_cube.py CUBE SWEEP"""
import sys

import h5py
import numpy as np
from scipy import stats

path, name = sys.argv[1], sys.argv[2]
f = h5py.File(path, "r")
g = f["sweeps/" + name]
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


def close(a, b, rtol, what, floor=1e-300):
    """|a - b| <= rtol max(|b|, floor), NaN where b is NaN."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    same_nan = np.array_equal(np.isnan(a), np.isnan(b))
    err = np.abs(a - b)[~np.isnan(b)]
    good = same_nan and np.all(err <= rtol * np.maximum(np.abs(b), floor)[~np.isnan(b)])
    check(good, f"{what}: {a} != {b}")


def stat_close(a, b, what):
    # Correlations, R^2, slopes and intercepts are of order one: a near-zero value (an R^2 of
    # 3e-5) is compared on the scale 1, where both computations round.
    close(a, b, 1e-12, what, floor=1.0)


def strings(ds):
    return [s.decode() if isinstance(s, bytes) else s for s in ds[()]]


axis_order = list(g.attrs["axis_order"])
axis_order = [a.decode() if isinstance(a, bytes) else a for a in axis_order]
check(axis_order == ["record", "Pi_delta"], f"axis order {axis_order}")
rec = g["records"]
labels = strings(rec["label"])
check(labels == strings(g["axes/record"]), "records/label differs from axes/record")
pga, wg, le_rec, tm = (rec[k][()] for k in ("pga_mps2", "w_g_radps", "L_e_m", "T_m_s"))
close(le_rec, pga / wg**2, 1e-12, "records L_e_m = pga / w_g^2")
close(wg, 2 * np.pi / tm, 1e-12, "records w_g = 2 pi / T_m")
check(np.all(pga >= 0.1 * 9.80665 * (1 - 1e-6)), "a record below 0.1 g")

pi_delta = g["axes/Pi_delta"][()]
resp = g["responses"]
status = g["status"][()]
check(np.all(status == 0), f"failed cells: {status}")
a_g, w_g, L_e, delta = (resp[k][()] for k in ("a_g", "w_g", "L_e", "delta"))
close(a_g, np.repeat(pga[:, None], len(pi_delta), 1), 1e-12, "a_g = PGA of the record")
close(w_g, np.repeat(wg[:, None], len(pi_delta), 1), 1e-12, "w_g of the record")
close(L_e, np.repeat((pga / wg**2)[:, None], len(pi_delta), 1), 1e-12, "L_e = PGA / w_g^2")
close(delta, pi_delta[None, :] * L_e, 1e-12, "delta = Pi_delta L_e")

edges = resp["band"].attrs["band_edges"]
ratio = resp["w0x_over_wg"][()]
check(np.array_equal(resp["band"][()], np.searchsorted(edges, ratio, side="right").astype(float)),
      "band does not match band_edges")

theta = resp["theta_m"][()]
c = g["correlation"]
check(list(c.attrs["band_edges"]) == list(edges), "correlation band_edges")
nb = len(edges) + 1


def statistics(x, y):
    out = {"n": len(x)}
    out["pearson"] = stats.pearsonr(x, y)[0] if len(x) >= 2 else np.nan
    out["spearman"] = stats.spearmanr(x, y)[0] if len(x) >= 2 else np.nan
    pos = (x > 0) & (y > 0)
    lx, ly = np.log10(x[pos]), np.log10(y[pos])
    out["loglog_n"] = int(pos.sum())
    slope, intercept = np.polyfit(lx, ly, 1)
    r2 = 1 - np.sum((ly - (intercept + slope * lx)) ** 2) / np.sum((ly - ly.mean()) ** 2)
    out.update(slope=slope, intercept=intercept, r2=r2)
    # Pearson straight from its definition, as a second reference.
    dx, dy = x - x.mean(), y - y.mean()
    out["pearson_direct"] = np.sum(dx * dy) / np.sqrt(np.sum(dx * dx) * np.sum(dy * dy))
    return out


for p in range(len(pi_delta)):
    ok = (status[:, p] == 0) & np.isfinite(theta[:, p]) & np.isfinite(L_e[:, p])
    x, y = L_e[ok, p], theta[ok, p]
    s = statistics(x, y)
    check(c["n"][p] == s["n"], f"n at Pi_delta {pi_delta[p]}")
    check(c["loglog_n"][p] == s["loglog_n"], f"loglog_n at Pi_delta {pi_delta[p]}")
    stat_close(c["pearson_theta_Le"][p], s["pearson"], f"pearson at {pi_delta[p]}")
    stat_close(c["pearson_theta_Le"][p], s["pearson_direct"], f"pearson (direct) at {pi_delta[p]}")
    stat_close(c["spearman_theta_Le"][p], s["spearman"], f"spearman at {pi_delta[p]}")
    stat_close(c["loglog_slope"][p], s["slope"], f"slope at {pi_delta[p]}")
    stat_close(c["loglog_intercept"][p], s["intercept"], f"intercept at {pi_delta[p]}")
    stat_close(c["loglog_r2"][p], s["r2"], f"r2 at {pi_delta[p]}")
    reason = c["reason"][p]
    check((reason.decode() if isinstance(reason, bytes) else reason) == "", f"reason {reason}")
    band = resp["band"][ok, p]
    for b in range(nb):
        inb = band == b
        check(c["band_n"][p, b] == inb.sum(), f"band_n at {pi_delta[p]}, band {b}")
        if inb.sum() >= 3:
            sb = statistics(x[inb], y[inb])
            stat_close(c["band_pearson_theta_Le"][p, b], sb["pearson"], f"band pearson {p} {b}")
            stat_close(c["band_spearman_theta_Le"][p, b], sb["spearman"], f"band spearman {p} {b}")
            stat_close(c["band_loglog_slope"][p, b], sb["slope"], f"band slope {p} {b}")
            stat_close(c["band_loglog_r2"][p, b], sb["r2"], f"band r2 {p} {b}")
        else:
            check(np.isnan(c["band_pearson_theta_Le"][p, b]), f"band {b} below 3 records has a value")
    # The scale of dimension 0 is the Pi_delta axis.
    check(np.array_equal(c["pearson_theta_Le"].dims[0][0][()], pi_delta), "Pi_delta scale")

if failures:
    print("check_study_cube: FAIL\n  " + "\n  ".join(failures))
    sys.exit(1)
print(f"check_study_cube: ok ({len(labels)} records x {len(pi_delta)} Pi_delta)")
for p in range(len(pi_delta)):
    print(f"  Pi_delta {pi_delta[p]:g}: n {c['n'][p]}, pearson {c['pearson_theta_Le'][p]:.4f}, "
          f"spearman {c['spearman_theta_Le'][p]:.4f}, slope {c['loglog_slope'][p]:.4f}, "
          f"r2 {c['loglog_r2'][p]:.4f}")
