"""The figures and table of `skewbridge risk` (risk/ of a cube, docs/risk.md): per limit state,
the hazard curve, the fragility and the integrand of the risk integral on shared IM axes, and
a table of the annual rates with what each assumes."""
import math

import matplotlib.pyplot as plt
import numpy as np
from scipy.stats import norm

from . import common
from .data import as_text, tree_attrs


def _at(array, idx):
    """The value of a per-combination array at a combination's multi-index."""
    return np.asarray(array)[idx] if idx else np.asarray(array).ravel()[0]


def has_risk(sweep):
    """Whether the sweep holds risk/ with at least one limit state."""
    return "risk" in sweep.extra and "limit_states" in sweep.extra["risk"]["attrs"]


def _hazard(r):
    return np.asarray(r["hazard_im"], dtype=float), np.asarray(r["hazard_rate"], dtype=float)


def hazard_at(x, xs, rs):
    """lambda_IM(x) interpolated log-log between the points, the last interval's power law
    beyond the last one."""
    x = np.asarray(x, dtype=float)
    k = np.log(rs[:-1] / rs[1:]) / np.log(xs[1:] / xs[:-1])
    i = np.clip(np.searchsorted(xs, x, side="right") - 1, 0, len(xs) - 2)
    return rs[i] * (x / xs[i]) ** (-k[i])


def integrand(x, xs, rs, theta, beta, tail):
    """P(LS | x) |d lambda / d ln x| on the log-log interpolated hazard (the density of
    lambda_LS per unit ln IM), with the tail of the stored convention beyond the last point."""
    x = np.asarray(x, dtype=float)
    k = np.log(rs[:-1] / rs[1:]) / np.log(xs[1:] / xs[:-1])
    i = np.clip(np.searchsorted(xs, x, side="right") - 1, 0, len(xs) - 2)
    lam = rs[i] * (x / xs[i]) ** (-k[i])
    slope = k[i].copy()
    beyond = x > xs[-1]
    if tail != "power-law":
        slope[beyond] = 0.0
    below = x < xs[0]
    slope[below] = 0.0
    return norm.cdf(np.log(x / theta) / beta) * slope * lam


def figure(sweep, ls, out_dir, name, pdf):
    """Three panels over one IM axis: the hazard lambda_IM(x) with its points, the fitted
    fragility per combination with the stripes' range, and the integrand P |d lambda / d ln x|
    normalised by lambda_LS (the deaggregation by IM), with the hazard's last point marked."""
    r = sweep.extra["risk"]
    f = sweep.extra["fragility"]
    fa = tree_attrs(f)
    ra = tree_attrs(r)
    order = [as_text(k) for k in fa.get("axis_order", [])]
    combos = common.combinations(sweep, order)
    g, rg = f[ls], r[ls]
    rates = np.asarray(rg["rate_per_yr"], dtype=float).ravel()
    shown = [c for c in combos if math.isfinite(rates[c[0]])][:common.MAX_COMBOS]
    xs, rs = _hazard(r)
    tail = as_text(ra.get("tail", "power-law"))
    # The IM range where the rates come from: from a third of the lowest median's
    # theta e^-4 beta (P below 3e-5) to past the hazard's last point.
    lo, hi = xs[-1], xs[-1] * 2.0
    for flat, idx, _ in shown:
        theta, beta = float(_at(g["theta"], idx)), float(_at(g["beta"], idx))
        lo, hi = min(lo, theta * math.exp(-4 * beta) / 3.0), max(hi, theta * math.exp(3 * beta))
    if not shown:
        lo = xs[0]
    x = np.geomspace(max(lo, xs[0]), hi, 800)
    fig, axes = plt.subplots(3, 1, figsize=(8.5, 9.5), sharex=True, layout="constrained")
    ax_h, ax_f, ax_d = axes
    window = (xs >= x[0]) & (xs <= x[-1])
    ax_h.plot(xs[window], rs[window], "ko", ms=3.5, mfc="none", label="hazard points")
    inside = x[(x >= xs[0]) & (x <= xs[-1])]
    ax_h.plot(inside, hazard_at(inside, xs, rs), "k-", lw=1.2, label="log-log interpolation")
    if tail == "power-law":
        xt = x[x > xs[-1]]
        ax_h.plot(xt, hazard_at(xt, xs, rs), "k:", lw=1.2, label="power-law tail")
    common.log_axis(ax_h, "y")
    ax_h.set_ylabel(r"$\lambda_{IM}(x)$ [1/yr]")
    ax_h.set_title(f"{sweep.name}: {ls} over {as_text(ra.get('hazard_file', ''))}", fontsize=10)
    styles = common.category_styles(len(shown))
    for (flat, idx, label), (color, marker, ls_style) in zip(shown, styles):
        theta, beta = float(_at(g["theta"], idx)), float(_at(g["beta"], idx))
        ax_f.plot(x, norm.cdf(np.log(x / theta) / beta), color=color, ls=ls_style,
                  label=f"{label}: λ = {rates[flat]:.2g}/yr")
        if "stripe_im" in g:
            sx = np.asarray(g["stripe_im"])[idx] if idx else np.asarray(g["stripe_im"])[0]
            sn = np.asarray(g["stripe_n"])[idx] if idx else np.asarray(g["stripe_n"])[0]
            sz = (np.asarray(g["stripe_exceeded"])[idx] if idx
                  else np.asarray(g["stripe_exceeded"])[0])
            ok = sn > 0
            ax_f.plot(sx[ok], sz[ok] / sn[ok], marker=marker, ls="none", color=color, mfc="none",
                      ms=5)
        dens = integrand(x, xs, rs, theta, beta, tail) / rates[flat]
        ax_d.plot(x, dens, color=color, ls=ls_style)
    for ax in (ax_f, ax_d):
        ax.axvline(xs[-1], color="0.4", lw=0.8, ls="--")
    ax_d.text(xs[-1], 1.0, " last hazard point", transform=ax_d.get_xaxis_transform(),
              ha="left", va="top", fontsize=8, color="0.3")
    if not shown:
        common.no_data(ax_f, "no fitted fragility: no rate")
        common.no_data(ax_d, "no rate")
    ax_f.set_ylim(-0.03, 1.03)
    ax_f.set_ylabel("P(LS | IM = x)")
    ax_d.set_ylabel(r"$P\,|d\lambda_{IM}/d\ln x|\,/\,\lambda_{LS}$")
    ax_d.set_ylim(bottom=0.0)
    common.log_axis(ax_d, "x")
    ax_d.set_xlabel(common.im_label(sweep, fa))
    handles, labels = ax_f.get_legend_handles_labels()
    h2, l2 = ax_h.get_legend_handles_labels()
    ax_h.legend(h2, l2, loc="upper right", fontsize=8)
    if handles:
        ax_f.legend(handles, labels, loc="upper left", fontsize=8)
    common.caption_text(fig, (
        "Top: the site's hazard λ_IM(x), the annual rate at which the IM exceeds x (points as "
        "stored, log-log interpolation between them, the tail beyond the last point as the "
        f"integral takes it: {tail}). Middle: the maximum-likelihood lognormal fragility of "
        "each combination (markers: fraction of each stripe's cells that exceeded). Bottom: "
        "the integrand P(LS | x) |dλ_IM/d ln x| over λ_LS, the deaggregation of the annual "
        "rate by IM (its area over ln x is 1; its kinks sit at the hazard's points, where the "
        "interpolated slope changes); the dashed line is the hazard's last point."
        + common.shown_text(len(shown), len([c for c in combos if math.isfinite(rates[c[0]])]))))
    return common.save(fig, out_dir, name, pdf)


def _num(v, fmt="{:.3g}"):
    return fmt.format(v) if math.isfinite(v) else "–"


def table(sweep):
    """(header, rows) of the rates: limit state, combination, lambda_LS with its 16-84 %,
    P(50 yr), return period, Cornell's closed form, the shares from beyond the hazard and from
    outside the stripes, and the flags or the reason for no rate."""
    r = sweep.extra["risk"]
    order = [as_text(k) for k in tree_attrs(sweep.extra["fragility"]).get("axis_order", [])]
    combos = common.combinations(sweep, order)
    header = ["limit state", "combination", "λ [1/yr]", "λ 16–84 %", "P(50 yr)", "T_R [yr]",
              "Cornell [1/yr]", "beyond hazard", "outside stripes", "flags / reason"]
    rows = []
    for ls in (as_text(n) for n in r["attrs"]["limit_states"]):
        g = r[ls]

        def val(key, flat):
            return float(np.asarray(g[key], dtype=float).ravel()[flat])
        for flat, idx, label in combos:
            reason = as_text(g["reason"][flat])
            if reason:
                rows.append((ls, label, "–", "–", "–", "–", "–", "–", "–", reason))
                continue
            outside = val("share_above_stripes", flat) + val("share_below_stripes", flat)
            rows.append((ls, label, _num(val("rate_per_yr", flat)),
                         f"{_num(val('rate_p16', flat))}–{_num(val('rate_p84', flat))}",
                         _num(val("p_50yr", flat)), _num(val("return_period_yr", flat), "{:.0f}"),
                         _num(val("cornell_rate", flat)),
                         _num(100 * val("share_beyond_hazard", flat), "{:.1f} %"),
                         _num(100 * outside, "{:.1f} %"), as_text(g["flags"][flat])))
    return header, rows


def notes(sweep):
    """The hazard's identity and what every rate assumes, as Markdown lines."""
    a = tree_attrs(sweep.extra["risk"])
    out = [f"Hazard: `{a.get('hazard_file', '')}` ({a.get('hazard_format', '')}, "
           f"{int(a.get('hazard_bytes', 0))} bytes, SHA-256 `{a.get('hazard_sha256', '')}`), "
           f"{a.get('hazard_imt', '')}; fragility {a.get('fragility_imt', '')}; rule "
           f"{a.get('rule', '')}, tail {a.get('tail', '')}."]
    for n in sweep.extra["risk"]["attrs"].get("notes", []):
        out.append(f"- assumes: {as_text(n)}")
    return out
