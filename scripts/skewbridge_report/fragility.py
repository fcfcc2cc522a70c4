"""The fragility figures and tables of a sweep with limit states (docs/hdf5-layout.md,
fragility/): per limit state, the maximum-likelihood lognormal curves with the observed fraction
per stripe and the 95 % band of the likelihood, and the cloud of demand over capacity against
the intensity measure with its regression line."""
import math
import textwrap

import matplotlib.pyplot as plt
import numpy as np
from scipy.stats import norm

from . import common
from .common import MAX_COMBOS, combinations, im_label, limit_state_text, shown_text
from .data import as_text, tree_attrs

Z95 = 1.959963984540054


def cell_im(sweep, fa):
    """The IM of every cell, shaped like the cells (as jobs/study.cpp takes it)."""
    if fa["im"] in ("im_g", "im_mps"):
        axis = np.asarray(sweep.axes[fa["im"]], dtype=float)
        return np.broadcast_to(axis.reshape([-1 if k == fa["im"] else 1
                                             for k in sweep.axis_order]), sweep.shape())
    if fa["im"] == "im":
        return np.asarray(sweep.responses["im"], dtype=float)
    return np.asarray(sweep.responses["a_g"], dtype=float) / 9.80665


def beyond_max_scale(sweep):
    """The cells scaled beyond [records] max_scale (response scaled_too_far), the rule
    ("keep" or "exclude") and the limit; (None, "", None) without a limit."""
    limit = float(sweep.im_attrs.get("max_scale", "inf"))
    if not math.isfinite(limit) or "scaled_too_far" not in sweep.responses:
        return None, "", None
    far = np.asarray(sweep.responses["scaled_too_far"], dtype=float) == 1.0
    return far, sweep.im_attrs.get("beyond_max_scale", "keep"), limit


def beyond_text(rule, limit):
    """The legend label of the cells scaled beyond max_scale."""
    return f"scaled > {limit:g} ({'left out' if rule == 'exclude' else 'in the fit'})"


def _select(sweep, order, idx):
    """The index of one combination's cells in the cube's arrays."""
    sel = [slice(None)] * len(sweep.axis_order)
    for key, i in zip(order, idx):
        sel[sweep.axis_order.index(key)] = i
    return tuple(sel)


def floored(demand, ls_attrs):
    """A limit state's demands with the values below the cube's round-off floor (rotations:
    spectra::kRotationRoundOffFloor_rad) set to 0, as the fits read them."""
    floor = float(ls_attrs.get("round_off_floor", 0.0))
    return np.where(np.abs(demand) < floor, 0.0, demand)


def _at(array, idx):
    return np.asarray(array)[idx] if idx else np.asarray(array).ravel()[0]


def band(x, theta, beta, var_ln, var_beta, cov):
    """The fitted curve and its pointwise 95 % band by the delta method on (ln theta, beta):
    u = (ln x - ln theta) / beta, du/d ln theta = -1 / beta, du/d beta = -u / beta."""
    u = (np.log(x) - math.log(theta)) / beta
    g1, g2 = -1.0 / beta, -u / beta
    sd = np.sqrt(np.maximum(g1 * g1 * var_ln + 2 * g1 * g2 * cov + g2 * g2 * var_beta, 0.0))
    return norm.cdf(u), norm.cdf(u - Z95 * sd), norm.cdf(u + Z95 * sd)


def fragility_curves(sweep, out_dir, name, pdf):
    """One panel per limit state: fitted P(exceeded | IM) per combination, its 95 % band, and
    the observed fraction per stripe (or each cell's 0/1 for a cloud). Returns table rows."""
    f = sweep.extra["fragility"]
    fa = tree_attrs(f)
    names = [as_text(n) for n in fa["limit_states"]]
    order = [as_text(k) for k in fa.get("axis_order", [])]
    combos = combinations(sweep, order)
    shown = combos[:MAX_COMBOS]
    rows_n, cols_n = common.panel_grid(len(names))
    fig, axes = plt.subplots(rows_n, cols_n, figsize=(4.2 * cols_n + 2.2, 3.6 * rows_n + 1.2),
                             squeeze=False, layout="constrained")
    styles = common.category_styles(len(shown))
    table = []
    for k, ls in enumerate(names):
        ax = axes[k // cols_n][k % cols_n]
        g = f[ls]
        im_vals = cell_im(sweep, fa).ravel()
        lo = np.nanmin(im_vals[im_vals > 0]) if np.any(im_vals > 0) else 0.01
        hi = np.nanmax(im_vals) if np.any(im_vals > 0) else 1.0
        x = np.geomspace(lo / 1.5, hi * 1.5, 200)
        notes = []
        far, rule, limit = beyond_max_scale(sweep)
        z_cells = np.asarray(sweep.responses["ls_" + ls], dtype=float)
        im_cells = cell_im(sweep, fa)
        far_label = beyond_text(rule, limit) if far is not None else ""
        for (flat, idx, label), (color, marker, ls_style) in zip(shown, styles):
            theta, beta = float(_at(g["theta"], idx)), float(_at(g["beta"], idx))
            if far is not None:
                # The cells beyond max_scale: their own fraction per stripe (a cloud: each 0/1),
                # grey crosses, so that what they say is seen beside what the fit uses.
                sel = _select(sweep, order, idx)
                fz, fx, ff = z_cells[sel], im_cells[sel], far[sel]
                pick = ff & np.isfinite(fz) & (fx > 0)
                if pick.any():
                    xs, inv = np.unique(fx[pick], return_inverse=True)
                    frac = np.bincount(inv, weights=fz[pick]) / np.bincount(inv)
                    ax.plot(xs, frac, marker="x", ls="none", color="0.45", ms=5, mew=1.0,
                            label=far_label, zorder=1)
                    far_label = ""
            if "stripe_im" in g:
                sx = np.asarray(g["stripe_im"])[idx] if idx else np.asarray(g["stripe_im"])[0]
                sn = np.asarray(g["stripe_n"])[idx] if idx else np.asarray(g["stripe_n"])[0]
                sz = (np.asarray(g["stripe_exceeded"])[idx] if idx
                      else np.asarray(g["stripe_exceeded"])[0])
                ok = sn > 0
                ax.plot(sx[ok], sz[ok] / sn[ok], marker=marker, ls="none", color=color,
                        mfc="none", ms=6, label=label)
            else:
                zc, xc = _cells_of(sweep, fa, ls, idx, order)
                ax.plot(xc, zc + 0.02 * (2 * (flat % 2) - 1), marker=marker, ls="none",
                        color=color, ms=3, alpha=0.5, label=label)
            if math.isfinite(theta):
                p, plo, phi = band(x, theta, beta, float(_at(g["se_ln_theta"], idx)) ** 2,
                                   float(_at(g["se_beta"], idx)) ** 2,
                                   float(_at(g["cov_ln_theta_beta"], idx)))
                ax.plot(x, p, color=color, ls=ls_style)
                ax.fill_between(x, plo, phi, color=color, alpha=0.15, lw=0)
            else:
                notes.append((label, as_text(g["reason"][flat])))
        if notes:
            # Where the curves are not: left of the steps, at mid height; each combination with
            # its own reason (the full reasons are in the table).
            ax.text(0.02, 0.62, _no_fit_text(notes, len(shown)), transform=ax.transAxes,
                    va="top", fontsize=8, color="0.3")
        common.log_axis(ax, "x")
        ax.set_ylim(-0.05, 1.05)
        ax.set_xlabel(im_label(sweep, fa))
        ax.set_ylabel("P(exceeded | IM)")
        ax.set_title(limit_state_text(ls, g), fontsize=10)
        for flat, idx, label in combos:
            table.append(_row(ls, g, flat, idx, label))
    common.finish_panels(fig, axes, len(names), (
        "Markers: fraction of the cells of a stripe that exceeded the limit state (a cloud: each "
        "cell's 0 or 1). Lines: the maximum-likelihood lognormal fragility "
        "Φ(ln(IM/θ)/β) (binomial likelihood, Baker 2015); bands: its pointwise 95 % interval "
        "from the observed information (delta method)." + _far_caption(sweep)
        + shown_text(len(shown), len(combos))))
    return common.save(fig, out_dir, name, pdf), table


def _far_caption(sweep):
    """The caption's sentence on the cells scaled beyond max_scale, or ""."""
    far, rule, limit = beyond_max_scale(sweep)
    if far is None:
        return ""
    if rule == "exclude":
        return (f" Grey crosses: the cells whose record was scaled by more than max_scale = "
                f"{limit:g} ({int(far.sum())} cells), left out of every fit; the open markers "
                f"count the other cells only.")
    return (f" Grey crosses: the cells whose record was scaled by more than max_scale = "
            f"{limit:g} ({int(far.sum())} cells), kept in the fits (beyond_max_scale = keep).")


def _short(reason):
    """The first clause of a reason: what happened, without the numbers that follow."""
    return reason.split(" (")[0].split(":")[0]


def _no_fit_text(notes, shown):
    """The words of a panel for its combinations without a fit: the reason once when they share
    it, else each combination's label with its own reason. `notes`: (label, reason) pairs."""
    head = f"no fit for {len(notes)} of {shown}:"
    short = [_short(reason) for _, reason in notes]
    if len(set(short)) == 1:
        return head + "\n" + "\n".join(textwrap.wrap(short[0], 26))
    return head + "\n" + "\n".join(
        textwrap.shorten(f"{label}: {why}", 40, placeholder="…")
        for (label, _), why in zip(notes, short))


def _cells_of(sweep, fa, ls, idx, order):
    """The 0/1 exceedance and IM of the cells of one combination (cloud panels)."""
    z = np.asarray(sweep.responses["ls_" + ls], dtype=float)
    im = cell_im(sweep, fa)
    sel = [slice(None)] * len(sweep.axis_order)
    for key, i in zip(order, idx):
        sel[sweep.axis_order.index(key)] = i
    z, im = z[tuple(sel)].ravel(), im[tuple(sel)].ravel()
    ok = np.isfinite(z) & (im > 0)
    return z[ok], im[ok]


def _row(ls, g, flat, idx, label):
    def num(key, fmt="{:.3g}"):
        v = float(_at(g[key], idx))
        return fmt.format(v) if math.isfinite(v) else "–"
    theta = num("theta")
    ci = (f"{num('theta_lo')}–{num('theta_hi')}" if theta != "–" else "–")
    boot = (f"{num('boot_theta_lo')}–{num('boot_theta_hi')}"
            if math.isfinite(float(_at(g["boot_theta_lo"], idx))) else "–")
    reason = as_text(g["reason"][flat]) or as_text(g["cloud_reason"][flat])
    if "n_excluded_beyond_max_scale" in g:
        out = int(_at(g["n_excluded_beyond_max_scale"], idx))
        left = f"{out} cell(s) scaled beyond max_scale left out of the fits"
        reason = f"{left}; {reason}" if reason else left
    return (ls, label, int(_at(g["n_cells"], idx)), int(_at(g["n_exceeded"], idx)), theta, ci,
            boot, num("beta"), num("se_beta"), num("cloud_theta"), num("cloud_beta"), reason)


def table_header(sweep):
    """The header of the table of fits, θ in the unit of the IM."""
    unit = tree_attrs(sweep.extra["fragility"]).get("im_units", "g")
    return ["limit state", "combination", "cells", "exceeded", f"θ [{unit}]",
            "θ 95 % (likelihood)", "θ 95 % (bootstrap)", "β", "se(β)", f"cloud θ [{unit}]",
            "cloud β", "note"]


def cloud(sweep, out_dir, name, pdf):
    """One panel per limit state with a cloud fit: D / C of every cell against the IM (log-log)
    with the regression line per combination and D / C = 1. Returns None when none has one."""
    f = sweep.extra["fragility"]
    fa = tree_attrs(f)
    names = [as_text(n) for n in fa["limit_states"]
             if any(not as_text(r) for r in f[as_text(n)]["cloud_reason"])]
    if not names:
        return None
    order = [as_text(k) for k in fa.get("axis_order", [])]
    combos = combinations(sweep, order)
    shown = combos[:MAX_COMBOS]
    styles = common.category_styles(len(shown))
    rows_n, cols_n = common.panel_grid(len(names))
    fig, axes = plt.subplots(rows_n, cols_n, figsize=(4.2 * cols_n + 2.2, 3.6 * rows_n + 1.2),
                             squeeze=False, layout="constrained")
    for k, ls in enumerate(names):
        ax = axes[k // cols_n][k % cols_n]
        g = f[ls]
        a = tree_attrs(g)
        cap = 1.0 if a.get("kind") == "unseating" else float(a.get("threshold", 1.0))
        d_all = floored(np.asarray(sweep.responses["ls_" + ls + "_demand"], dtype=float),
                        a) / cap
        im_all = cell_im(sweep, fa)
        far_all, rule, limit = beyond_max_scale(sweep)
        far_label = beyond_text(rule, limit) if far_all is not None else ""
        for (flat, idx, label), (color, marker, ls_style) in zip(shown, styles):
            sel = _select(sweep, order, idx)
            d, im = d_all[sel].ravel(), im_all[sel].ravel()
            far = (far_all[sel].ravel() if far_all is not None
                   else np.zeros(d.shape, dtype=bool))
            ok = np.isfinite(d) & (d > 0) & (im > 0)
            if rule == "exclude":
                # The stored line is the fit without them: so is the range it is drawn over.
                ok_line = ok & ~far
            else:
                ok_line = ok
            ax.plot(im[ok & ~far], d[ok & ~far], marker=marker, ls="none", color=color, ms=4,
                    alpha=0.6, mfc="none", label=label)
            if (ok & far).any():
                ax.plot(im[ok & far], d[ok & far], marker="x", ls="none", color="0.45", ms=4,
                        mew=0.9, label=far_label, zorder=1)
                far_label = ""
            b, c = float(_at(g["cloud_slope"], idx)), float(_at(g["cloud_intercept"], idx))
            if math.isfinite(b) and ok_line.any():
                x = np.geomspace(im[ok_line].min(), im[ok_line].max(), 50)
                ax.plot(x, np.exp(c + b * np.log(x)), color=color, ls=ls_style)
        ax.axhline(1.0, color="k", lw=1.0, ls=":")
        ax.text(0.02, 1.0, " D/C = 1", transform=ax.get_yaxis_transform(), ha="left",
                va="bottom", fontsize=8)
        common.log_axis(ax, "x")
        common.log_axis(ax, "y")
        ax.set_xlabel(im_label(sweep, fa))
        ax.set_ylabel("demand / capacity D/C")
        ax.set_title(limit_state_text(ls, g), fontsize=10)
    common.finish_panels(fig, axes, len(names), (
        "Markers: each cell's demand over the limit state's capacity (unseating: corner travel "
        "over seat width; a rotation below the cube's round-off floor round_off_floor_rad is 0, "
        "not drawn). Lines: least squares of ln(D/C) on ln(IM) per combination (cloud "
        "analysis, Cornell et al. 2002); their crossing of D/C = 1 is the cloud median θ."
        + _far_caption(sweep).replace("open markers count", "lines fit")
        + shown_text(len(shown), len(combos))))
    return common.save(fig, out_dir, name, pdf)
