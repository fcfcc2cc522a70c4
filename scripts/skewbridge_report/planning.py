"""What each sweep of a cube supports, decided from its axes, family and responses alone: the
report's planning (`scripts/report`). Pure: nothing here reads a file or draws, so a sweep built
in memory plans as a cube read from disk (tests/report/planning_test.py).

- plan(): the figures of the dimensionless study (spectra, the Π_δ family, rotation against
  η_0, the record correlations) with the curve axis of each, and those not made with why;
- plan_generic(): the generic figures of any sweep (each drawn quantity against each numeric
  axis, the unseating margins, the responses against each record's intensity), and those not
  made with why; drawn_quantities() says which responses they draw;
- draws_generic(): whether a sweep gets the generic figures at all."""
import re
from dataclasses import dataclass

import numpy as np

# Responses that describe the cell's excitation, its geometry or the solver rather than the
# bridge's demand: listed in the table of responses, not drawn against the axes.
DESCRIPTORS = {"a_g", "w_g", "L_e", "delta", "L", "pga", "pgv", "pgd", "arias", "T_m", "D5_95",
               "w0x_over_wg", "band", "min_impact_separation"}
# A normalised response and its dimensional twin: where the cube has both, the dimensional one
# (in metres and radians, as an engineer reads their own bridge) is drawn.
NORMALISED_TWIN = {"x_norm": "x_m", "y_norm": "y_m", "theta_norm": "theta_m",
                   "theta_end_norm": "theta_end", "margin_norm": "margin_m"}
# Residual displacements and the bound of the corner travel: in the table; the residual rotation
# is drawn.
TABLE_ONLY = {"x_end", "y_end", "travel_end_m", "travel_bound_m"}
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
    missing; theta_norm_max only without per-deck rotations."""
    qs = quantities(sweep)
    bases = {q.base for q in qs}
    drawn, margins = [], []
    for q in qs:
        if (q.base in DESCRIPTORS or q.base in TABLE_ONLY or q.base.startswith(LIMIT_STATE_PREFIX)
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


def plan_generic(sweep):
    """[(kind, x_axis)] of the generic figures and [(kind, reason)] of those not made."""
    todo, skipped = [], []
    drawn, margins = drawn_quantities(sweep)
    xs = numeric_axes(sweep)
    if drawn and intensity_source(sweep) is not None:
        todo.append(("response_vs_intensity", None))
    if not xs:
        skipped.append(("response_vs_axis", "no numeric axis with two or more values"))
        return todo, skipped
    if drawn:
        todo += [("response_vs_axis", x) for x in xs]
    else:
        skipped.append(("response_vs_axis", "no response of the bridge's demand in the cube"))
    if margins:
        todo += [("unseating_margins", x) for x in xs]
    else:
        skipped.append(("unseating_margins", "the cube stores no unseating margin "
                        "(give seat_over_L)"))
    return todo, skipped


def draws_generic(sweep, todo, forced=False):
    """Whether a sweep gets the generic figures: when forced (--generic), when plan() gives it
    no figure (`todo` empty), or when its family is one's own bridge (GENERIC_FAMILIES)."""
    return forced or not todo or sweep.family in GENERIC_FAMILIES
