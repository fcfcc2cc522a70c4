#!/usr/bin/python3
"""The report's planning (scripts/skewbridge_report/planning.py) on sweeps built in memory: one
row per sweep shape, with the figures each one must get and the ones it must not, with the
reason, written out by hand from the rules the README states ("It looks at each sweep's axes
and draws what they support"): a spectrum takes w0/w_g with two or more values and one curve
axis besides pulse; Pi_delta as that axis is the Π_δ family; rotation against η_0 takes an
eta0 axis and one curve axis besides; the correlations take records over at most Pi_delta; the
generic figures draw every response of the bridge's demand (not descriptors, limit states,
IDA runs, residual displacements, nor a normalised twin of a dimensional one, nor a response
computed in no cell) against every numeric axis, the margins apart, and against the intensity
of each record; never against an axis of the limit states alone (a seat width), nor a
response against an axis it does not change along, nor the inputs of scaled records. No MPI,
no HDF5 file, no figure.

usage: planning_test.py SOURCE_ROOT"""
import os
import sys
import unittest

import numpy as np

ROOT = sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..",
                                                                "..")
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from skewbridge_report import planning  # noqa: E402
from skewbridge_report.sweep import Sweep  # noqa: E402
from skewbridge_report.data import floor_rotations  # noqa: E402

NUMBERS = {"w0_over_wg": 12, "a_deg": 4, "eta0": 6, "Pi_delta": 3, "W0_over_w0": 4, "mu": 2,
           "k_factor": 2, "T_g": 5, "im_g": 3, "seat_over_L": 1}
LABELS = {"pulse": ["cosine", "sine"], "record": ["r1", "r2", "r3"]}


def sweep(axes, responses, family="subsystem", nan=(), extra=None, equal=None):
    """A sweep over `axes` ({key: number of values} or a list of labels) whose responses differ
    from cell to cell (1 + the cell's flat index: they vary along every axis), except those in
    `nan` (computed in no cell) and those `equal` ({response: [axis, ...]}) names: the same at
    every value of those axes (the value at their first index, as a seat width leaves a
    response bit for bit)."""
    values = {}
    for key, n in axes.items():
        values[key] = list(n) if isinstance(n, list) else np.linspace(1.0, 2.0, n)
    shape = tuple(len(v) for v in values.values())
    out = {}
    for r in responses:
        v = 1.0 + np.arange(int(np.prod(shape)), dtype=float).reshape(shape)
        for key in (equal or {}).get(r, []):
            k = list(axes).index(key)
            v = np.broadcast_to(np.take(v, [0], axis=k), shape).copy()
        out[r] = np.full(shape, np.nan) if r in nan else v
    return Sweep(path="memory", name="s", family=family, complete=True,
                 axis_order=list(axes), axes=values, responses=out,
                 status=np.zeros(shape, dtype=int), status_names={0: "ok"}, fixed={},
                 spec_text="", response_attrs={r: {} for r in responses},
                 extra=extra or {})


SPECTRA = ["x_norm", "y_norm", "theta_norm", "impacts"]
RECORDS = ["theta_m", "L_e", "theta_norm", "w0x_over_wg", "impacts", "a_g"]
NO_ETA0 = ("rotation_vs_eta0", "no eta0 axis with two or more values")
NO_RECORDS = ("correlation", "no record axis with two or more records")
NO_W0 = ("spectra", "no w0_over_wg axis with two or more values")
W = NUMBERS["w0_over_wg"]

# (what, axes, responses, figures made, figures not made with the reason)
PLAN = [
    ("the default: skew angles, both pulses",
     {"pulse": LABELS["pulse"], "a_deg": 4, "w0_over_wg": W}, SPECTRA,
     [("spectra", "a_deg")], [NO_ETA0, NO_RECORDS]),
    ("one curve: pulse and w0/w_g alone", {"pulse": LABELS["pulse"], "w0_over_wg": W}, SPECTRA,
     [("spectra", None)], [NO_ETA0, NO_RECORDS]),
    ("an axis of one value is no curve axis",
     {"a_deg": 1, "w0_over_wg": W, "eta0": 1}, SPECTRA,
     [("spectra", None)], [NO_ETA0, NO_RECORDS]),
    ("Pi_delta as the curve axis: the family",
     {"pulse": LABELS["pulse"], "Pi_delta": 3, "w0_over_wg": W}, SPECTRA,
     [("pi_delta_family", "Pi_delta")], [NO_ETA0, NO_RECORDS]),
    ("two curve axes: no spectrum; rotation against eta0 per skew angle",
     {"a_deg": 4, "eta0": 6, "w0_over_wg": W}, SPECTRA,
     [("rotation_vs_eta0", "a_deg")],
     [("spectra", "2 curve axes (a_deg, eta0); a spectrum figure takes one besides pulse and "
       "w0_over_wg"), NO_RECORDS]),
    ("Fig. 7 of the paper: eta0 per Omega0/w0",
     {"eta0": 6, "W0_over_w0": 4, "w0_over_wg": W}, SPECTRA,
     [("rotation_vs_eta0", "W0_over_w0")],
     [("spectra", "2 curve axes (eta0, W0_over_w0); a spectrum figure takes one besides pulse "
       "and w0_over_wg"), NO_RECORDS]),
    ("eta0 alone: one rotation curve, the spectra per eta0",
     {"eta0": 6, "w0_over_wg": W}, SPECTRA,
     [("spectra", "eta0"), ("rotation_vs_eta0", None)], [NO_RECORDS]),
    ("eta0 without w0/w_g", {"eta0": 6}, SPECTRA,
     [("rotation_vs_eta0", None)], [NO_W0, NO_RECORDS]),
    ("two curve axes besides eta0",
     {"eta0": 6, "W0_over_w0": 4, "mu": 2, "w0_over_wg": W}, SPECTRA, [],
     [("spectra", "3 curve axes (eta0, W0_over_w0, mu); a spectrum figure takes one besides "
       "pulse and w0_over_wg"),
      ("rotation_vs_eta0", "2 curve axes besides eta0 (W0_over_w0, mu); the figure takes one"),
      NO_RECORDS]),
    ("w0/w_g of one value", {"a_deg": 4, "w0_over_wg": 1}, SPECTRA, [],
     [NO_W0, NO_ETA0, NO_RECORDS]),
    ("a cube without the normalised maxima",
     {"eta0": 6, "w0_over_wg": W}, ["x_norm", "y_norm", "impacts"], [],
     [("spectra", "the cube lacks x_norm, y_norm or theta_norm"),
      ("rotation_vs_eta0", "the cube lacks theta_norm"), NO_RECORDS]),
    ("the pilot study: records by Pi_delta",
     {"record": LABELS["record"], "Pi_delta": 3}, RECORDS,
     [("correlation_theta_vs_Le", None), ("correlation_rotation_vs_w0x", None)],
     [NO_W0, NO_ETA0]),
    ("records without L_e and w0x/w_g",
     {"record": LABELS["record"], "Pi_delta": 3}, ["theta_m", "theta_norm"], [],
     [NO_W0, NO_ETA0, ("correlation_theta_vs_Le", "the cube lacks theta_m or L_e"),
      ("correlation_rotation_vs_w0x", "the cube lacks theta_norm or w0x_over_wg")]),
    ("records over w0/w_g: one spectrum per record is not drawn",
     {"record": LABELS["record"], "w0_over_wg": W}, SPECTRA + RECORDS, [],
     [("spectra", "a record axis: one spectrum per record is not plotted"), NO_ETA0,
      ("correlation", "axes besides record and Pi_delta: w0_over_wg")]),
    ("a single record", {"record": ["r1"], "Pi_delta": 3}, RECORDS, [],
     [NO_W0, NO_ETA0, NO_RECORDS]),
]

OWN = ["x_m", "y_m", "theta_m", "impacts", "x_norm", "theta_norm", "x_end", "theta_end",
       "L_e", "pga", "ls_unseating", "ls_unseating_demand", "ida_im_00", "margin_m_d0",
       "margin_m_d1", "margin_norm_d0", "theta_norm_max"]
DRAWN = ["x_m", "y_m", "theta_m", "impacts", "theta_end"]
NO_MARGIN = ("unseating_margins", "the cube stores no unseating margin (give seat_over_L or seat_m)")
NO_NUMERIC = ("response_vs_axis", "no numeric axis with two or more values")
RECORD_TABLE = {"records": {"pga_mps2": np.array([1.0, 2.0, 3.0])}}

# (what, axes, responses, responses computed in no cell, extra groups, family, drawn
# quantities, margins, figures made, figures not made with the reason)
GENERIC = [
    ("one's own bridge over skew and stiffness", {"a_deg": 4, "k_factor": 3}, OWN, (), None,
     "model-file", DRAWN, ["margin_m"],
     [("response_vs_axis", "a_deg"), ("response_vs_axis", "k_factor"),
      ("unseating_margins", "a_deg"), ("unseating_margins", "k_factor")], []),
    ("label axes only", {"pulse": LABELS["pulse"], "record": ["r1"]}, OWN, (), None,
     "model-file", DRAWN, ["margin_m"], [], [NO_NUMERIC]),
    ("records by seat: the intensity is the stored pga",
     {"record": LABELS["record"], "seat_over_L": 1, "T_g": 5},
     ["x_m", "theta_m", "pga", "im"], ["im"], None, "model-file", ["x_m", "theta_m"], [],
     [("response_vs_intensity", None), ("response_vs_axis", "T_g")], [NO_MARGIN]),
    ("records with no intensity stored per cell: the record table's PGA",
     {"record": LABELS["record"], "im_g": 3}, ["x_m", "margin_m", "a_g"], ["a_g"],
     RECORD_TABLE, "model-file", ["x_m"], ["margin_m"],
     [("response_vs_intensity", None), ("response_vs_axis", "im_g"),
      ("unseating_margins", "im_g")], []),
    ("records with no intensity at all", {"record": LABELS["record"], "im_g": 3}, ["x_m"], (),
     None, "model-file", ["x_m"], [], [("response_vs_axis", "im_g")], [NO_MARGIN]),
    ("nothing of the bridge's demand: descriptors, limit states, a response never computed",
     {"a_deg": 4}, ["L_e", "w0x_over_wg", "ls_unseating", "ida_capacity_unseating", "y_m"],
     ["y_m"], None, "model-file", [], [], [],
     [("response_vs_axis", "no response of the bridge's demand in the cube"), NO_MARGIN]),
    ("normalised maxima alone are drawn, and the rotation envelope of the decks",
     {"Pi_delta": 3}, ["x_norm", "theta_norm_max", "margin_norm"], (), None, "multi-span",
     ["x_norm", "theta_norm_max"], ["margin_norm"],
     [("response_vs_axis", "Pi_delta"), ("unseating_margins", "Pi_delta")], []),
]

# Sweeps of one's own bridge with an axis of the limit states alone (a seat width), responses
# equal along an axis, the inputs of scaled records, an axis of two values beside a longer
# one, records scaled to stripes: (what, axes, responses, {response: axes it is equal along},
# drawn quantities, figures made, figures not made with the reason), written out by hand from
# the rules: no response page against, nor margin page against, an axis that enters the
# limit states alone; a response equal at every value of an axis is not drawn against it,
# stated in one line per axis; T1, im, im_unscaled, scale_factor and scaled_too_far are
# inputs, never drawn; an axis of two values is no abscissa beside one of three or more; a
# stripe sweep's responses are not drawn again against the stripe they were scaled to.
SEAT_REASON = ("response_vs_axis", "against seat_over_L: it enters the limit states alone, no "
               "response changes along it (the fragility figures draw it)")
SEAT_MARGIN = ("unseating_margins", "against seat_over_L: the margin moves with the seat width "
               "alone, the corner travel is the same at every value (the fragility figures draw "
               "it)")
SCALED = ["x_m", "theta_m", "impacts", "margin_m", "T1", "im", "im_unscaled", "scale_factor",
          "scaled_too_far", "ls_unseating"]
ALL_BUT_MARGIN = {r: ["seat_over_L"] for r in SCALED if r not in ("margin_m", "ls_unseating")}
RECORD_STRIPES = {"record": LABELS["record"], "im_g": 4, "k_factor": 3, "seat_over_L": 3}
LIMITS = [
    ("a seat axis: no response page, no margin page against it; inputs not drawn",
     {"im_g": 4, "k_factor": 3, "seat_over_L": 3}, SCALED, ALL_BUT_MARGIN,
     ["x_m", "theta_m", "impacts"],
     [("response_vs_axis", "im_g"), ("response_vs_axis", "k_factor"),
      ("unseating_margins", "im_g"), ("unseating_margins", "k_factor")],
     [SEAT_REASON, SEAT_MARGIN]),
    ("a response equal along an axis: not drawn against it, said once",
     {"a_deg": 4, "k_factor": 3}, ["x_m", "theta_m", "impacts", "y_m"],
     {"impacts": ["k_factor"], "theta_m": ["k_factor", "a_deg"]},
     ["x_m", "theta_m", "impacts", "y_m"],
     [("response_vs_axis", "a_deg"), ("response_vs_axis", "k_factor")],
     [("response_vs_axis", "against a_deg: theta_m equal at every a_deg in every cell"),
      ("response_vs_axis", "against k_factor: theta_m, impacts equal at every k_factor in "
       "every cell"), NO_MARGIN]),
    ("no response changes along an axis: no page against it",
     {"a_deg": 4, "k_factor": 3}, ["x_m", "impacts"],
     {"x_m": ["a_deg"], "impacts": ["a_deg"]}, ["x_m", "impacts"],
     [("response_vs_axis", "k_factor")],
     [("response_vs_axis", "against a_deg: x_m, impacts equal at every a_deg in every cell"),
      NO_MARGIN]),
    ("an axis of two values beside a longer one: columns, no abscissa",
     {"a_deg": 2, "T_g": 5}, ["x_m", "margin_m"], {}, ["x_m"],
     [("response_vs_axis", "T_g"), ("unseating_margins", "T_g")],
     [("response_vs_axis", "against a_deg: two values, drawn as columns or curves of the pages "
       "against T_g"),
      ("unseating_margins", "against a_deg: two values, drawn as columns or curves of the "
       "pages against T_g")]),
    ("two axes of two values: both abscissas",
     {"a_deg": 2, "k_factor": 2}, ["x_m"], {}, ["x_m"],
     [("response_vs_axis", "a_deg"), ("response_vs_axis", "k_factor")], [NO_MARGIN]),
    ("a seat axis of three values is no longer axis for one of two",
     {"a_deg": 2, "seat_over_L": 3}, ["x_m", "margin_m"], {"x_m": ["seat_over_L"]}, ["x_m"],
     [("response_vs_axis", "a_deg"), ("unseating_margins", "a_deg")],
     [SEAT_REASON, SEAT_MARGIN]),
    ("records scaled to stripes: no second figure against the intensity",
     RECORD_STRIPES, SCALED, ALL_BUT_MARGIN, ["x_m", "theta_m", "impacts"],
     [("response_vs_axis", "im_g"), ("response_vs_axis", "k_factor"),
      ("unseating_margins", "im_g"), ("unseating_margins", "k_factor")],
     [("response_vs_intensity", "the intensity of every cell is its stripe im_g: the pages "
       "against im_g draw them"), SEAT_REASON, SEAT_MARGIN]),
]

# (what, axes, responses, responses computed in no cell, extra groups, where the intensity of
# each cell comes from)
R3 = {"record": LABELS["record"], "im_g": 3}
INTENSITY = [
    ("the measure as applied first", R3, ["im", "pga", "a_g"], (), RECORD_TABLE, "im"),
    ("then the cell's PGA", R3, ["im", "pga", "a_g"], ["im"], RECORD_TABLE, "pga"),
    ("then a_g, the PGA of a record", R3, ["im", "a_g"], ["im"], RECORD_TABLE, "a_g"),
    ("then the record table", R3, ["im", "pga", "a_g"], ["im", "pga", "a_g"], RECORD_TABLE,
     "records"),
    ("none stored", R3, ["im"], ["im"], None, None),
    ("no record axis", {"im_g": 3}, ["im"], (), RECORD_TABLE, None),
    ("one record", {"record": ["r1"], "im_g": 3}, ["im"], (), RECORD_TABLE, None),
]

# (what, family, figures of plan(), --generic, generic figures drawn)
DRAWS_GENERIC = [
    ("a spectrum sweep gets its spectra alone", "subsystem", [("spectra", None)], False, False),
    ("--generic draws them for any sweep", "subsystem", [("spectra", None)], True, True),
    ("a sweep with no spectrum figure gets the generic ones", "pilot-bridge", [], False, True),
    ("a model file: always", "model-file", [("spectra", None)], False, True),
    ("several decks: always", "multi-span", [("rotation_vs_eta0", None)], False, True),
]


class Planning(unittest.TestCase):
    def test_plan(self):
        for what, axes, responses, todo, skipped in PLAN:
            with self.subTest(what):
                made, not_made = planning.plan(sweep(axes, responses))
                self.assertEqual(made, todo)
                self.assertEqual(not_made, skipped)

    def test_plan_generic(self):
        for what, axes, responses, nan, extra, family, drawn, margins, todo, skipped in GENERIC:
            with self.subTest(what):
                s = sweep(axes, responses, family, nan, extra)
                got_drawn, got_margins = planning.drawn_quantities(s)
                self.assertEqual([q.base for q in got_drawn], drawn)
                self.assertEqual([q.base for q in got_margins], margins)
                self.assertEqual(planning.plan_generic(s), (todo, skipped))

    def test_limit_states_and_equal_responses(self):
        for what, axes, responses, equal, drawn, todo, skipped in LIMITS:
            with self.subTest(what):
                s = sweep(axes, responses, "model-file", equal=equal)
                if "im" in responses and "im_g" in axes:  # the intensity each cell was scaled to
                    k = list(axes).index("im_g")
                    shape = [-1 if i == k else 1 for i in range(len(axes))]
                    s.responses["im"] = np.broadcast_to(
                        s.axes["im_g"].reshape(shape), s.shape()).copy()
                got_drawn, _ = planning.drawn_quantities(s)
                self.assertEqual([q.base for q in got_drawn], drawn)
                self.assertEqual(planning.plan_generic(s), (todo, skipped))

    def test_seat_axes(self):
        """The axes of the limit states alone, only with two or more values."""
        s = sweep({"a_deg": 2, "seat_over_L": 3, "T_g": 4}, ["x_m"])
        self.assertEqual(planning.limit_state_axes(s), ["seat_over_L"])
        s = sweep({"a_deg": 2, "seat_over_L": 1}, ["x_m"])
        self.assertEqual(planning.limit_state_axes(s), [])

    def test_equal_within_round_off(self):
        """A difference of round-off (1e-12 of the response) is no variation; one of 1e-6 is."""
        s = sweep({"a_deg": 3, "k_factor": 2}, ["x_m"], equal={"x_m": ["k_factor"]})
        q = planning.quantities(s)[0]
        s.responses["x_m"][:, 1] *= 1 + 1e-12
        self.assertFalse(planning.varies_along(s, q, "k_factor"))
        s.responses["x_m"][:, 1] *= 1 + 1e-6
        self.assertTrue(planning.varies_along(s, q, "k_factor"))

    def test_intensity_source(self):
        for what, axes, responses, nan, extra, want in INTENSITY:
            with self.subTest(what):
                s = sweep(axes, responses, "model-file", nan, extra)
                self.assertEqual(planning.intensity_source(s), want)

    def test_decks_merge(self):
        """A response per deck is one quantity with its datasets in deck order."""
        s = sweep({"a_deg": 2}, ["x_m_d0", "x_m_d1", "x_m_d2", "impacts"], "multi-span")
        x, impacts = planning.quantities(s)
        self.assertEqual((x.base, x.names, x.decks), ("x_m", ["x_m_d0", "x_m_d1", "x_m_d2"],
                                                      [0, 1, 2]))
        self.assertEqual(x.dataset(1), "x_m_d1")
        self.assertEqual((impacts.base, impacts.decks), ("impacts", [None]))

    def test_draws_generic(self):
        for what, family, todo, forced, want in DRAWS_GENERIC:
            with self.subTest(what):
                s = sweep({"a_deg": 2}, ["x_m"], family)
                self.assertEqual(planning.draws_generic(s, todo, forced), want)



class BreakTimes(unittest.TestCase):
    """A shear key that never breaks stores the break time +inf (key_break_time_px, _mx). The
    generic figures do not draw break times against the axes (a curve would drop the intact
    cells), say so once under "Figures not made", and draw keys_broken; the table of responses
    counts the inf cells as cells with a value and prints "inf" for the min, median or max that
    is infinite, the others over the same cells, by hand below. NaN (a failed cell) stays no
    value."""

    def test_break_times_in_the_table_not_in_the_figures(self):
        from skewbridge_report import generic
        s = sweep({"record": LABELS["record"], "im_g": 2},
                  ["x_m_d0", "key_break_time_px", "key_break_time_mx", "keys_broken"],
                  "model-file")
        inf, nan = np.inf, np.nan
        s.responses["key_break_time_px"] = np.array([[inf, 7.5], [inf, 3.25], [nan, inf]])
        s.responses["key_break_time_mx"] = np.full((3, 2), inf)
        s.responses["keys_broken"] = np.array([[0.0, 1.0], [0.0, 2.0], [nan, 0.0]])
        drawn, _ = planning.drawn_quantities(s)
        self.assertEqual([q.base for q in drawn], ["x_m", "keys_broken"])
        todo, skipped = planning.plan_generic(s)
        self.assertIn(("response_vs_axis", "im_g"), todo)
        notes = [r for kind, r in skipped if "key_break_time_px, key_break_time_mx" in r]
        self.assertEqual(len(notes), 1, skipped)
        rows = {r[0]: r for r in generic.response_table(s)}
        # px: five cells with a value (one NaN); sorted 3.25, 7.5, inf, inf, inf: median inf.
        self.assertEqual(rows["key_break_time_px"][2:6], (5, 3.25, "inf", "inf"))
        self.assertEqual(rows["key_break_time_mx"][2:6], (6, "inf", "inf", "inf"))
        # keys_broken: 0, 1, 0, 2, 0 -> median 0, max 2 at the second record's second stripe.
        self.assertEqual(rows["keys_broken"][2:6], (5, 0.0, 0.0, 2.0))
        self.assertIn("r2", rows["keys_broken"][6])


class RoundOffFloor(unittest.TestCase):
    """A rotation below the cube's round_off_floor_rad is 0, and its normalised twin in the same
    cells; a rotation above it, responses in other units and NaN keep their values."""

    def test_rotations_below_the_floor_and_their_twins_are_zero(self):
        responses = {"theta_m": np.array([1e-19, 2e-4, np.nan, -5e-13]),
                     "theta_norm": np.array([3e-9, 0.05, np.nan, 4e-10]),
                     "theta_end_d0": np.array([1e-14, 1e-3, 0.0, 0.0]),
                     "theta_end_norm_d0": np.array([7e-11, 0.2, 0.0, 0.0]),
                     "x_m": np.array([1e-19, 0.1, 0.2, 0.3])}
        attrs = {"theta_m": {"units": "rad"}, "theta_norm": {"units": "1"},
                 "theta_end_d0": {"units": "rad"}, "theta_end_norm_d0": {"units": "1"},
                 "x_m": {"units": "m"}}
        self.assertEqual(floor_rotations(responses, attrs, 1e-12), 3)
        np.testing.assert_array_equal(responses["theta_m"], [0.0, 2e-4, np.nan, 0.0])
        np.testing.assert_array_equal(responses["theta_norm"], [0.0, 0.05, np.nan, 0.0])
        np.testing.assert_array_equal(responses["theta_end_d0"], [0.0, 1e-3, 0.0, 0.0])
        np.testing.assert_array_equal(responses["theta_end_norm_d0"], [0.0, 0.2, 0.0, 0.0])
        np.testing.assert_array_equal(responses["x_m"], [1e-19, 0.1, 0.2, 0.3])
        self.assertEqual(floor_rotations(responses, attrs, 0.0), 0)

if __name__ == "__main__":
    unittest.main(verbosity=1)
