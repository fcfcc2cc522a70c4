#!/usr/bin/python3
"""Checks the IDA cubes of ida_test.sh with h5py and numpy.

usage: check_ida.py ONE_RANK.h5 TWO_RANKS.h5 BRUTE.h5

- one and two ranks give the same cells;
- each cell's runs: the first at ida.start, intensities = scale factor x im_unscaled, at most
  max_runs, each limit state's capacity the lowest intensity of a run that exceeds it and
  ida_capacity_below the highest run below it that does not, their gap within the tolerance
  unless all max_runs runs were spent;
- joint closing (the first impact) is monotone in the scale factor, so its crossing lies both
  in (below, capacity] and between the brute-force sweep's last stripe without an impact and
  its first with one (stripes 0.005 g apart): the two intervals overlap and the capacity is
  within tolerance + 0.005 g of the first stripe with an impact;
- the fragility group: method "ida", theta = exp(mean ln capacity) and beta = std(ln
  capacity, ddof=1) per k_factor, as numpy computes them; with censored records, the
  maximum-likelihood fit with each censored at its highest run, as scipy's optimiser finds it.
"""
import sys

import h5py
import numpy as np

START, TOL, MAX_RUNS, SPACING = 0.1, 0.01, 30, 0.005


def censored_mle(y, u):
    """theta, beta of the lognormal with ln capacities y and ln censoring points u, by scipy."""
    from scipy import optimize, stats

    def nll(p):
        sigma = np.exp(p[1])
        return -(stats.norm.logpdf(y, p[0], sigma).sum() + stats.norm.logsf(u, p[0], sigma).sum())

    res = optimize.minimize(nll, [y.mean(), np.log(y.std())], method="Nelder-Mead",
                            options=dict(xatol=1e-12, fatol=1e-14, maxiter=20000))
    return float(np.exp(res.x[0])), float(np.exp(res.x[1]))


def main():
    one, two, brute = (h5py.File(p, "r") for p in sys.argv[1:4])
    g, g2, b = one["sweeps/ida"], two["sweeps/ida"], brute["sweeps/brute"]
    for name in g["responses"]:
        assert np.array_equal(g["responses"][name][()], g2["responses"][name][()],
                              equal_nan=True), name
    r = {k: v[()] for k, v in g["responses"].items()}
    assert np.all(g["status"][()] == 0)
    own = r["im_unscaled"]
    limit_states = list(g["fragility"].attrs["limit_states"])
    assert sorted(limit_states) == ["joint_closing", "rotation"], limit_states
    assert g["fragility"].attrs["method"] == "ida"
    n_records, n_k = own.shape
    for i in range(n_records):
        for k in range(n_k):
            runs = int(r["ida_runs"][i, k])
            assert 2 <= runs <= MAX_RUNS, runs
            im = np.array([r[f"ida_im_{j:02d}"][i, k] for j in range(MAX_RUNS)])
            scale = np.array([r[f"ida_scale_{j:02d}"][i, k] for j in range(MAX_RUNS)])
            assert np.all(np.isnan(im[runs:])) and np.all(np.isfinite(im[:runs]))
            assert im[0] == START, im[0]
            assert np.allclose(scale[:runs] * own[i, k], im[:runs], rtol=1e-12)
            for ls in limit_states:
                ex = np.array([r[f"ida_exceeded_{ls}_{j:02d}"][i, k] for j in range(runs)])
                cap, below = r[f"ida_capacity_{ls}"][i, k], r[f"ida_capacity_below_{ls}"][i, k]
                assert cap == im[:runs][ex == 1].min(), (ls, cap)
                assert below == max([0.0] + list(im[:runs][(ex == 0) & (im[:runs] < cap)]))
                # Within the tolerance, unless the run budget ran out first.
                assert cap - below <= TOL or runs == MAX_RUNS, (ls, cap, below, runs)
                close = r[f"ida_capacity_scale_{ls}"][i, k] * own[i, k]
                assert abs(close - cap) <= 1e-12 * cap
    # The brute force: the first stripe with an impact, per record and k_factor.
    stripes = b["axes/im_g"][()]
    assert list(b.attrs["axis_order"]) == ["record", "im_g", "k_factor"], b.attrs["axis_order"]
    impact = np.swapaxes(b["responses/ls_joint_closing"][()], 1, 2)  # [record, k, stripe]
    worst = 0.0
    for i in range(n_records):
        for k in range(n_k):
            hit = np.flatnonzero(impact[i, k] == 1)
            assert hit.size and hit[0] > 0, "the brute-force stripes must bracket the first impact"
            first = hit[0]
            assert np.all(impact[i, k, first:] == 1), "first impact not monotone in the stripes"
            s1, s0 = stripes[first], stripes[first - 1]
            cap = r["ida_capacity_joint_closing"][i, k]
            below = r["ida_capacity_below_joint_closing"][i, k]
            assert cap - below <= TOL, (i, k, cap, below)
            assert below < s1 and s0 < cap, (i, k, (below, cap), (s0, s1))
            assert abs(cap - s1) <= TOL + SPACING + 1e-12, (cap, s1)
            worst = max(worst, abs(cap - s1))
    # The lognormal fit of the capacities, per k_factor.
    for ls in limit_states:
        f = g["fragility"][ls]
        cap = r[f"ida_capacity_{ls}"]
        for k in range(n_k):
            finite = np.isfinite(cap[:, k])
            logs = np.log(cap[:, k][finite])
            assert f["n_records"][k] == logs.size and f["n_censored"][k] == n_records - logs.size
            if logs.size == n_records:
                assert abs(f["theta"][k] - np.exp(logs.mean())) <= 1e-12 * f["theta"][k]
                assert abs(f["beta"][k] - np.std(logs, ddof=1)) <= 1e-12 + 1e-12 * f["beta"][k]
            else:
                # Censored at each record's highest run: scipy's own optimiser on the likelihood.
                u = np.log(r[f"ida_capacity_below_{ls}"][:, k][~finite])
                theta, beta = censored_mle(logs, u)
                assert abs(f["theta"][k] - theta) <= 1e-6 * theta, (f["theta"][k], theta)
                assert abs(f["beta"][k] - beta) <= 1e-6 * beta, (f["beta"][k], beta)
    print(f"check_ida: ok ({n_records * n_k} cells; joint-closing capacity within {worst:.4f} g "
          f"of the brute-force first impact)")


if __name__ == "__main__":
    main()
