"""What each sweep of a cube supports, decided from its axes, family and responses alone: the
report's planning (`scripts/report`). Pure: nothing here reads a file or draws, so a sweep built
in memory plans as a cube read from disk (tests/report/planning_test.py).

- plan(): the figures of the dimensionless study (spectra, the Π_δ family, rotation against
  η_0, the record correlations) with the curve axis of each, and those not made with why;
- plan_generic(): the generic figures of any sweep (each drawn quantity against each numeric
  axis, the unseating margins, the responses against each record's intensity), and those not
  made with why; drawn_quantities() says which responses they draw, drawn_against() which of
  them change along an axis; no page against an axis of the limit states alone
  (limit_state_axes) nor an axis of two values beside a longer one (two_point_axes);
- draws_generic(): whether a sweep gets the generic figures at all."""
import re
from dataclasses import dataclass

import numpy as np

# Responses that describe the cell's excitation, its geometry or the solver rather than the
# bridge's demand: listed in the table of responses, not drawn against the axes.
DESCRIPTORS = {"a_g", "w_g", "L_e", "delta", "L", "pga", "pgv", "pgd", "arias", "T_m", "D5_95",
               "w0x_over_wg", "band", "min_impact_separation"}
# The inputs of a cell scaled to an intensity ([records] scale_to or im): the fundamental period,
# the intensity as applied and as recorded, the factor and its flag. They set the excitation;
# drawn against the stripes they would only redraw the axis.
SCALING_INPUTS = {"T1", "im", "im_unscaled", "scale_factor", "scaled_too_far"}
# Axes that enter the limit states and the unseating margins alone: a seat width changes no
# motion of the bridge, only how much of its seat a corner has left. The response figures hold
# them at their first value; the fragility figures draw them.
LIMIT_STATE_AXES = ("seat_over_L", "seat_m")
# A normalised response and its dimensional twin: where the cube has both, the dimensional one
# (in metres and radians, as an engineer reads their own bridge) is drawn.
NORMALISED_TWIN = {"x_norm": "x_m", "y_norm": "y_m", "theta_norm": "theta_m",
                   "theta_end_norm": "theta_end", "margin_norm": "margin_m"}
# Residual displacements and the bound of the corner travel: in the table; the residual rotation
# is drawn.
TABLE_ONLY = {"x_end", "y_end", "travel_end_m", "travel_bound_m"}
# Times of an event that may never come (a shear key's break, key_break_time_px / _mx: +inf for
# keys left intact): a curve against an axis would drop the cells where it never came and read
# as if the event came in every cell it shows. In the table, with the cells where it never came
# counted; keys_broken is what is drawn.
EVENT_TIMES = re.compile(r"^key_break_time_(px|mx)$")
# Limit-state responses (ls_<name>, ls_<name>_demand): their demands repeat drawn responses and
# their exceedances are the fragility figures' business; they stay in the tables.
LIMIT_STATE_PREFIX = "ls_"
# IDA responses (ida_<...>, per run and per limit state): drawn by the IDA figures (ida.py).
IDA_PREFIX = "ida_"
MARGINS = ("margin_m", "margin_norm")
DECK = re.compile(r"^(.+)_d(\d+)$")

# Axes that are not curve parameters of a spectrum: the pulse is the column, w0/w_g the
# abscissa, a record axis a sample of the suite.
NON_CURVE_AXES = ("pulse", "w0_over_wg", "record")


def _curve_axes(sweep, exclude=()):
    return [k for k in sweep.axis_order
            if k not in NON_CURVE_AXES and k not in exclude and len(sweep.axes[k]) > 1]


def plan(sweep):
    """The figures a sweep supports as (kind, curve_key) and the ones it does not, as
    (kind, reason). Pure: decided from axes, family and responses alone."""
    todo, skipped = [], []
    resp = sweep.responses
    curves = _curve_axes(sweep)
    spectra_ok = all(r in resp for r in ("x_norm", "y_norm", "theta_norm"))
    if not sweep.has_axis("w0_over_wg", 2):
        skipped.append(("spectra", "no w0_over_wg axis with two or more values"))
    elif sweep.has_axis("record", 2):
        skipped.append(("spectra", "a record axis: one spectrum per record is not plotted"))
    elif not spectra_ok:
        skipped.append(("spectra", "the cube lacks x_norm, y_norm or theta_norm"))
    elif len(curves) > 1:
        skipped.append(("spectra", f"{len(curves)} curve axes ({', '.join(curves)}); a spectrum "
                        "figure takes one besides pulse and w0_over_wg"))
    else:
        key = curves[0] if curves else None
        todo.append(("pi_delta_family" if key == "Pi_delta" else "spectra", key))
    if not sweep.has_axis("eta0", 2):
        skipped.append(("rotation_vs_eta0", "no eta0 axis with two or more values"))
    elif "theta_norm" not in resp:
        skipped.append(("rotation_vs_eta0", "the cube lacks theta_norm"))
    else:
        others = _curve_axes(sweep, exclude=("eta0",))
        if len(others) > 1:
            skipped.append(("rotation_vs_eta0", f"{len(others)} curve axes besides eta0 "
                            f"({', '.join(others)}); the figure takes one"))
        else:
            todo.append(("rotation_vs_eta0", others[0] if others else None))
    if not sweep.has_axis("record", 2):
        skipped.append(("correlation", "no record axis with two or more records"))
    else:
        extra = [k for k in sweep.axis_order
                 if k not in ("record", "Pi_delta") and len(sweep.axes[k]) > 1]
        if extra:
            skipped.append(("correlation", f"axes besides record and Pi_delta: {', '.join(extra)}"))
        else:
            if all(r in resp for r in ("theta_m", "L_e")):
                todo.append(("correlation_theta_vs_Le", None))
            else:
                skipped.append(("correlation_theta_vs_Le", "the cube lacks theta_m or L_e"))
            if all(r in resp for r in ("theta_norm", "w0x_over_wg")):
                todo.append(("correlation_rotation_vs_w0x", None))
            else:
                skipped.append(("correlation_rotation_vs_w0x",
                                "the cube lacks theta_norm or w0x_over_wg"))
    return todo, skipped


# Families whose responses are the user's own bridge (metres, radians, margins per deck): the
# generic figures are drawn for them whatever else is.
GENERIC_FAMILIES = ("model-file", "multi-span")


@dataclass
class Quantity:
    """One response of the cube, or one response per deck (x_m_d0, x_m_d1, ...)."""

    base: str  # the response name without the deck suffix
    names: list  # dataset names, one per deck (or one)
    decks: list  # deck indices, or [None]
    unit: str
    description: str

    def dataset(self, deck):
        """The dataset name of one deck's response (deck None: the response of the one deck)."""
        return self.names[self.decks.index(deck)]


def quantities(sweep):
    """The cube's responses as quantities, in stored order, decks merged."""
    out = {}
    order = list(sweep.responses)
    for name in order:
        m = DECK.match(name)
        base, deck = (m.group(1), int(m.group(2))) if m else (name, None)
        attrs = sweep.response_attrs.get(name, {})
        q = out.setdefault(base, Quantity(base, [], [], str(attrs.get("units", "")),
                                          str(attrs.get("description", ""))))
        q.names.append(name)
        q.decks.append(deck)
    return list(out.values())


def drawn_quantities(sweep):
    """(drawn, margins): the quantities drawn against the axes, and the unseating margins (drawn
    by unseating_margins). A normalised response is drawn only when its dimensional twin is
    missing; theta_norm_max only without per-deck rotations; a break time (EVENT_TIMES) never."""
    qs = quantities(sweep)
    bases = {q.base for q in qs}
    drawn, margins = [], []
    for q in qs:
        if (q.base in DESCRIPTORS or q.base in SCALING_INPUTS or q.base in TABLE_ONLY
                or EVENT_TIMES.match(q.base) or q.base.startswith(LIMIT_STATE_PREFIX)
                or q.base.startswith(IDA_PREFIX)):
            continue
        if NORMALISED_TWIN.get(q.base) in bases:
            continue
        if q.base == "theta_norm_max" and bases & {"theta_m", "theta_norm"}:
            continue
        if q.base in MARGINS:
            margins.append(q)
            continue
        if not np.any(np.isfinite(np.concatenate(
                [np.ravel(sweep.responses[n]) for n in q.names]))):
            continue  # not computed in any cell (e.g. a response this family leaves NaN)
        drawn.append(q)
    return drawn, margins


def numeric_axes(sweep):
    """Axes with numbers and two or more values: the abscissas of the generic figures."""
    return [k for k in sweep.axis_order
            if sweep.has_axis(k, 2) and not isinstance(sweep.axes[k], list)]


def two_point_axes(sweep, xs):
    """The abscissas of xs with two values where another of xs (an axis of the limit states
    alone aside) has three or more: a line between two points says no more than the two columns
    (or curves) those values make in the pages against the longer axis, which draw every cell
    already."""
    longer = [k for k in xs if k not in LIMIT_STATE_AXES and len(sweep.axes[k]) >= 3]
    return [k for k in xs if len(sweep.axes[k]) == 2 and longer]


def limit_state_axes(sweep):
    """The sweep's axes of two or more values that enter the limit states alone
    (LIMIT_STATE_AXES): no response page is drawn against them or over them."""
    return [k for k in sweep.axis_order if k in LIMIT_STATE_AXES and sweep.has_axis(k, 2)]


# A response varies along an axis when, in some cell, its values along the axis differ by more
# than this fraction of its largest magnitude over the sweep (and by more than ZERO_RESPONSE):
# bit-identical repeats (a seat width) and round-off stay "equal".
VARY_RTOL = 1e-9
ZERO_RESPONSE = 1e-9


def varies_along(sweep, q, key):
    """Whether quantity q (any of its decks) takes different values along axis `key` in some
    combination of the other axes; NaN cells are left out."""
    axis = sweep.axis_order.index(key)
    for name in q.names:
        values = np.asarray(sweep.responses[name], dtype=float)
        finite = np.isfinite(values)
        if not np.any(finite):
            continue
        scale = max(float(np.max(np.abs(values[finite]))), ZERO_RESPONSE)
        with np.errstate(all="ignore"):
            hi = np.max(np.where(finite, values, -np.inf), axis=axis)
            lo = np.min(np.where(finite, values, np.inf), axis=axis)
        spread = np.where(np.isfinite(hi) & np.isfinite(lo), hi - lo, 0.0)
        if np.any(spread > max(VARY_RTOL * scale, ZERO_RESPONSE)):
            return True
    return False


def drawn_against(sweep, key, qs):
    """(varying, equal): the quantities of qs that vary along axis `key` (drawn against it) and
    those equal at every value of it in every cell (left out, stated once)."""
    varying, equal = [], []
    for q in qs:
        (varying if varies_along(sweep, q, key) else equal).append(q)
    return varying, equal


def intensity_source(sweep):
    """Where the intensity each cell of a record sweep felt comes from: "im" (the measure as
    applied, records scaled to stripes), else the cell's PGA "pga" or "a_g" (the PGA of a
    record), the first of them stored with a finite value, else "records" (the record table's
    PGA); None without a record axis of two or more records or any of these."""
    if not sweep.has_axis("record", 2):
        return None
    for name in ("im", "pga", "a_g"):
        if name in sweep.responses and np.any(np.isfinite(sweep.responses[name])):
            return name
    rec = sweep.extra.get("records")
    if rec and "pga_mps2" in rec:
        return "records"
    return None


def quantity_names(qs):
    """The bases of quantities as a comma-separated list."""
    return ", ".join(q.base for q in qs)


STRIPE_AXES = ("im_g", "im_mps")


def stripe_axis(sweep):
    """The stripe axis (im_g, im_mps) that every cell's stored intensity `im` equals, when the
    intensity of a record sweep is that (records scaled to stripes), else None: drawn against
    their intensity, the cells would redraw the pages against the stripes."""
    if intensity_source(sweep) != "im":
        return None
    im = np.asarray(sweep.responses["im"], dtype=float)
    for key in STRIPE_AXES:
        if not sweep.has_axis(key, 2) or isinstance(sweep.axes[key], list):
            continue
        shape = [-1 if k == key else 1 for k in sweep.axis_order]
        stripe = np.broadcast_to(np.asarray(sweep.axes[key], dtype=float).reshape(shape),
                                 im.shape)
        finite = np.isfinite(im)
        if np.any(finite) and np.allclose(im[finite], stripe[finite], rtol=1e-9, atol=0.0):
            return key
    return None


def plan_generic(sweep):
    """[(kind, x_axis)] of the generic figures and [(kind, reason)] of those not made: no
    response page against an axis of the limit states alone (limit_state_axes), and a response
    equal at every value of an axis is not drawn against it (one reason per axis)."""
    todo, skipped = [], []
    drawn, margins = drawn_quantities(sweep)
    xs = numeric_axes(sweep)
    held = limit_state_axes(sweep)
    short = two_point_axes(sweep, xs)
    if drawn and intensity_source(sweep) is not None:
        stripes = stripe_axis(sweep)
        if stripes:
            skipped.append(("response_vs_intensity", f"the intensity of every cell is its "
                            f"stripe {stripes}: the pages against {stripes} draw them"))
        else:
            todo.append(("response_vs_intensity", None))
    if not xs:
        skipped.append(("response_vs_axis", "no numeric axis with two or more values"))
        return todo, skipped
    if not drawn:
        skipped.append(("response_vs_axis", "no response of the bridge's demand in the cube"))
    times = [n for n in sweep.responses if EVENT_TIMES.match(n)]
    if times:
        skipped.append(("response_vs_axis", f"{', '.join(times)}: the time of an event that may "
                        "never come (inf: the keys left intact), in the table of responses with "
                        "those cells counted; keys_broken is drawn"))
    for x in xs:
        if not drawn:
            break
        if x in held:
            skipped.append(("response_vs_axis", f"against {x}: it enters the limit states "
                            "alone, no response changes along it (the fragility figures draw "
                            "it)"))
            continue
        if x in short:
            skipped.append(("response_vs_axis", _two_points(sweep, x, xs)))
            continue
        varying, equal = drawn_against(sweep, x, drawn)
        if varying:
            todo.append(("response_vs_axis", x))
        if equal:
            skipped.append(("response_vs_axis", f"against {x}: {quantity_names(equal)} equal "
                            f"at every {x} in every cell"))
    if not margins:
        skipped.append(("unseating_margins", "the cube stores no unseating margin "
                        "(give seat_over_L or seat_m)"))
        return todo, skipped
    for x in xs:
        if x in held:
            skipped.append(("unseating_margins", f"against {x}: the margin moves with the "
                            "seat width alone, the corner travel is the same at every value "
                            "(the fragility figures draw it)"))
        elif x in short:
            skipped.append(("unseating_margins", _two_points(sweep, x, xs)))
        else:
            todo.append(("unseating_margins", x))
    return todo, skipped


def _two_points(sweep, x, xs):
    longer = [k for k in xs if k not in LIMIT_STATE_AXES and len(sweep.axes[k]) >= 3]
    return (f"against {x}: two values, drawn as columns or curves of the pages against "
            f"{', '.join(longer)}")


def draws_generic(sweep, todo, forced=False):
    """Whether a sweep gets the generic figures: when forced (--generic), when plan() gives it
    no figure (`todo` empty), or when its family is one's own bridge (GENERIC_FAMILIES)."""
    return forced or not todo or sweep.family in GENERIC_FAMILIES
