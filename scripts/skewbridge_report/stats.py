"""Correlation statistics of the pilot-bridge study with numpy alone (docs/theory.md §6).

theta_m against the persistency L_e = a_g / w_g^2 over the records at one Pi_delta: Pearson's
r of the values, Spearman's rho (Pearson's r of the average ranks, ties shared), and the
least-squares line log10(theta_m) = slope log10(L_e) + intercept with its R^2 over the pairs
with theta_m > 0 (a record that never closes the gap has theta_m = 0, and no logarithm)."""
import numpy as np


def average_ranks(values):
    """Ranks 1..n, tied values sharing the mean of their ranks (as Spearman's rho needs)."""
    values = np.asarray(values, dtype=float)
    order = np.argsort(values, kind="mergesort")
    ranks = np.empty(len(values))
    sorted_values = values[order]
    i = 0
    while i < len(values):
        j = i
        while j + 1 < len(values) and sorted_values[j + 1] == sorted_values[i]:
            j += 1
        ranks[order[i:j + 1]] = 0.5 * (i + j) + 1.0
        i = j + 1
    return ranks


def pearson(x, y):
    """Pearson's correlation coefficient; NaN when either sample has no spread."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    if len(x) < 2:
        return float("nan")
    dx, dy = x - x.mean(), y - y.mean()
    denom = np.sqrt(np.sum(dx * dx) * np.sum(dy * dy))
    return float(np.sum(dx * dy) / denom) if denom > 0 else float("nan")


def spearman(x, y):
    """Spearman's rank correlation: Pearson's r of the average ranks."""
    return pearson(average_ranks(x), average_ranks(y))


def loglog_fit(x, y):
    """(slope, intercept, r2, n) of log10 y = slope log10 x + intercept over x, y > 0."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    keep = (x > 0) & (y > 0) & np.isfinite(x) & np.isfinite(y)
    n = int(np.count_nonzero(keep))
    if n < 2:
        return float("nan"), float("nan"), float("nan"), n
    lx, ly = np.log10(x[keep]), np.log10(y[keep])
    slope, intercept = np.polyfit(lx, ly, 1)
    residual = ly - (slope * lx + intercept)
    total = np.sum((ly - ly.mean()) ** 2)
    r2 = 1.0 - np.sum(residual ** 2) / total if total > 0 else float("nan")
    return float(slope), float(intercept), float(r2), n


def correlation_row(le, theta):
    """All statistics of one Pi_delta over the finite pairs, as a dict."""
    le = np.asarray(le, dtype=float)
    theta = np.asarray(theta, dtype=float)
    ok = np.isfinite(le) & np.isfinite(theta)
    slope, intercept, r2, n_log = loglog_fit(le[ok], theta[ok])
    return {"n": int(np.count_nonzero(ok)), "pearson": pearson(le[ok], theta[ok]),
            "spearman": spearman(le[ok], theta[ok]), "slope": slope, "intercept": intercept,
            "r2": r2, "n_log": n_log}
