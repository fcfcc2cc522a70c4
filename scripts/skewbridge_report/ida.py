"""The figures and table of an incremental dynamic analysis ([ida], docs/sweep-format.md): per
limit state the IDA curves (each record's demand against the intensity of its runs, V&C's
axes: demand across, intensity up) with its capacity marked, and the fragility from the
capacities (their empirical distribution and the lognormal fit stored in fragility/)."""
import math
import re
import textwrap

import matplotlib.pyplot as plt
import matplotlib.ticker
import numpy as np
from scipy.stats import norm

from . import common
from .common import MAX_COMBOS, combinations, im_label, limit_state_text, shown_text
from .data import as_text, tree_attrs

COLUMNS = 4  # combinations a row of IDA curves; more than this: one figure per limit state
# The demand of each kind of limit state, as the x axis of its IDA curves.
DEMAND_TEXT = {"unseating": "corner travel / seat", "joint_closing": "impacts",
               "rotation": "rotation", "seat_displacement": "corner travel",
               "residual": "residual travel", "response": "response"}
RUN = re.compile(r"^ida_im_(\d+)$")


def is_ida(sweep):
    """Whether the cube is an IDA sweep (its fragility/ group's method is "ida")."""
    f = sweep.extra.get("fragility")
    return bool(f) and tree_attrs(f).get("method") == "ida"


def _runs(sweep):
    return sorted(int(m.group(1)) for n in sweep.responses if (m := RUN.match(n)))


def _select(sweep, array, order, idx):
    """The cells of one combination of the axes `order` (index `idx`): [record, ...] flat."""
    sel = [slice(None)] * len(sweep.axis_order)
    for key, i in zip(order, idx):
        sel[sweep.axis_order.index(key)] = i
    return np.asarray(array, dtype=float)[tuple(sel)].ravel()


def curves(sweep, out_dir, name, pdf):
    """The IDA curves of every combination of the other axes: up to COLUMNS combinations in one
    figure NAME (rows: limit states; columns: combinations), more as one figure per limit state
    NAME_<limit state> with the combinations as small multiples on shared axes, COLUMNS a row.
    Returns the paths written."""
    f = sweep.extra["fragility"]
    fa = tree_attrs(f)
    names = [as_text(n) for n in fa["limit_states"]]
    order = [as_text(k) for k in fa.get("axis_order", [])]
    combos = combinations(sweep, order)
    if len(combos) <= COLUMNS:
        fig, axes = plt.subplots(len(names), len(combos), squeeze=False, layout="constrained",
                                 figsize=(3.6 * len(combos) + 1.5, 3.0 * len(names) + 1.0))
        for r, ls in enumerate(names):
            for c, combo in enumerate(combos):
                _curves_panel(axes[r][c], sweep, ls, order, combo,
                              f"{limit_state_text(ls, f[ls])}\n{combo[2]}", c == 0)
        _from_zero(axes)
        common.finish_panels(fig, axes, axes.size, CURVES_TEXT)
        return [common.save(fig, out_dir, name, pdf)]
    paths = []
    rows_n = int(math.ceil(len(combos) / COLUMNS))
    for ls in names:
        fig, axes = plt.subplots(rows_n, COLUMNS, squeeze=False, layout="constrained",
                                 sharex=True, sharey=True,
                                 figsize=(3.0 * COLUMNS + 1.0, 2.6 * rows_n + 1.2))
        for c, combo in enumerate(combos):
            ax = axes[c // COLUMNS][c % COLUMNS]
            _curves_panel(ax, sweep, ls, order, combo, combo[2], c % COLUMNS == 0)
            # Shared axes: the demand named once per column, under its lowest panel.
            ax.xaxis.label.set_visible(c + COLUMNS >= len(combos))
            ax.xaxis.set_tick_params(labelbottom=c + COLUMNS >= len(combos))
        _from_zero(axes)
        title = (f"IDA curves of {limit_state_text(ls, f[ls]).strip()}, each of the {len(combos)} "
                 f"combinations of {', '.join(order)}")
        # 11 pt: under 8.5 px a glyph at 100 dpi.
        fig.suptitle("\n".join(textwrap.wrap(title, int(fig.get_figwidth() * common.DPI / 8.5))),
                     fontsize=11)
        common.finish_panels(fig, axes, len(combos), CURVES_TEXT)
        paths.append(common.save(fig, out_dir, f"{name}_{ls}", pdf))
    return paths


CURVES_TEXT = (
    "IDA curves [Vamvatsikos and Cornell 2002]: each line is one record, through the runs of its "
    "hunt-and-fill search sorted by intensity (from 0, 0); a cross marks its capacity, the lowest "
    "intensity at which the limit state is exceeded; the dotted line is the limit state's "
    "threshold (the seat for unseating: demand ratio 1).")


def _from_zero(axes):
    """Demand and intensity axes from 0, set once every panel is drawn (shared axes take their
    range from all of them)."""
    for ax in np.ravel(axes):
        ax.set_xlim(left=0.0)
        ax.set_ylim(bottom=0.0)


def _curves_panel(ax, sweep, ls, order, combo, title, first_column):
    """The IDA curves of one limit state and one combination (flat, idx, label) in `ax`."""
    f = sweep.extra["fragility"]
    a = tree_attrs(f[ls])
    runs = _runs(sweep)
    idx = combo[1]
    n_records = len(sweep.axes["record"]) if "record" in sweep.axes else 1
    cmap = "tab10" if n_records <= 10 else "tab20"  # tab20's pairs only where 10 do not do
    colors = [plt.get_cmap(cmap)(i % 20) for i in range(n_records)]
    im = np.stack([_select(sweep, sweep.responses[f"ida_im_{k:02d}"], order, idx) for k in runs])
    d = np.stack([_select(sweep, sweep.responses[f"ida_demand_{ls}_{k:02d}"], order, idx)
                  for k in runs])
    cap = _select(sweep, sweep.responses[f"ida_capacity_{ls}"], order, idx)
    for j in range(im.shape[1]):
        ok = np.isfinite(im[:, j]) & np.isfinite(d[:, j])
        o = np.argsort(im[ok, j])
        x, y = d[ok, j][o], im[ok, j][o]
        ax.plot(np.r_[0.0, x], np.r_[0.0, y], "-", lw=0.9, color=colors[j % len(colors)],
                marker=".", ms=3)
        if math.isfinite(cap[j]):
            at = np.flatnonzero(y == cap[j])
            if at.size:
                ax.plot(x[at[0]], y[at[0]], "x", color="k", ms=6, mew=1.4)
    if a.get("kind") not in ("unseating", "joint_closing"):
        ax.axvline(float(a.get("threshold", 0.0)), color="k", ls=":", lw=1.0)
    elif a.get("kind") == "unseating":
        ax.axvline(1.0, color="k", ls=":", lw=1.0)
    units = sweep.response_attrs.get(f"ida_demand_{ls}_00", {}).get("units", "")
    ax.set_xlabel(f"{DEMAND_TEXT.get(a.get('kind'), 'demand')} [{as_text(units) or '1'}]")
    if first_column:
        ax.set_ylabel(im_label(sweep, tree_attrs(f)))
    ax.set_title(title, fontsize=9)
    ax.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(4))  # rad: 6-digit tick labels


def fragility(sweep, out_dir, name, pdf):
    """One panel per limit state: the empirical distribution of the capacities (steps) per
    combination and the stored lognormal fit Φ(ln(IM/θ)/β). Returns the table rows."""
    f = sweep.extra["fragility"]
    fa = tree_attrs(f)
    names = [as_text(n) for n in fa["limit_states"]]
    order = [as_text(k) for k in fa.get("axis_order", [])]
    combos = combinations(sweep, order)
    shown = combos[:MAX_COMBOS]
    styles = common.category_styles(len(shown))
    rows_n, cols_n = common.panel_grid(len(names))
    fig, axes = plt.subplots(rows_n, cols_n, figsize=(4.2 * cols_n + 2.2, 3.6 * rows_n + 1.2),
                             squeeze=False, layout="constrained")
    table = []
    for k, ls in enumerate(names):
        ax = axes[k // cols_n][k % cols_n]
        g = f[ls]
        caps_all = np.asarray(sweep.responses[f"ida_capacity_{ls}"], dtype=float)
        finite = caps_all[np.isfinite(caps_all) & (caps_all > 0)]
        lo, hi = (finite.min(), finite.max()) if finite.size else (0.05, 5.0)
        x = np.geomspace(lo / 2, hi * 2, 200)
        for (flat, idx, label), (color, marker, ls_style) in zip(shown, styles):
            cap = np.sort(_select(sweep, caps_all, order, idx))
            n = np.count_nonzero(~np.isnan(cap))
            fin = cap[np.isfinite(cap)]
            if fin.size:
                # Empirical: the share of records whose capacity is at most x (censored ones
                # count in n, never reached).
                ax.step(np.r_[x[0], fin], np.r_[0.0, np.arange(1, fin.size + 1) / n],
                        where="post", color=color, lw=0.9)
                ax.plot(fin, np.arange(1, fin.size + 1) / n, ls="none", color=color,
                        marker=marker, mfc="none", ms=5, label=label)
            theta = float(np.asarray(g["theta"]).ravel()[flat])
            beta = float(np.asarray(g["beta"]).ravel()[flat])
            if math.isfinite(theta) and math.isfinite(beta) and beta > 0:
                ax.plot(x, norm.cdf(np.log(x / theta) / beta), color=color, ls=ls_style)
        for flat, idx, label in combos:
            theta = float(np.asarray(g["theta"]).ravel()[flat])
            beta = float(np.asarray(g["beta"]).ravel()[flat])
            table.append((ls, label, int(np.asarray(g["n_records"]).ravel()[flat]),
                          int(np.asarray(g["n_censored"]).ravel()[flat]),
                          int(np.asarray(g["n_scaled_too_far"]).ravel()[flat])
                          if "n_scaled_too_far" in g else 0,
                          f"{theta:.3g}" if math.isfinite(theta) else "–",
                          f"{beta:.3g}" if math.isfinite(beta) else "–",
                          as_text(np.asarray(g["reason"]).ravel()[flat])))
        common.log_axis(ax, "x")
        ax.set_ylim(-0.05, 1.05)
        ax.set_xlabel(im_label(sweep, fa))
        ax.set_ylabel("P(capacity ≤ IM)")
        ax.set_title(limit_state_text(ls, g), fontsize=10)
    common.finish_panels(fig, axes, len(names), (
        "Steps: the share of the records whose IDA capacity is at or below the intensity "
        "(records that never reached the limit state count, never exceeded). Lines: the "
        "lognormal fit Φ(ln(IM/θ)/β) with θ the geometric mean of the capacities and β the "
        "standard deviation of their logarithms (Baker 2015), or, where some records never "
        "reached it, the maximum-likelihood fit with those right-censored at their highest "
        "run; none where fewer than 2 capacities are finite (the table says why)."
        + shown_text(len(shown), len(combos))))
    return common.save(fig, out_dir, name, pdf), table


def table_header(sweep):
    unit = tree_attrs(sweep.extra["fragility"]).get("im_units", "g")
    return ["limit state", "combination", "records with a capacity", "censored",
            "of them beyond max_scale", f"θ [{unit}]", "β", "note"]
