"""Figures and tables for any sweep of any family, from what the cube itself says: its axes with
their units, its responses with theirs, per deck where a response carries a deck suffix _d<i>.

- which quantities are drawn and against which axes is planning.plan_generic's (pure);
- response_vs_intensity(): each drawn quantity against the intensity of each cell's record;
- response_vs_axis(): each drawn quantity (a row of panels) against one numeric axis, one curve
  per value of a second axis, one column per combination of the others (small multiples, in
  pages of at most MAX_COLUMNS columns); over a record axis, one thin line per record with the
  median and the 16-84 % band of the records;
- unseating_margins(): the unseating margins against one numeric axis with the line of zero
  margin and the unseated side shaded;
- response_table(), unseating_table(), record_table(): the Markdown tables of summary.md.

Each figure function draws one figure kind and returns (path, table rows), as in figures.py,
so that other figure kinds slot in beside them."""
import itertools
import re
from dataclasses import dataclass

import matplotlib.lines
import matplotlib.pyplot as plt
import numpy as np

from . import common, planning, stats
from .common import ZERO, unit_text
from .planning import MARGINS, numeric_axes

# The per-run responses of an IDA search (ida_..._NN): drawn by the IDA curves (ida.py), left
# out of the table of responses.
IDA_RUN = re.compile(r"^ida_.*_\d+$")

# Axis symbols for mathtext, beyond common.AXIS_LABEL.
AXIS_SYMBOL = {"T_g": r"$T_g$", "w_g": r"$\omega_g$", "k_factor": r"$K$ factor",
               "scale": "scale factor", "gap_m": r"$\delta$", "a_g_g": r"$a_g$",
               "seat_over_L": "seat/$L$", "seat_m": "seat", "spans": "spans",
               "L_over_Le": r"$L/L_e$", "method": "method", "pulse": "pulse", "record": "record"}
QUANTITY_SYMBOL = {
    "x_m": r"$x_m$", "y_m": r"$y_m$", "theta_m": r"$\theta_m$", "x_end": r"$x_{end}$",
    "y_end": r"$y_{end}$", "theta_end": r"$\theta_{end}$", "margin_m": "unseating margin",
    "travel_m": "corner travel", "travel_end_m": "residual corner travel",
    "travel_bound_m": "corner travel bound",
    "margin_norm": r"unseating margin $\times\,\omega_g^2/a_g$", "impacts": "impacts",
    "theta_norm_max": r"$\max_i\,\theta_{m,i}\,\rho_i\,\omega_g^2/a_g$",
}
QUANTITY_TEXT = {"x_m": "x_m", "y_m": "y_m", "theta_m": "θ_m", "x_end": "x_end",
                 "y_end": "y_end", "theta_end": "θ_end", "margin_m": "unseating margin",
                 "margin_norm": "unseating margin ω_g²/a_g", "impacts": "impacts",
                 "travel_m": "corner travel", "travel_bound_m": "corner travel bound",
                 "x_norm": "x_m ω_g²/a_g", "y_norm": "y_m ω_g²/a_g",
                 "theta_norm": "θ_m ρ ω_g²/a_g", "theta_end_norm": "θ_end ρ ω_g²/a_g",
                 "theta_norm_max": "max over decks of θ_m ρ ω_g²/a_g"}
# At most this many columns of panels in one figure; more combinations make more pages.
MAX_COLUMNS = 6
# One panel's size in inches; a figure is as large as its panels and legend need.
PANEL_IN = (3.3, 2.3)


def axis_symbol(key, sweep=None):
    """The symbol of an axis in mathtext; the stripes of a scaled record sweep by the name of
    their measure (`Sa(T1, 5 %)`) when `sweep` stores it."""
    if key in ("im_g", "im_mps") and sweep is not None and common.im_name(sweep):
        return common.im_name(sweep)
    return common.AXIS_LABEL.get(key) or AXIS_SYMBOL.get(key) or key.replace("_", " ")


def axis_unit(sweep, key):
    unit = sweep.axis_attrs.get(key, {}).get("units")
    if unit is None:
        unit = sweep.fixed_units.get(key, "")
    return unit_text(unit)


def axis_label(sweep, key):
    """`α [°]`, `$T_g$ [s]`: the axis symbol with its unit from the cube's attributes."""
    unit = axis_unit(sweep, key)
    return axis_symbol(key, sweep) + (f" [{unit}]" if unit else "")


def value_label(sweep, key, value):
    """A legend or panel entry: `α = 30°`, `$T_g$ = 0.5 s`, `pulse: cosine`, `deck 1`."""
    if key == "deck":
        return f"deck {value}"
    if isinstance(value, str):
        return f"{axis_symbol(key, sweep)}: {value}"
    unit = axis_unit(sweep, key)
    sep = "" if unit == "°" else " "
    text = common.number_text(value, sweep.axes.get(key, [value]))
    return f"{axis_symbol(key, sweep)} = {text}" + (f"{sep}{unit}" if unit else "")


def quantity_label(q, unit=None):
    """The y label of a quantity: its symbol and unit (`unit` replaces the cube's: mm, mrad)."""
    symbol = QUANTITY_SYMBOL.get(q.base) or common.RESPONSE_LABEL.get(q.base)
    if symbol is None:
        symbol = q.base.replace("_", " ")
    symbol = symbol.split(" [")[0]
    unit = unit or unit_text(q.unit)
    return symbol + (f" [{unit}]" if unit else "")


def quantity_text(q, deck=None):
    text = QUANTITY_TEXT.get(q.base, q.base)
    return text + (f" (deck {deck})" if deck is not None else "")


def intensity_of(sweep):
    """(values per cell, axis label, table text) of the intensity each cell of a record sweep
    felt, from planning.intensity_source: the stored `im`, else the cell's PGA (`pga`, `a_g`),
    else the record table's PGA; None without one."""
    source = planning.intensity_source(sweep)
    if source is None:
        return None
    if source == "records":
        pga = np.asarray(sweep.extra["records"]["pga_mps2"], dtype=float)
        shape = [1] * len(sweep.axis_order)
        shape[sweep.axis_order.index("record")] = len(pga)
        return np.broadcast_to(pga.reshape(shape), sweep.shape()), "PGA [m/s²]", "PGA"
    text = (common.im_name(sweep) or "IM") if source == "im" else "PGA"
    unit = unit_text(str(sweep.response_attrs.get(source, {}).get("units", "")))
    return (np.asarray(sweep.responses[source], dtype=float),
            text + (f" [{unit}]" if unit else ""), text)


def response_vs_intensity(sweep, qs, out_dir, name, pdf):
    """Each quantity (a panel) against the intensity of each cell's record (intensity_of): one
    point per cell, told apart by the values of the sweep's numeric axis of most values.
    Returns table rows (quantity, cells, Spearman rank correlation with the intensity)."""
    im, im_label, _ = intensity_of(sweep)
    numeric = sorted((k for k in numeric_axes(sweep)), key=lambda k: -len(sweep.axes[k]))
    key = numeric[0] if numeric else None
    groups = list(range(len(sweep.axes[key]))) if key else [None]
    n_rows, n_cols, place = _panel_grid(len(qs), 1)
    fig, axes = _figure(n_rows, n_cols, 1)
    styles = common.curve_styles(len(groups))
    legend, table = {}, []
    for row, q in enumerate(qs):
        r, c = place(row, 0)
        ax = axes[r][c]
        stacked = np.stack([np.asarray(sweep.responses[n], dtype=float) for n in q.names])
        values = envelope(q, stacked)
        values = np.where(np.abs(values) < ZERO, 0.0, values)
        factor, unit = display_scale(sweep, q)
        for ig, gi in enumerate(groups):
            sel = np.ones(sweep.shape(), dtype=bool)
            if key is not None:
                sel = np.zeros(sweep.shape(), dtype=bool)
                index = [slice(None)] * len(sweep.axis_order)
                index[sweep.axis_order.index(key)] = gi
                sel[tuple(index)] = True
            color, marker, _ = styles[ig]
            many = len(groups) > common.MAX_LEGEND
            h, = ax.plot(im[sel], values[sel] * factor, marker if not many else "o", ms=4,
                         ls="none", color=color, mfc="none" if not many else color)
            if key is not None and not many:
                legend.setdefault(value_label(sweep, key, sweep.axes[key][gi]), h)
        finite = np.isfinite(values) & np.isfinite(im)
        if not np.any(finite):
            common.no_data(ax)
        if np.all(im[np.isfinite(im)] > 0) and np.nanmax(im) / np.nanmin(im) >= 5:
            common.log_axis(ax, "x")
        if q.base == "impacts":
            common.integer_axis(ax)
        ax.set_ylabel(quantity_label(q, unit) + _deck_note(q))
        ax.set_xlabel(im_label)
        ax.xaxis.set_tick_params(labelbottom=True)
        x, y = im[finite], values[finite]
        rho = stats.spearman(x, y) if len(x) >= 3 else float("nan")
        table.append((quantity_text(q), int(finite.sum()), rho))
    for rr in range(n_rows):
        for cc in range(n_cols):
            if rr * n_cols + cc >= len(qs):
                axes[rr][cc].remove()
    layout = Layout("record", key, False, [()], "")
    if key is not None and len(groups) > common.MAX_LEGEND:
        legend = {}
    _finish(fig, axes, sweep, layout, legend, "responses against the intensity of each record",
            qs=qs)
    return common.save(fig, out_dir, name, pdf), table


@dataclass
class Layout:
    """How one figure spreads the grid: abscissa, curves, sample and columns of panels."""

    x: str
    curve: str  # axis key, or None for one curve
    sample: bool  # curves over a record axis: thin lines, median and band
    columns: list  # [(key, index)] per column: a combination of the remaining axes
    fixed_text: str  # the axes of one value, as `key = value, ...`


def _column_axes(sweep, x, curve, hold=()):
    keys = [k for k in sweep.axis_order
            if k not in (x, curve) and k not in hold and sweep.has_axis(k, 2)]
    return [(k, list(range(len(sweep.axes[k])))) for k in keys]


def layouts(sweep, x, hold=()):
    """The pages of figures for abscissa x: curves over the other numeric axis of most values
    (else a label axis; over the records when there is a record axis), columns over the rest.
    The axes in `hold` (those of the limit states alone, for the responses) are held at their
    first value and named once in the title: every value draws the same."""
    others = [k for k in sweep.axis_order
              if k != x and k not in hold and sweep.has_axis(k, 2)]
    sample = "record" in others
    if sample:
        curve = "record"
    else:
        # the numeric axis of most values makes the curves (a colour bar beyond MAX_LEGEND),
        # so that the fewest combinations are left for the columns
        numeric = [k for k in others if not isinstance(sweep.axes[k], list)]
        numeric.sort(key=lambda k: -len(sweep.axes[k]))
        curve = (numeric or others or [None])[0]
    col_axes = _column_axes(sweep, x, curve, hold)
    combos = list(itertools.product(*[[(key, i) for i in idx] for key, idx in col_axes])) or [()]
    fixed = [value_label(sweep, k, sweep.axes[k][0]) for k in sweep.axis_order
             if len(sweep.axes[k]) == 1]
    fixed += [f"the same at every {axis_symbol(k, sweep)}" for k in hold
              if k != x and sweep.has_axis(k, 2)]
    pages = [combos[i:i + MAX_COLUMNS] for i in range(0, len(combos), MAX_COLUMNS)]
    return [Layout(x, curve, sample, list(page), ", ".join(fixed)) for page in pages]


def _combo_title(sweep, combo):
    return ", ".join(value_label(sweep, key, sweep.axes[key][i]) for key, i in combo)


def envelope(q, stacked):
    """The worst deck of a per-deck quantity, cell by cell (axis 0 of `stacked` is the deck):
    the smallest unseating margin, the residual of largest magnitude (its sign kept), else the
    largest value. NaN only where every deck is NaN."""
    if len(stacked) == 1:
        return stacked[0]
    with np.errstate(all="ignore"):
        if q.base in MARGINS:
            return np.nanmin(np.where(np.isnan(stacked), np.inf, stacked), axis=0).astype(float) \
                if np.any(np.isfinite(stacked)) else stacked[0]
        if q.base.endswith("_end"):
            k = np.nanargmax(np.where(np.isnan(stacked), -1.0, np.abs(stacked)), axis=0)
            return np.take_along_axis(stacked, k[np.newaxis], axis=0)[0]
        return np.nanmax(np.where(np.isnan(stacked), -np.inf, stacked), axis=0)


def _series(sweep, q, layout, combo):
    """The quantity over [curve, x] (or [1, x]) at one column combination; a per-deck quantity
    as its envelope over the decks (envelope())."""
    at = dict(combo)
    keep = ([layout.curve] if layout.curve else []) + [layout.x]
    stacked = np.stack([common.select(sweep, n, keep, at) for n in q.names])
    values = envelope(q, stacked)
    values = np.where(np.isinf(values), np.nan, values)
    if not layout.curve:
        values = values[np.newaxis, :]
    return np.where(np.abs(values) < ZERO, 0.0, values), None


def _caption_keys(sweep, layout, qs=()):
    keys = ["x"] + (["end"] if any(q.base.endswith("_end") for q in qs) else [])
    if any(len(q.decks) > 1 for q in qs):
        keys.append("decks")
    if any(q.base == "travel_m" for q in qs):
        keys.append("travel")
    labels = " ".join(quantity_label(q) for q in qs)
    if r"\rho" in labels:
        keys.append("rho")
    if "a_g" in labels and "ag" not in keys:
        keys.append("ag")
    present = set(sweep.axis_order) | set(sweep.fixed)
    if "a_deg" in present:
        keys.append("alpha")
    if present & {"T_g", "w_g", "a_g_g", "pulse", "Pi_delta", "record", "w0_over_wg"}:
        keys.append("ag")
    if "w0_over_wg" in present:
        keys.append("w0")
    if "T_g" in present:
        keys.append("Tg")
    if "Pi_delta" in present:
        keys.append("Pi")
    if present & {"eps_N", "mu", "xi"}:
        keys.append("eps")
    if "eta0" in present:
        keys.append("eta0")
    if "k_factor" in present:
        keys.append("k")
    if layout.sample:
        keys.append("records")
    return keys


def _figure(n_rows, n_cols, legend_cols):
    """The figure of a grid of panels, sized and placed by _place when it is finished (a fixed
    layout: the margins are known in inches, so no layout engine measures every tick label)."""
    width = PANEL_IN[0] * n_cols + 1.9 + 0.2 * legend_cols
    height = PANEL_IN[1] * n_rows + 1.4
    return plt.subplots(n_rows, n_cols, figsize=(width, height), squeeze=False, sharex=True)


# The fixed layout of a grid of panels, in inches: the left margin (a y label of two lines and
# its tick labels), the gap between columns (tick labels; a y label too where every column has
# one), between rows (x tick labels and label where a panel above another has them), above the
# panels (the title; panel titles) and under them (x tick labels and label), the pad beside
# the legend.
LEFT_IN, COLUMN_GAP_IN, COLUMN_GAP_LABELLED_IN = 1.0, 0.62, 1.05
ROW_GAP_IN, ROW_GAP_LABELLED_IN = 0.22, 0.62
TOP_IN, TOP_TITLED_IN, BOTTOM_IN, RIGHT_PAD_IN, TITLE_IN = 0.4, 0.62, 0.62, 0.2, 0.25


def _place(fig, axes, legend_artist, room_above=0.0, colorbar=False):
    """Sizes the figure and places the panels of `axes` (rows x columns, removed ones left out)
    at PANEL_IN each with the fixed margins, the legend beside them (its width measured), and
    returns the figure's width in inches. `room_above`: inches for a legend over the panels."""
    grid = np.asarray(axes)
    n_rows, n_cols = grid.shape
    shown = [[ax in fig.axes for ax in row] for row in grid]
    labelled_columns = any(grid[r][c].get_ylabel() for r in range(n_rows)
                           for c in range(1, n_cols) if shown[r][c])
    labelled_rows = any(grid[r][c].get_xlabel() for r in range(n_rows - 1)
                        for c in range(n_cols) if shown[r][c])
    titled = any(grid[0][c].get_title() for c in range(n_cols) if shown[0][c])
    titled_below = any(grid[r][c].get_title() for r in range(1, n_rows)
                       for c in range(n_cols) if shown[r][c])
    col_gap = COLUMN_GAP_LABELLED_IN if labelled_columns else COLUMN_GAP_IN
    row_gap = ROW_GAP_LABELLED_IN if labelled_rows else ROW_GAP_IN
    if titled_below:  # a panel title over each row: its line besides
        row_gap += TITLE_IN
    panel_w, panel_h = PANEL_IN[0] - COLUMN_GAP_IN, PANEL_IN[1] - ROW_GAP_IN
    right = RIGHT_PAD_IN
    if colorbar:
        right += 1.2
    elif legend_artist is not None:
        renderer = fig.canvas.get_renderer()
        right += legend_artist.get_window_extent(renderer).width / fig.dpi + 0.1
    top = (TOP_TITLED_IN if titled else TOP_IN) + room_above
    width = LEFT_IN + n_cols * panel_w + (n_cols - 1) * col_gap + right
    height = top + n_rows * panel_h + (n_rows - 1) * row_gap + BOTTOM_IN
    fig.set_size_inches(width, height)
    fig.subplots_adjust(left=LEFT_IN / width, right=1 - right / width,
                        bottom=BOTTOM_IN / height, top=1 - top / height,
                        wspace=col_gap / panel_w, hspace=row_gap / panel_h)
    return width


def _draw(ax, sweep, layout, values, styles, legend):
    xs = np.asarray(sweep.axes[layout.x], dtype=float)
    if layout.sample:
        for row in values:
            ax.plot(xs, row, color="0.65", lw=0.7)
        finite = np.isfinite(values).sum(axis=0) > 0
        if np.any(finite):
            with np.errstate(all="ignore"):
                med = np.nanmedian(values[:, finite], axis=0)
                lo, hi = np.nanpercentile(values[:, finite], [16, 84], axis=0)
            band = ax.fill_between(xs[finite], lo, hi, color="C0", alpha=0.25, lw=0)
            line, = ax.plot(xs[finite], med, color="C0", lw=2.0, marker="o", ms=4)
            legend.setdefault("median of the records", line)
            legend.setdefault("16-84 % of the records", band)
            legend.setdefault("one record", matplotlib.lines.Line2D([], [], color="0.65",
                                                                     lw=0.7))
        return
    curves = list(sweep.axes[layout.curve]) if layout.curve else [None]
    many = len(curves) > common.MAX_LEGEND
    for ic, value in enumerate(curves):
        color, marker, ls = styles[ic]
        if many:
            ax.plot(xs, values[ic], color=color, lw=1.0)
        else:
            h, = ax.plot(xs, values[ic], color=color, ls=ls, marker=marker, ms=4,
                         markevery=max(1, len(xs) // 8))
            if value is not None:
                legend.setdefault(value_label(sweep, layout.curve, value), h)


def _x_scale(ax, sweep, key):
    xs = np.asarray(sweep.axes[key], dtype=float)
    spacing = sweep.axis_attrs.get(key, {}).get("spacing", "")
    if spacing == "logspace" or (np.all(xs > 0) and xs.max() / xs.min() >= 20):
        common.log_axis(ax, "x")


def _finish(fig, axes, sweep, layout, legend, title, extra_caption="", qs=()):
    """The legend (or colour bar) beside the panels, the title and the caption; sizes the
    figure and places the panels (_place), the caption's lines added under them, before a
    colour bar takes its share of the panels' room."""
    curves = list(sweep.axes[layout.curve]) if layout.curve and not layout.sample else []
    shown = np.array([ax for ax in np.ravel(axes) if ax in fig.axes], dtype=object)
    many = len(curves) > common.MAX_LEGEND
    artist = None
    if legend and not many:
        artist = np.asarray(axes)[0, -1].legend(list(legend.values()), list(legend.keys()),
                                                loc="upper left", bbox_to_anchor=(1.02, 1.0),
                                                borderaxespad=0.0)
    _place(fig, axes, artist, room_above=0.35 if many and legend else 0.0, colorbar=many)
    _grow_bottom(fig, common.caption(fig, _caption_keys(sweep, layout, qs), extra_caption))
    if many:
        common.curve_key_legend(fig, shown, layout.curve, curves)
        fig.axes[-1].set_ylabel(axis_label(sweep, layout.curve))
        if legend:  # reference lines and sample entries still need their legend
            shown[0].legend(list(legend.values()), list(legend.keys()), loc="lower left",
                            bbox_to_anchor=(0.0, 1.08), ncol=len(legend), frameon=False)
    fixed = f" ({layout.fixed_text})" if layout.fixed_text else ""
    fig.suptitle(f"{sweep.name}: {title}{fixed}", fontsize=10, y=1 - 0.08 / fig.get_figheight())


def _grow_bottom(fig, inches):
    """Adds `inches` under the panels (the caption's band) keeping every panel's size and
    place relative to the top."""
    if inches <= 0:
        return
    width, height = fig.get_size_inches()
    params = fig.subplotpars
    top_in, bottom_in = (1 - params.top) * height, params.bottom * height
    new_h = height + inches
    fig.set_size_inches(width, new_h)
    fig.subplots_adjust(top=1 - top_in / new_h, bottom=(bottom_in + inches) / new_h)
    for text in fig.texts:  # the caption, anchored at the bottom
        x, y = text.get_position()
        text.set_position((x, y * height / new_h))


def display_scale(sweep, q):
    """(factor, unit) to draw a quantity in, the same in every panel: mm and mrad when all its
    values over the sweep are below 0.1 (m or rad), µm and µrad below 1e-4, so that the ticks
    carry no power of ten; SI otherwise."""
    values = np.concatenate([np.ravel(sweep.responses[n]) for n in q.names])
    finite = np.abs(values[np.isfinite(values)])
    largest = finite.max() if len(finite) else 1.0
    for below, factor, prefix in ((1e-4, 1e6, "µ"), (0.1, 1e3, "m")):
        if q.unit in ("m", "rad") and largest < below:
            return factor, prefix + q.unit
    return 1.0, None


def _panel_grid(n_quantities, n_columns):
    """(rows, cols, place) of the panels: a row per quantity and a column per combination, or,
    with one combination, the quantities wrapped into two or three columns."""
    if n_columns > 1:
        return n_quantities, n_columns, lambda row, col: (row, col)
    cols = 1 if n_quantities == 1 else (2 if n_quantities <= 4 else 3)
    rows = int(np.ceil(n_quantities / cols))
    return rows, cols, lambda row, col: (row // cols, row % cols)


def response_vs_axis(sweep, layout, qs, out_dir, name, pdf):
    """The quantities qs against layout.x: with several column combinations a row per quantity
    and a column per combination, else the quantities wrapped into a grid. Returns table rows
    (quantity text, column, curve value, peak, x at peak, at the grid edge, no response)."""
    n_rows, n_cols, place = _panel_grid(len(qs), len(layout.columns))
    fig, axes = _figure(n_rows, n_cols, 1)
    curves = list(sweep.axes[layout.curve]) if layout.curve and not layout.sample else [None]
    styles = common.curve_styles(len(curves))
    legend, table = {}, []
    xs = np.asarray(sweep.axes[layout.x], dtype=float)
    used = set()
    for col, combo in enumerate(layout.columns):
        for row, q in enumerate(qs):
            r, c = place(row, col)
            used.add((r, c))
            ax = axes[r][c]
            values, deck = _series(sweep, q, layout, combo)
            factor, unit = display_scale(sweep, q)
            _draw(ax, sweep, layout, values * factor, styles, legend)
            if not np.any(np.isfinite(values)):
                common.no_data(ax)
            elif not np.any(values[np.isfinite(values)]):
                common.no_data(ax, f"no response: 0 everywhere (below {ZERO:g})", y=0.6)
            _x_scale(ax, sweep, layout.x)
            if q.base == "impacts":
                common.integer_axis(ax)
            if c == 0 or n_cols == 1 or len(layout.columns) == 1:
                ax.set_ylabel(quantity_label(q, unit) + _deck_note(q))
            if r == 0 and combo:
                ax.set_title(_combo_title(sweep, combo), fontsize=9.5)
            if not layout.sample:
                for ic, value in enumerate(curves):
                    peak, at, _, edge, zero = common.peak_of(values[ic], xs)
                    table.append((quantity_text(q, deck if len(q.decks) > 1 else None),
                                  _combo_title(sweep, combo), value, peak, at, edge, zero))
    for r in range(n_rows):
        for c in range(n_cols):
            if (r, c) not in used:
                axes[r][c].remove()
            elif (r + 1, c) not in used:
                axes[r][c].set_xlabel(axis_label(sweep, layout.x))
                axes[r][c].xaxis.set_tick_params(labelbottom=True)
    _finish(fig, axes, sweep, layout, legend, f"responses against {axis_symbol(layout.x, sweep)}",
            qs=qs)
    return common.save(fig, out_dir, name, pdf), table


def _deck_note(q):
    """What a y label adds for a quantity of several decks: that its worst deck is drawn."""
    if len(q.decks) < 2:
        return ""
    return ",\nsmallest of the decks" if q.base in MARGINS else ",\nworst deck"


def unseating_margins(sweep, layout, q, out_dir, name, pdf):
    """The unseating margin of each deck against layout.x (a panel per column combination),
    with the line of zero margin and the unseated side (margin < 0) shaded."""
    n = len(layout.columns)
    n_cols = min(n, 2) if n > 1 else 1
    n_rows = int(np.ceil(n / n_cols))
    fig, axes = _figure(n_rows, n_cols, 1)
    curves = list(sweep.axes[layout.curve]) if layout.curve and not layout.sample else [None]
    styles = common.curve_styles(len(curves))
    legend = {}
    for k, combo in enumerate(layout.columns):
        ax = axes[k // n_cols][k % n_cols]
        values, _ = _series(sweep, q, layout, combo)
        factor, unit = display_scale(sweep, q)
        values = values * factor
        _draw(ax, sweep, layout, values, styles, legend)
        ax.axhline(0.0, color="C3", lw=1.1, ls=(0, (4, 3)))
        finite = values[np.isfinite(values)]
        if len(finite):
            lo = min(finite.min(), 0.0)
            span = max(finite.max(), 0.0) - lo
            ax.set_ylim(lo - 0.08 * span - ZERO, max(finite.max(), 0.0) + 0.08 * span + ZERO)
            ax.axhspan(ax.get_ylim()[0], 0.0, color="C3", alpha=0.08, lw=0)
        else:
            common.no_data(ax)
        _x_scale(ax, sweep, layout.x)
        if combo:
            ax.set_title(_combo_title(sweep, combo), fontsize=9.5)
        ax.set_ylabel(quantity_label(q, unit) + _deck_note(q))
        ax.set_xlabel(axis_label(sweep, layout.x))
        ax.xaxis.set_tick_params(labelbottom=True)
    for k in range(n, n_rows * n_cols):
        axes[k // n_cols][k % n_cols].remove()
    legend["margin = 0: a corner leaves its seat\n(shaded: unseated)"] = matplotlib.lines.Line2D(
        [], [], color="C3", lw=1.1, ls=(0, (4, 3)))
    _finish(fig, axes, sweep, layout, legend, f"unseating margins against "
            f"{axis_symbol(layout.x, sweep)}", qs=[q], extra_caption="Unseating margin: seat width minus the largest travel "
            "of a corner normal to the deck's end line; below 0 the corner has left its seat.")
    return common.save(fig, out_dir, name, pdf), []


# Axis symbols in plain Unicode for the Markdown tables, beyond common.AXIS_TEXT.
AXIS_PLAIN = {"T_g": "T_g", "w_g": "ω_g", "k_factor": "K factor", "scale": "scale",
              "gap_m": "δ", "a_g_g": "a_g", "record": "record", "method": "method",
              "seat_over_L": "seat/L", "seat_m": "seat"}


def value_text(sweep, key, value):
    """`α = 30°`, `T_g = 0.5 s`, `pulse: cosine` in plain text."""
    symbol = common.AXIS_TEXT.get(key) or AXIS_PLAIN.get(key, key)
    if isinstance(value, str):
        return f"{symbol}: {value}"
    unit = axis_unit(sweep, key)
    sep = "" if unit == "°" else " "
    text = common.number_text(value, sweep.axes.get(key, [value]))
    return f"{symbol} = {text}" + (f"{sep}{unit}" if unit else "")


def cell_text(sweep, flat_index):
    """The coordinates of a cell along its axes of two or more values, in plain text."""
    idx = np.unravel_index(flat_index, sweep.shape())
    return ", ".join(value_text(sweep, k, sweep.axes[k][i])
                     for k, i in zip(sweep.axis_order, idx) if len(sweep.axes[k]) > 1)


def infinite_text(v):
    """A value of the responses table: +-inf as the text "inf" / "-inf" (a value: the event never
    came), anything else as it is."""
    return ("inf" if v > 0 else "-inf") if np.isinf(v) else v


def response_table(sweep):
    """Rows (response, unit, cells with a value, min, median, max, cell of the max) of every
    response of the cube, descriptors included; the per-run responses of an IDA search
    (ida_..._NN, shown by the IDA curves) are left out. NaN is no value (a failed cell, a
    response the cell does not have); +inf is one (a shear key that never broke,
    key_break_time_*; fewer than two impacts, min_impact_separation): counted, and shown as
    "inf" in min, median and max."""
    rows = []
    for name in sweep.responses:
        if IDA_RUN.match(name):
            continue
        values = np.asarray(sweep.responses[name], dtype=float)
        valued = ~np.isnan(values)
        unit = unit_text(str(sweep.response_attrs.get(name, {}).get("units", ""))) or "1"
        if not np.any(valued):
            rows.append((name, unit, 0, None, None, None, "–"))
            continue
        k = int(np.argmax(np.where(valued, values, -np.inf)))
        with np.errstate(invalid="ignore"):
            median = float(np.median(values[valued]))
        rows.append((name, unit, int(valued.sum()), infinite_text(float(values[valued].min())),
                     infinite_text(median), infinite_text(float(values.flat[k])),
                     cell_text(sweep, k) or "the single cell"))
    return rows


def unseating_table(sweep, q):
    """Rows (deck, cells, cells unseated, share, smallest margin, cell of the smallest)."""
    rows = []
    for deck, name in zip(q.decks, q.names):
        values = np.asarray(sweep.responses[name], dtype=float)
        finite = np.isfinite(values)
        if not np.any(finite):
            rows.append((deck, 0, 0, None, None, "–"))
            continue
        k = int(np.argmin(np.where(finite, values, np.inf)))
        unseated = int(np.count_nonzero(values[finite] < 0))
        rows.append((deck if deck is not None else "–", int(finite.sum()), unseated,
                     f"{unseated / finite.sum():.0%}", float(values.flat[k]),
                     cell_text(sweep, k) or "the single cell"))
    return rows


RECORD_COLUMNS = [("label", "record", None), ("component", "component", None),
                  ("scale", "scale", None), ("pga_mps2", "PGA [m/s²]", None),
                  ("pgv_mps", "PGV [m/s]", None), ("pgd_m", "PGD [m]", None),
                  ("T_m_s", "T_m [s]", None), ("L_e_m", "L_e [m]", None),
                  ("arias_mps", "Arias [m/s]", None), ("D5_95_s", "D5-95 [s]", None),
                  ("w_g_radps", "ω_g [rad/s]", None), ("dt_s", "dt [s]", None),
                  ("npts", "samples", None)]


def record_table(sweep):
    """(header, rows) of the cube's record table (records/), columns it lacks left out; None
    when the sweep has none."""
    rec = sweep.extra.get("records")
    if not rec:
        return None
    cols = [(key, title) for key, title, _ in RECORD_COLUMNS if key in rec]
    extra = [k for k in rec if k != "attrs" and not k.endswith("@attrs")
             and not isinstance(rec[k], dict) and k not in dict(cols)]
    for k in extra:  # columns other programs add (measures): titled with their units
        if np.ndim(rec[k]) == 1 and k != "file":
            unit = rec.get(k + "@attrs", {}).get("units", "")
            unit = unit.decode() if isinstance(unit, bytes) else str(unit)
            cols.append((k, k + (f" [{unit_text(unit)}]" if unit_text(unit) else "")))
    if "file" in rec:
        cols.append(("file", "file"))
    n = len(rec[cols[0][0]])
    rows = []
    for i in range(n):
        row = []
        for key, _ in cols:
            v = rec[key][i]
            row.append(v.decode() if isinstance(v, bytes) else v)
        rows.append(row)
    return [title for _, title in cols], rows
