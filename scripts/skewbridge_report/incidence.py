"""The figures of a sweep over the incidence angle (an incidence_deg axis; docs/hdf5-layout.md,
over_incidence/ and fragility_worst_incidence/): each limit state's demand against the angle,
one curve per stripe (the median over the records), with the median of the records' largest
over the angles beside it; and the fragility per angle beside the fragility at the worst
angle."""
import math
import textwrap

import matplotlib.pyplot as plt
import numpy as np

from . import common
from .common import combinations, im_label, limit_state_text
from .data import as_text, tree_attrs
from .fragility import _at, band, cell_im, floored

MAX_ROWS = 3  # combinations of the other axes drawn, one row each; the rest in the tables


def has_incidence(sweep):
    """Whether the sweep has an incidence_deg axis and its reductions over it."""
    return "incidence_deg" in sweep.axis_order and "over_incidence" in sweep.extra


def _other_axes(sweep, stripe_axis):
    """The axes other than record, the stripe axis and incidence_deg: one row per combination."""
    return [k for k in sweep.axis_order if k not in ("record", stripe_axis, "incidence_deg")]


def _demand_names(sweep):
    """(limit state, its demand response) of the sweep, in the fragility group's order; without
    limit states the rotation of the (first) deck."""
    if "fragility" in sweep.extra:
        names = [as_text(n) for n in tree_attrs(sweep.extra["fragility"])["limit_states"]]
        return [(n, f"ls_{n}_demand") for n in names
                if f"ls_{n}_demand" in sweep.responses and n != "joint_closing"]
    for r in ("theta_m", "theta_m_d0"):
        if r in sweep.responses:
            return [(None, r)]
    return []


def _take(sweep, values, keep, at):
    """`values` (cell-shaped) over the axes `keep` in that order, the others of `at` fixed."""
    order = list(sweep.axis_order)
    for key, i in at.items():
        values = np.take(values, i, axis=order.index(key))
        order.remove(key)
    return np.transpose(values, [order.index(k) for k in keep])


def response_figure(sweep, out_dir, name, pdf):
    """Per limit state (columns) and combination of the other axes (rows): its demand over the
    angle, median over the records, one curve per stripe, with dashed the median over the
    records of each record's largest over the angles (over_incidence/max). Returns the PNG's
    path and table rows (stripe, the angle of the largest median, the worst-angle median)."""
    pairs = _demand_names(sweep)
    fa = tree_attrs(sweep.extra["fragility"]) if "fragility" in sweep.extra else {}
    stripe_axis = fa.get("stripe_axis", "")
    others = _other_axes(sweep, stripe_axis)
    combos = combinations(sweep, others)
    shown = combos[:MAX_ROWS]
    angles = np.asarray(sweep.axes["incidence_deg"], dtype=float)
    stripes = list(sweep.axes[stripe_axis]) if stripe_axis else [None]
    styles = common.curve_styles(len(stripes), "viridis")
    over_max = sweep.extra["over_incidence"]["max"]
    rows_n, cols_n = len(shown), max(len(pairs), 1)
    fig, axes = plt.subplots(rows_n, cols_n, figsize=(4.4 * cols_n + 2.4, 3.5 * rows_n + 1.3),
                             squeeze=False, layout="constrained")
    table = []
    for r, (_, idx, label) in enumerate(shown):
        at = dict(zip(others, idx))
        for c, (ls, resp) in enumerate(pairs):
            ax = axes[r][c]
            ls_attrs = tree_attrs(sweep.extra["fragility"][ls]) if ls else {}
            cap = 1.0
            if ls and ls_attrs.get("kind") != "unseating":
                cap = float(ls_attrs.get("threshold", 1.0)) or 1.0
            demand = floored(np.asarray(sweep.responses[resp], dtype=float), ls_attrs) / cap
            keep = [k for k in (stripe_axis, "incidence_deg", "record") if k]
            keep = [k for k in keep if k in sweep.axis_order]
            d = _take(sweep, demand, keep, at)
            worst = floored(np.asarray(over_max[resp], dtype=float), ls_attrs) / cap
            wkeep = [k for k in (stripe_axis, "record") if k and k in sweep.axis_order]
            w = _take_reduced(sweep, worst, wkeep, at)
            if not stripe_axis:
                d, w = d[np.newaxis], w[np.newaxis]
            if "record" not in sweep.axis_order:
                d, w = d[..., np.newaxis], w[..., np.newaxis]
            positive = True
            for s, (color, marker, line) in zip(range(len(stripes)), styles):
                med = np.nanmedian(d[s], axis=-1) if np.isfinite(d[s]).any() else d[s][:, 0]
                wmed = float(np.nanmedian(w[s])) if np.isfinite(w[s]).any() else math.nan
                lab = (common.value_with_unit(sweep, stripe_axis, stripes[s]) if stripe_axis
                       else "median over the records" if "record" in sweep.axis_order
                       else resp)
                ax.plot(angles, med, marker=marker, ls="-", color=color, ms=4,
                        label=lab if r == 0 and c == 0 else None)
                if math.isfinite(wmed):
                    # open marker at the right end: which stripe the dashed line belongs to
                    ax.plot([angles.min(), angles.max()], [wmed, wmed], ls="--", color=color,
                            lw=0.9, marker=marker, mfc="none", ms=5, markevery=[1])
                positive = positive and bool(np.all(med[np.isfinite(med)] > 0))
                if np.isfinite(med).any():
                    k = int(np.nanargmax(med))
                    table.append((label, ls or resp, lab, f"{angles[k]:g}", f"{med[k]:.3g}",
                                  f"{wmed:.3g}"))
            if ls:
                ax.axhline(1.0, color="k", lw=1.0, ls=":")
            if positive and np.isfinite(d).any():
                common.log_axis(ax, "y")
            ax.set_xticks(angles if len(angles) <= 13 else angles[::2])
            ax.set_xlabel(r"incidence angle $\alpha_I$ [°] (H1 from the bridge's x axis)")
            unit = common.unit_text(sweep.response_attrs.get(resp, {}).get("units", ""))
            ax.set_ylabel("demand / capacity D/C" if ls else f"{resp} [{unit}]")
            title = limit_state_text(ls, sweep.extra["fragility"][ls]) if ls else resp
            ax.set_title(title + (f"\n{label}" if others else ""), fontsize=10)
    if not any(ls for ls, _ in pairs):
        common.finish_panels(fig, axes, rows_n * cols_n, (
            f"Solid: {pairs[0][1]} at each incidence angle α_I (the excitation along α_I from the "
            "bridge's x axis; a record pair's H1 along α_I, H2 at α_I + 90°), the median over the "
            "records where there are records. Dashed: its largest over the angles "
            "(over_incidence/max; the median over the records)."))
        return common.save(fig, out_dir, name, pdf), table
    common.finish_panels(fig, axes, rows_n * cols_n, (
        "Solid: median over the records of demand/capacity at each incidence angle α_I (H1 "
        "along α_I from the bridge's x axis, H2 at α_I + 90°), one curve per stripe. Dashed, "
        "ending in the stripe's open marker: median over the records of each record's largest "
        "demand over the angles (over_incidence/max), never below its stripe's solid curve. "
        "Dotted: D/C = 1."
        + (f" Only the first {len(shown)} of {len(combos)} combinations of "
           f"{', '.join(others)} are drawn." if len(shown) < len(combos) else "")))
    return common.save(fig, out_dir, name, pdf), table


def _take_reduced(sweep, values, keep, at):
    """_take over the axes of the sweep without incidence_deg (over_incidence/)."""
    order = [k for k in sweep.axis_order if k != "incidence_deg"]
    values = np.reshape(values, [len(sweep.axes[k]) for k in order])
    for key, i in at.items():
        values = np.take(values, i, axis=order.index(key))
        order.remove(key)
    return np.transpose(values, [order.index(k) for k in keep])


def _row_of(values, idx):
    """The stripe row [S] of one combination of a fragility's [combination..., S] array (the
    row [0] of a fit over no other axis)."""
    values = np.asarray(values)
    return values[idx] if idx else values[0]


def fragility_figure(sweep, out_dir, name, pdf):
    """Per limit state (columns) and combination of the other axes (rows): the fitted fragility
    at each incidence angle (thin, a sequential colour per angle) and at the worst angle (black,
    its 95 % band and its observed fraction per stripe). Returns the PNG's path and table
    rows of the worst-angle fits."""
    f, w = sweep.extra["fragility"], sweep.extra["fragility_worst_incidence"]
    fa, wa = tree_attrs(f), tree_attrs(w)
    names = [as_text(n) for n in fa["limit_states"]]
    order = [as_text(k) for k in fa.get("axis_order", [])]
    worder = [as_text(k) for k in wa.get("axis_order", [])]
    ki = order.index("incidence_deg")
    angles = np.asarray(sweep.axes["incidence_deg"], dtype=float)
    combos = combinations(sweep, worder)
    shown = combos[:MAX_ROWS]
    colors = plt.get_cmap("plasma")(np.linspace(0.0, 0.8, max(len(angles), 1)))
    styles = [(colors[i], None, common.LINESTYLES[i % len(common.LINESTYLES)])
              for i in range(len(angles))]
    im_vals = cell_im(sweep, fa).ravel()
    lo = np.nanmin(im_vals[im_vals > 0]) if np.any(im_vals > 0) else 0.01
    hi = np.nanmax(im_vals) if np.any(im_vals > 0) else 1.0
    x = np.geomspace(lo / 1.5, hi * 1.5, 200)
    rows_n, cols_n = len(shown), len(names)
    fig, axes = plt.subplots(rows_n, cols_n, figsize=(4.4 * cols_n + 2.4, 3.5 * rows_n + 1.3),
                             squeeze=False, layout="constrained")
    table = []
    for r, (wflat, widx, label) in enumerate(shown):
        for c, ls in enumerate(names):
            ax = axes[r][c]
            g, h = f[ls], w[ls]
            notes = []
            for i, (color, _, line) in enumerate(styles):
                idx = list(widx)
                idx.insert(ki, i)
                idx = tuple(idx)
                theta, beta = float(_at(g["theta"], idx)), float(_at(g["beta"], idx))
                lab = rf"$\alpha_I$ = {angles[i]:g}°" if r == 0 and c == 0 else None
                if math.isfinite(theta):
                    ax.plot(x, band(x, theta, beta, 0.0, 0.0, 0.0)[0], color=color, ls=line,
                            lw=1.3, label=lab)
                else:
                    ax.plot([], [], color=color, ls=line, lw=1.3, label=lab)
                    notes.append(f"{angles[i]:g}°")
            theta, beta = float(_at(h["theta"], widx)), float(_at(h["beta"], widx))
            if "stripe_im" in h:
                sx, sn, sz = (_row_of(h[key], widx)
                              for key in ("stripe_im", "stripe_n", "stripe_exceeded"))
                ok = sn > 0
                ax.plot(sx[ok], sz[ok] / sn[ok], marker="o", ls="none", color="k", mfc="none",
                        ms=6, label="worst angle: fraction" if r == 0 and c == 0 else None)
            if math.isfinite(theta):
                p, plo, phi = band(x, theta, beta, float(_at(h["se_ln_theta"], widx)) ** 2,
                                   float(_at(h["se_beta"], widx)) ** 2,
                                   float(_at(h["cov_ln_theta_beta"], widx)))
                ax.plot(x, p, color="k", lw=2.2,
                        label="worst angle: fit" if r == 0 and c == 0 else None)
                ax.fill_between(x, plo, phi, color="k", alpha=0.12, lw=0)
            else:
                notes.append("worst: " + as_text(h["reason"][wflat]).split(" (")[0])
            if notes:
                # Wrapped to the panel, so that a long reason does not widen the layout.
                angle_notes = [n for n in notes if not n.startswith("worst: ")]
                if len(angle_notes) == len(angles) > 1:
                    notes = ["every angle"] + notes[len(angles):]
                ax.text(0.02, 0.62, textwrap.fill("no fit: " + "; ".join(notes), 42),
                        transform=ax.transAxes, va="top", fontsize=8, color="0.3")
            common.log_axis(ax, "x")
            ax.set_ylim(-0.05, 1.05)
            ax.set_xlabel(im_label(sweep, fa))
            ax.set_ylabel("P(exceeded | IM)")
            ax.set_title(limit_state_text(ls, g) + (f"\n{label}" if worder else ""), fontsize=10)
    for wflat, widx, label in combos:
        for ls in names:
            g, h = f[ls], w[ls]
            per = []
            for i in range(len(angles)):
                idx = list(widx)
                idx.insert(ki, i)
                per.append(float(_at(g["theta"], tuple(idx))))
            per = np.asarray(per)
            gov = (f"{angles[int(np.nanargmin(per))]:g}" if np.isfinite(per).any() else "–")

            def num(key, grp=h, at=widx):
                v = float(_at(grp[key], at))
                return f"{v:.3g}" if math.isfinite(v) else "–"
            table.append((ls, label, int(_at(h["n_cells"], widx)), int(_at(h["n_exceeded"], widx)),
                          num("theta"), f"{num('boot_theta_lo')}–{num('boot_theta_hi')}",
                          num("beta"),
                          " / ".join(f"{v:.3g}" if math.isfinite(v) else "–" for v in per), gov,
                          as_text(h["reason"][wflat])))
    common.finish_panels(fig, axes, rows_n * cols_n, (
        "Thin lines: the maximum-likelihood lognormal fragility Φ(ln(IM/θ)/β) fitted at each "
        "incidence angle α_I (fragility/). Black: the fragility at the worst angle "
        "(fragility_worst_incidence/): a record at a stripe exceeds when it exceeds at some "
        "angle; circles its fraction per stripe, the band its pointwise 95 % interval from the "
        "observed information."
        + (f" Only the first {len(shown)} of {len(combos)} combinations are drawn; the table "
           "lists all." if len(shown) < len(combos) else "")))
    return common.save(fig, out_dir, name, pdf), table


def table_header(sweep):
    """The header of the worst-angle table, θ in the unit of the IM."""
    unit = tree_attrs(sweep.extra["fragility"]).get("im_units", "g")
    angles = " / ".join(f"{a:g}°" for a in sweep.axes["incidence_deg"])
    return ["limit state", "combination", "records × stripes", "exceeded at some angle",
            f"worst θ [{unit}]", "θ 95 % (bootstrap)", "worst β", f"θ per angle ({angles})",
            "governing angle [°] (lowest θ)", "note"]
