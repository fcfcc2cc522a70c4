"""Checks the fragility/ group of a sweep cube against an independent computation from the
cube's own cells: the maximum-likelihood (theta, beta) against scipy.optimize.minimize on the
binomial likelihood written out here (Baker 2015, eq. 11), the standard errors against a
finite-difference Hessian of that likelihood, the cloud fit against numpy.polyfit, and the
counts per stripe against the exceedance columns. With records.beyond_max_scale = "exclude" the
cells whose scale_factor exceeds max_scale are removed before the refit, and the stored counts of
left-out cells (per fit and per stripe) are checked against them.

With --worst-incidence the group checked is fragility_worst_incidence/ of a sweep with an
incidence_deg axis, against cells reduced here with numpy: a record at a stripe exceeds when it
exceeds at some angle (np.max of ls_<name> over the axis), its demand is the largest over the
angles, and it is used only when the cells of every angle are done with status ok.

An IDA sweep's fits (method "ida") are checked against its capacities (ida_capacity_<name>,
and ida_capacity_below_<name> where a record is censored): every capacity finite, theta and
beta are the geometric mean and the standard deviation (n - 1) of their logarithms; some
censored, scipy.optimize maximises the right-censored lognormal likelihood written out here
(Baker 2015). At the worst angle a record's capacity is np.min of its capacities over the
incidence_deg axis, censored at the lowest of its censoring intensities when it is infinite at
every angle.

usage: check_fragility_cube.py FILE.h5 SWEEP [MIN_FITTED] [--worst-incidence]
MIN_FITTED: fail unless at least this many (limit state, combination) pairs have a fit.
"""
import itertools
import math
import sys

import h5py
import numpy as np
from scipy import optimize, stats

G = 9.80665


def negloglik(p, x, z):
    ln_theta, beta = p
    u = (np.log(x) - ln_theta) / beta
    return -np.sum(z * stats.norm.logcdf(u) + (1 - z) * stats.norm.logcdf(-u))


def close(a, b, rtol, what):
    assert abs(a - b) <= rtol * abs(b), "%s: cube %r, independent %r" % (what, a, b)


def check_ida(g, f, axes, ok, worst):
    """The IDA fits of group f against the capacities of the cells; returns the fits checked."""
    assert not np.isfinite(float(g.attrs.get("max_scale", np.inf))), "max_scale not checked here"
    combo_axes = [a.decode() if isinstance(a, bytes) else a for a in f.attrs["axis_order"]]
    fitted = 0
    for name in f.attrs["limit_states"]:
        name = name.decode() if isinstance(name, bytes) else name
        h = f[name]
        cap = np.where(ok, g["responses/ida_capacity_" + name][()], np.nan)
        below = np.where(ok, g["responses/ida_capacity_below_" + name][()], np.nan)
        use = ok.copy()
        ax = list(axes)
        if worst:
            k = ax.index("incidence_deg")
            cap, below = np.min(cap, axis=k), np.min(below, axis=k)
            use = np.all(ok, axis=k)
            ax.pop(k)
        shape = [len(g["axes/" + a]) for a in combo_axes]
        reasons = [r.decode() for r in h["reason"][()]]
        for flat, idx in enumerate(itertools.product(*[range(s) for s in shape])):
            sel = [slice(None)] * len(ax)
            for a, i in zip(combo_axes, idx):
                sel[ax.index(a)] = i
            sel = tuple(sel)
            c, b = cap[sel][use[sel]], below[sel][use[sel]]
            finite = np.isfinite(c)
            at = idx if idx else 0
            assert int(h["n_records"][at]) == int(finite.sum()), "%s %s: n_records" % (name, idx)
            assert int(h["n_censored"][at]) == int((~finite).sum()), "%s %s: n_censored" % (name, idx)
            theta, beta = float(h["theta"][at]), float(h["beta"][at])
            if reasons[flat]:
                assert math.isnan(theta) and math.isnan(beta), "a reason and a number"
                continue
            fitted += 1
            y = np.log(c[finite])
            if finite.all():
                close(theta, math.exp(y.mean()), 1e-12, "%s %s theta" % (name, idx))
                close(beta, y.std(ddof=1), 1e-12, "%s %s beta" % (name, idx))
                continue
            yc = np.log(b[~finite])

            def nll(p):
                return -(stats.norm.logpdf(y, p[0], p[1]).sum()
                         + stats.norm.logsf(yc, p[0], p[1]).sum())
            res = optimize.minimize(nll, [y.mean(), max(y.std(), 0.1)], method="Nelder-Mead",
                                    options={"xatol": 1e-11, "fatol": 1e-13, "maxiter": 40000})
            close(theta, math.exp(res.x[0]), 1e-6, "%s %s censored theta" % (name, idx))
            close(beta, res.x[1], 1e-6, "%s %s censored beta" % (name, idx))
    return fitted


def main():
    args = [a for a in sys.argv[1:] if a != "--worst-incidence"]
    worst = len(args) < len(sys.argv) - 1
    path, sweep = args[0], args[1]
    min_fitted = int(args[2]) if len(args) > 2 else 1
    g = h5py.File(path, "r")["sweeps/" + sweep]
    axes = [a.decode() if isinstance(a, bytes) else a for a in g.attrs["axis_order"]]
    f = g["fragility_worst_incidence" if worst else "fragility"]
    if f.attrs["method"] == "ida":
        ok = (g["done"][()] == 1) & (g["status"][()] == 0)
        fitted = check_ida(g, f, axes, ok, worst)
        assert fitted >= min_fitted, "only %d fits, expected at least %d" % (fitted, min_fitted)
        print("%s of %s: %d IDA fits agree with numpy and scipy" % (f.name.split("/")[-1], sweep,
                                                                     fitted))
        return
    combo_axes = list(f.attrs["axis_order"])
    stripe_axis = f.attrs["stripe_axis"]
    ok = (g["done"][()] == 1) & (g["status"][()] == 0)
    # The cells the fits leave out, from the scale factors themselves (not the stored flag).
    far = np.zeros(ok.shape, dtype=bool)
    excluding = g.attrs.get("beyond_max_scale", "keep") == "exclude"
    if excluding:
        far = g["responses/scale_factor"][()] > float(g.attrs["max_scale"])
        assert far.any(), "beyond_max_scale = exclude but no cell beyond max_scale"
    in_fit = ok & ~far
    if f.attrs["im"] == "im_g":
        im = np.broadcast_to(g["axes/im_g"][()].reshape(
            [-1 if a == "im_g" else 1 for a in axes]), ok.shape)
    else:
        im = g["responses/a_g"][()] / G
    columns = {}
    for name in f.attrs["limit_states"]:
        columns[name] = (g["responses/ls_" + name][()], g["responses/ls_" + name + "_demand"][()])
    if worst:
        # The worst angle, reduced here: every angle's cell used, the largest exceedance and
        # demand over the axis, the first angle's IM and flags.
        k = axes.index("incidence_deg")
        for name, (z, d) in columns.items():
            z = np.where(ok, z, np.nan)
            columns[name] = (np.max(z, axis=k), np.max(np.where(ok, d, np.nan), axis=k))
        im, far = np.take(im, 0, axis=k), np.any(far, axis=k)
        ok = np.all(ok, axis=k)
        in_fit = ok & ~far
        axes.pop(k)
    fitted = 0
    for name in f.attrs["limit_states"]:
        h = f[name]
        z_all, d_all = columns[name]
        kind = h.attrs["kind"]
        cap = 1.0 if kind == "unseating" else float(h.attrs["threshold"])
        reasons = [r.decode() for r in h["reason"][()]]
        shape = [len(g["axes/" + a]) for a in combo_axes]
        for flat, idx in enumerate(itertools.product(*[range(s) for s in shape])):
            sel = [slice(None)] * len(axes)
            for a, i in zip(combo_axes, idx):
                sel[axes.index(a)] = i
            sel = tuple(sel)
            use = in_fit[sel] & np.isfinite(z_all[sel])
            x, z, d = im[sel][use], z_all[sel][use], d_all[sel][use]
            at = idx if idx else 0
            out = ok[sel] & far[sel] & np.isfinite(z_all[sel])
            if excluding:
                assert int(h["n_excluded_beyond_max_scale"][at]) == int(out.sum()), \
                    "%s %s: n_excluded_beyond_max_scale" % (name, idx)
            else:
                assert "n_excluded_beyond_max_scale" not in h, "counts stored without the rule"
            assert int(h["n_cells"][at]) == len(x), "%s %s: n_cells" % (name, idx)
            assert int(h["n_exceeded"][at]) == int(z.sum()), "%s %s: n_exceeded" % (name, idx)
            assert set(np.unique(z)) <= {0.0, 1.0}, "exceedance not 0/1"
            if stripe_axis:
                zs, xs = z_all[sel], im[sel]
                # the stripe axis is the ks'th of the remaining (non-combination) dimensions
                rest = [a for a in axes if a not in combo_axes]
                ks = rest.index(stripe_axis)
                for s in range(len(g["axes/" + stripe_axis])):
                    take = [slice(None)] * len(rest)
                    take[ks] = s
                    take = tuple(take)
                    u = in_fit[sel][take] & np.isfinite(zs[take])
                    assert h["stripe_n"][at][s] == u.sum(), "%s stripe_n" % name
                    if excluding:
                        assert h["stripe_excluded"][at][s] == out[take].sum(), "stripe_excluded"
                    assert h["stripe_exceeded"][at][s] == zs[take][u].sum(), "%s stripe_exceeded" % name
                    if u.any():
                        close(h["stripe_im"][at][s], math.exp(np.log(xs[take][u]).mean()), 1e-12,
                              "%s stripe_im" % name)
            theta, beta = float(h["theta"][at]), float(h["beta"][at])
            if reasons[flat]:
                assert math.isnan(theta) and math.isnan(beta), "a reason and a number"
            else:
                fitted += 1
                start = [np.log(x).mean(), max(np.log(x).std(), 0.1)]
                res = optimize.minimize(negloglik, start, args=(x, z), method="Nelder-Mead",
                                        options={"xatol": 1e-11, "fatol": 1e-13, "maxiter": 40000})
                close(theta, math.exp(res.x[0]), 1e-6, "%s %s theta" % (name, idx))
                close(beta, res.x[1], 1e-6, "%s %s beta" % (name, idx))
                # observed information by central differences at the cube's optimum
                p0, hstep = np.array([math.log(theta), beta]), 1e-4
                H = np.zeros((2, 2))
                for i in range(2):
                    for j in range(2):
                        ei, ej = np.eye(2)[i] * hstep, np.eye(2)[j] * hstep
                        H[i, j] = (negloglik(p0 + ei + ej, x, z) - negloglik(p0 + ei - ej, x, z)
                                   - negloglik(p0 - ei + ej, x, z) + negloglik(p0 - ei - ej, x, z)) / (4 * hstep ** 2)
                cov = np.linalg.inv(H)
                close(float(h["se_ln_theta"][at]), math.sqrt(cov[0, 0]), 1e-4, "se_ln_theta")
                close(float(h["se_beta"][at]), math.sqrt(cov[1, 1]), 1e-4, "se_beta")
                lo, hi = float(h["boot_theta_lo"][at]), float(h["boot_theta_hi"][at])
                if not math.isnan(lo):
                    assert lo <= hi and 0 < int(h["boot_used"][at]) <= int(f.attrs["bootstrap_resamples"])
            cloud_reason = h["cloud_reason"][()][flat].decode()
            if not cloud_reason:
                keep = (d / cap > 0) & np.isfinite(d / cap)
                b, a = np.polyfit(np.log(x[keep]), np.log(d[keep] / cap), 1)
                r = np.log(d[keep] / cap) - a - b * np.log(x[keep])
                s = math.sqrt((r ** 2).sum() / (keep.sum() - 2))
                close(float(h["cloud_slope"][at]), b, 1e-9, "cloud slope")
                close(float(h["cloud_sigma"][at]), s, 1e-9, "cloud sigma")
                if b > 0:
                    close(float(h["cloud_theta"][at]), math.exp(-a / b), 1e-9, "cloud theta")
                    close(float(h["cloud_beta"][at]), s / b, 1e-9, "cloud beta")
    assert fitted >= min_fitted, "only %d fits, expected at least %d" % (fitted, min_fitted)
    print("%s of %s: %d fits agree with scipy and numpy" % (f.name.split("/")[-1], sweep, fitted))


if __name__ == "__main__":
    main()
