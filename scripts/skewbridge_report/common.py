"""What the report's modules share, so that every figure of a report looks alike and every
symbol is spelled and defined once: the figure style and `save`, which writes each figure; the
symbols of docs/theory.md in mathtext and in plain Unicode with their caption definitions; log
axes with plain tick labels, integer axes of counts, "no data" panels, curve styles (sequential
for a curve parameter, categorical for combinations), legends beside the panels or a colour
bar; `select`, a response over some axes of a sweep with the others held at an index; the
combinations of the axes of a fit and the texts of limit states and intensity measures.

Figures are drawn as a journal prints them: fonts at least 9 pt at 100 dpi (12.5 px), a fixed
pixel size (no tight bounding box, so the size is known in advance), the symbols in mathtext
with their units, log axes with plain tick labels at 1, 2 and 5 of each decade, curves told
apart by marker and line style as well as colour, legends outside the data (more than
MAX_LEGEND curves become a colour bar), reference lines labelled, integer ticks on counts,
"no data" on an empty panel, and a caption under each figure defining every symbol it uses."""
import math
import os
import re
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402

from .data import tree_attrs  # noqa: E402

DPI = 100

# More curves than this in one panel are told apart by a colour bar, not a legend.
MAX_LEGEND = 10
# A value below this in magnitude is printed as 0 in the tables and counts as no response: the
# normalised maxima are of order 0.01-10, so 1e-9 is far below any physical response and far
# above the round-off (about 1e-18 rad) of a deck that does not turn.
ZERO = 1e-9

plt.rcParams.update({"font.size": 10, "axes.labelsize": 11, "axes.titlesize": 11,
                     "legend.fontsize": 9, "xtick.labelsize": 9.5, "ytick.labelsize": 9.5,
                     "figure.dpi": DPI, "savefig.dpi": DPI, "lines.linewidth": 1.4,
                     "axes.grid": True, "grid.alpha": 0.3})

RESPONSE_LABEL = {
    "x_norm": r"$x_m\,\omega_g^2/a_g$",
    "y_norm": r"$y_m\,\omega_g^2/a_g$",
    "theta_norm": r"$\theta_m\,\rho\,\omega_g^2/a_g$",
    "theta_m": r"$\theta_m$ [rad]",
    "y_m": r"$y_m$ [m]",
    "L_e": r"$L_e = a_g/\omega_g^2$ [m]",
    "impacts": "impacts",
}
# The same quantities in plain Unicode, for the Markdown tables.
RESPONSE_TEXT = {"x_norm": "x_m ω_g²/a_g", "y_norm": "y_m ω_g²/a_g",
                 "theta_norm": "θ_m ρ ω_g²/a_g", "theta_m": "θ_m [rad]", "y_m": "y_m [m]",
                 "L_e": "L_e [m]"}
AXIS_LABEL = {
    "w0_over_wg": r"$\omega_0/\omega_g$",
    "a_deg": r"$\alpha$",
    "Pi_delta": r"$\Pi_\delta$",
    "eta0": r"$\eta_0$",
    "W0_over_w0": r"$\Omega_0/\omega_0$",
    "mu": r"$\mu$",
    "eps_N": r"$\varepsilon_N$",
    "xi": r"$\xi$",
    "delta_over_L": r"$\delta/L$",
    "W_over_L": r"$W/L$",
}
AXIS_TEXT = {"w0_over_wg": "ω_0/ω_g", "a_deg": "α", "Pi_delta": "Π_δ", "eta0": "η_0",
             "W0_over_w0": "Ω_0/ω_0", "mu": "μ", "eps_N": "ε_N", "xi": "ξ",
             "delta_over_L": "δ/L", "W_over_L": "W/L", "pulse": "pulse"}
AXIS_UNIT = {"a_deg": "°"}

# One line per symbol; each figure's caption and the summary's symbol list take theirs from here.
SYMBOLS = {
    "x": "x_m, y_m, θ_m: largest |x|, |y| (m) and |θ| (rad) of the deck over the run",
    "rho": "ρ: radius of gyration of the deck (I_m = m ρ²)",
    "ag": "a_g, ω_g: amplitude (m/s²) and circular frequency (rad/s) of the pulse; for a record "
          "PGA and 2π/T_m",
    "w0": "ω_0: frequency of the substructure along x and y; Ω_0: its torsional frequency",
    "w0x": "ω_0x: the pilot bridge's frequency along x",
    "eta0": "η_0 = sin 2α / (2W/L): skew ratio (the deck rotates after a full-edge impact iff "
            "η_0 > 1)",
    "alpha": "α: skew angle",
    "Pi": "Π_δ = δ ω_g²/a_g: joint gap δ in units of the persistency a_g/ω_g²",
    "Le": "L_e = a_g/ω_g²: persistency of the record (m)",
    "eps": "ε_N: coefficient of restitution; μ: friction coefficient; ξ: damping ratio",
    "gap": "g_N: normal gap of a corner (mm); γ_T: its tangential velocity (m/s)",
    "end": "x_end, y_end, θ_end: residual displacements (m) and rotation (rad) at the end of "
           "the run",
    "decks": "worst deck: per-deck responses drawn as their envelope over the decks (the "
             "largest maximum, the residual of largest magnitude, the smallest margin); "
             "summary.md lists every deck",
    "Tg": "T_g = 2π/ω_g: period of the pulse (s)",
    "travel": "corner travel: the largest travel of a deck corner normal to the end line, the "
              "demand on its seat",
    "k": "K factor: multiplier on the substructure's stiffness K",
    "records": "thin grey lines: one record each; thick line: the median over the records; "
               "band: 16-84 % of the records at each abscissa",
}


def caption(fig, keys, extra=""):
    """A caption under the figure defining the symbols in `keys`; the layout leaves room for it
    (constrained layout's rect), so that it never overlaps an axis label. Returns the height of
    its band in inches (a figure without a layout engine makes that room itself)."""
    return caption_text(fig, "; ".join(SYMBOLS[k] for k in keys) + "."
                        + (" " + extra if extra else ""))


def caption_text(fig, text):
    """The caption `text` under the figure, wrapped to its width; the constrained layout leaves
    room for it (its rect), so that it never overlaps an axis label. Returns the height of its
    band in inches."""
    width_px = fig.get_figwidth() * DPI
    lines = textwrap.wrap(text, int(width_px / 6.2))  # 8 pt DejaVu Sans: up to 5.9 px a glyph
    fig.text(0.005, 0.004, "\n".join(lines), fontsize=8, va="bottom", ha="left", color="0.2")
    band_in = (len(lines) * 8 * 1.25 + 6) / 72.0
    if fig.get_layout_engine() is not None:
        bottom = band_in / fig.get_figheight()
        fig.get_layout_engine().set(rect=(0, bottom, 1, 1 - bottom))
    return band_in


def finish_panels(fig, axes, n_used, text):
    """The end of a figure of panels in a grid (fragility, cloud, IDA): the panels past the first
    n_used hidden, the legend of the first panel's labelled curves beside the grid (none when it
    has none) and the caption `text` under it."""
    flat = np.ravel(axes)
    for ax in flat[n_used:]:
        ax.set_visible(False)
    curve_key_legend(fig, axes, None, [], *flat[0].get_legend_handles_labels())
    caption_text(fig, text)


class _PlainLogLocator(matplotlib.ticker.Locator):
    """Ticks of a log axis at 1, 2 and 5 of each decade, with 3, 4 and 7 (then every digit)
    added when the range holds fewer than three of those, and evenly spaced values on a range
    narrower still, so that every axis has three or more labels."""

    def __call__(self):
        lo, hi = self.axis.get_view_interval()
        return self.tick_values(lo, hi)

    def tick_values(self, vmin, vmax):
        lo, hi = sorted((max(vmin, 1e-300), max(vmax, 1e-300)))
        for mantissas in ((1, 2, 5), (1, 2, 3, 4, 5, 7), (1, 1.5, 2, 3, 4, 5, 6, 7, 8, 9)):
            ticks = [m * 10.0 ** e for e in range(int(np.floor(np.log10(lo))) - 1,
                                                    int(np.ceil(np.log10(hi))) + 1)
                     for m in mantissas]
            ticks = [t for t in ticks if lo * (1 - 1e-9) <= t <= hi * (1 + 1e-9)]
            if len(ticks) >= 3:
                break
        else:  # under a factor of about 1.5: evenly spaced plain numbers
            ticks = [t for t in matplotlib.ticker.MaxNLocator(4).tick_values(lo, hi)
                     if lo * (1 - 1e-9) <= t <= hi * (1 + 1e-9) and t > 0]
        if hi > 1000 * lo or len(ticks) > 12:  # three decades or more: decades only
            ticks = [t for t in ticks if abs(np.log10(t) - round(np.log10(t))) < 1e-9]
        return np.array(ticks)


class _PlainLogFormatter(matplotlib.ticker.Formatter):
    """Plain numbers (0.2, 0.5, 1, 2) on a log axis spanning under three decades; powers of ten
    (10^-4) on a wider one, whose ticks are then decades only."""

    def __call__(self, value, pos=None):
        lo, hi = sorted(self.axis.get_view_interval())
        exponent = int(np.floor(np.log10(value) + 1e-9))
        mantissa = round(value / 10.0 ** exponent, 6)
        if hi > 1000 * max(lo, 1e-300) or not 1e-3 <= value < 1e5:
            return (f"$10^{{{exponent}}}$" if mantissa == 1
                    else f"${mantissa:g}\\times 10^{{{exponent}}}$")
        return f"{value:g}"


def log_axis(ax, which="x"):
    """A log axis with three or more labelled ticks, never a lone 10^0 on a range under two
    decades (_PlainLogLocator, _PlainLogFormatter)."""
    axis = ax.xaxis if which == "x" else ax.yaxis
    (ax.set_xscale if which == "x" else ax.set_yscale)("log")
    axis.set_major_locator(_PlainLogLocator())
    axis.set_major_formatter(_PlainLogFormatter())
    axis.set_minor_formatter(matplotlib.ticker.NullFormatter())


def no_data(ax, text="no data", y=0.5):
    """Say so on a panel with nothing to draw (y: height of the note in axes units)."""
    ax.text(0.5, y, text, transform=ax.transAxes, ha="center", va="center", fontsize=12,
            color="0.4")
    if not ax.lines:  # nothing drawn: the tick labels of an empty range would mean nothing
        ax.set_yticks([])


def integer_axis(ax):
    """Integer ticks on a y axis of counts, half a count of margin around the drawn values (so
    that a constant count still gets one integer tick rather than fractional ones)."""
    values = np.concatenate([np.asarray(line.get_ydata(), dtype=float) for line in ax.lines]
                            or [np.array([])])
    values = values[np.isfinite(values)]
    if len(values):
        ax.set_ylim(values.min() - 0.5, values.max() + 0.5)
    ax.yaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True, min_n_ticks=1))


MARKERS = ["o", "s", "^", "v", "D", "P", "X", "*", "<", ">"]
LINESTYLES = ["-", "--", "-.", ":"]


def curve_styles(n, cmap="viridis"):
    """n (colour, marker, linestyle) triples: colour from a sequential map, marker and line style
    cycling so that curves stay distinct in grey print."""
    colors = plt.get_cmap(cmap)(np.linspace(0.0, 0.9, max(n, 1)))
    return [(colors[i], MARKERS[i % len(MARKERS)], LINESTYLES[i % len(LINESTYLES)])
            for i in range(n)]


def category_styles(n):
    """(colour, marker, line style) per combination: combinations are categories, so the colours
    are tab10's in order, with markers and line styles for grey print."""
    return [(plt.get_cmap("tab10")(i % 10), MARKERS[i % len(MARKERS)],
             LINESTYLES[i % len(LINESTYLES)]) for i in range(n)]


def panel_grid(n):
    """(rows, columns) of a grid of n panels, at most 3 a row."""
    cols = min(n, 3)
    rows = int(math.ceil(n / cols))
    return rows, cols


def curve_key_legend(fig, axes, curve_key, values, handles=None, labels=None, cmap="viridis"):
    """The legend of the curves beside the panels, or a colour bar when there are more than
    MAX_LEGEND of them; `handles`/`labels` add entries (reference lines) to the legend."""
    handles, labels = list(handles or []), list(labels or [])
    axes_flat = np.ravel(axes)
    if curve_key and len(values) > MAX_LEGEND:
        finite = np.asarray(values, dtype=float)
        norm = matplotlib.colors.Normalize(vmin=finite.min(), vmax=finite.max() / 0.9
                                           if finite.max() > 0 else finite.max())
        mappable = matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap)
        label = AXIS_LABEL.get(curve_key, curve_key)
        fig.colorbar(mappable, ax=list(axes_flat), label=label + (
            f" [{AXIS_UNIT[curve_key]}]" if curve_key in AXIS_UNIT else ""), shrink=0.6)
        if handles:
            axes_flat[0].legend(handles, labels, loc="upper left", bbox_to_anchor=(0.0, 1.22),
                                ncol=len(handles), frameon=False)
        return
    if curve_key:
        h, lab = axes_flat[0].get_legend_handles_labels()
        handles, labels = h + handles, lab + labels
    if handles:
        # Beside the top-right panel, outside every data area; constrained layout makes room.
        anchor = np.asarray(axes)[0, -1] if np.ndim(axes) == 2 else axes_flat[-1]
        anchor.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.02, 1.0),
                      borderaxespad=0.0)

def select(sweep, response, keep, at=None):
    """The response over the axes in `keep` (in that order), other axes at index at[key] or 0."""
    return select_array(sweep, sweep.responses[response], keep, at)


def select_array(sweep, values, keep, at=None):
    """select() for any array shaped like the sweep's cells."""
    at = at or {}
    order = list(sweep.axis_order)
    for key in list(order):
        if key not in keep:
            values = np.take(values, at.get(key, 0), axis=order.index(key))
            order.remove(key)
    return np.transpose(values, [order.index(k) for k in keep])


def save(fig, out_dir, name, pdf):
    """Writes `fig` as out_dir/NAME.png at DPI (and NAME.pdf with pdf=True), closes it and
    returns the PNG's path."""
    path = os.path.join(out_dir, name + ".png")
    fig.savefig(path, dpi=DPI)
    if pdf:
        fig.savefig(os.path.join(out_dir, name + ".pdf"))
    plt.close(fig)
    return path


def peak_of(values, grid):
    """(peak, abscissa at the peak, index, at the grid edge, no response) of one curve; NaN
    peak when the curve has no finite value. A curve whose largest value is below ZERO has
    no response: its arg-max is round-off and is not reported."""
    finite = np.isfinite(values)
    if not np.any(finite):
        return float("nan"), float("nan"), -1, False, False
    k = int(np.nanargmax(values))
    peak = float(values[k])
    if abs(peak) < ZERO:
        return 0.0, float("nan"), -1, False, True
    return peak, float(grid[k]), k, k in (0, len(grid) - 1), False



# Units as printed in brackets, where they differ from the cube's spelling.
UNIT_TEXT = {"deg": "°", "rad/s": "rad/s", "m/s^2": "m/s²"}


def unit_text(unit):
    """A unit as printed in brackets, '' for dimensionless."""
    if unit in ("", "1", "-", None):
        return ""
    return UNIT_TEXT.get(unit, unit)


# ---- limit states and intensity measures (fragility and IDA figures) -------------------------

MAX_COMBOS = 8  # curves per panel; more combinations are listed in the table only
IM_TEXT = {"im_g": "IM: the stripe im_g", "im_mps": "IM: the stripe im_mps",
           "im": "IM of the record",
           "a_g": r"IM = $a_g/g$ (PGA × scale)"}


def number_text(value, values):
    """A value of an axis with the fewest significant digits (2 to 6) that still tell every
    value of the axis apart: 0.00857143 among 0.004, 0.00857143 and 0.0171 is `0.0086`."""
    numbers = [float(v) for v in values if not isinstance(v, str)]
    for digits in range(2, 7):
        texts = {f"{v:.{digits}g}" for v in numbers}
        if len(texts) == len(set(numbers)):
            return f"{float(value):.{digits}g}"
    return f"{float(value):.6g}"


# Axis names in the legends of the fits' combinations, beyond AXIS_TEXT (plain Unicode).
COMBINATION_TEXT = {"seat_over_L": "seat/L", "seat_m": "seat"}


def value_with_unit(sweep, key, value):
    """`α = 20°`, `seat/L = 0.0086`, `δ = 0.03 m`: a value of an axis in plain Unicode with the
    digits that tell the axis's values apart (number_text) and the cube's unit of the axis."""
    if isinstance(value, str):
        return f"{AXIS_TEXT.get(key, key)}: {value}"
    unit = AXIS_UNIT.get(key) or unit_text(sweep.axis_attrs.get(key, {}).get("units", ""))
    sep = "" if unit in ("", "°") else " "
    name = AXIS_TEXT.get(key) or COMBINATION_TEXT.get(key, key)
    return f"{name} = {number_text(value, sweep.axes[key])}{sep}{unit}"


def combinations(sweep, order):
    """(flat index, multi-index, label) of every combination of the axes `order` of a fit."""
    shape = [len(sweep.axes[k]) for k in order]
    out = []
    for flat, idx in enumerate(np.ndindex(*shape) if shape else [()]):
        label = ", ".join(value_with_unit(sweep, k, sweep.axes[k][i])
                          for k, i in zip(order, idx))
        out.append((flat, idx, label or "all cells"))
    return out


def shown_text(n_shown, n_combos):
    """The caption's sentence saying which combinations a figure draws when not all ("" when
    it draws all of them)."""
    if n_shown >= n_combos:
        return ""
    return (f" Only the first {n_shown} of {n_combos} combinations are drawn; the table lists "
            "all.")


def limit_state_text(name, group):
    """The title of a limit state's panel: what exceeding it means, from the attributes of its
    fragility/<name> group (a tree of data.load_cube)."""
    a = tree_attrs(group)
    kind, thr = a.get("kind", ""), a.get("threshold", 0.0)
    units = a.get("demand_units", "")
    if kind == "unseating":
        return "unseating: corner travel over seat > 1"
    if kind == "joint_closing":
        return "joint closing: an impact"
    return f"{name}: demand > {thr:g} {units}"


def im_name(sweep):
    """The intensity measure by the name the cube stores (im_measure, and the period and damping
    of im_description): "Sa(T1, 5 %)", "AvgSa(0.5 s, 5 %)", "RotD50(T1, 5 %)", "PGA", "PGV"; ""
    when the sweep stores none."""
    measure = sweep.im_attrs.get("im_measure", "")
    m = re.match(r"\w+\((.+?), xi = ([0-9.eE+-]+)\)", sweep.im_attrs.get("im_description", ""))
    if measure not in ("", "PGA", "PGV") and m:
        return f"{measure}({m.group(1)}, {100.0 * float(m.group(2)):g} %)"
    return measure


def im_label(sweep, fa):
    """The IM axis label: the measure by its name where the IM is the record's measure (stripes
    of scale_to, im of a cloud, IDA capacities), else what the IM is; and its unit."""
    unit = fa.get("im_units", "g")
    name = im_name(sweep)
    if name and fa["im"] in ("im_g", "im_mps", "im", "ida_capacity"):
        return f"{name} [{unit}]"
    return f"{IM_TEXT.get(fa['im'], 'IM')} [{unit}]"
