#!/usr/bin/python3
"""Checks the output of scripts/report on the generic sweeps of generic_test.sh against the
cubes read directly with h5py (numpy only, none of the report's code):

- every figure the report names exists, has the size it was drawn at and is not blank; the
  figures expected for each sweep are there (responses against each numeric axis, unseating
  margins where the cube stores margins) and the ones it cannot make are listed with the reason;
- summary.md's table of responses over the grid (NaN no value, inf a value printed "inf"): min,
  median and max of every response equal the cube's to the 4 significant digits printed, and
  the cell of the max names its coordinates;
- the unseating table: per deck, the count of cells with a negative margin and the smallest
  margin equal the cube's;
- the fixed parameters and the record table (PGA, T_m of each record) equal the cube's;
- the Spearman correlation of each response with the record's PGA (scipy.stats) equals the
  table under the figure of responses against the intensity;
- the curves drawn: the report's figure code is run again in-process and the first curve of the
  first panel of each response figure must equal the envelope over the decks computed here.

usage: check_generic.py OUT_DIR REPORT_LOG OWN.h5 THREE.h5 REC.h5"""
import os
import re
import sys

import h5py
import matplotlib.image
import numpy as np
import scipy.stats

EXPECTED = {
    "own": ["response_vs_axis_T_g_own.png", "response_vs_axis_a_deg_own.png",
            "unseating_margins_T_g_own.png", "unseating_margins_a_deg_own.png"],
    "three-span": [f"{kind}_{x}_three-span.png" for kind in ("response_vs_axis",
                                                              "unseating_margins")
                   for x in ("a_deg", "Pi_delta", "k_factor")],
    "rec": ["response_vs_axis_Pi_delta_rec.png", "response_vs_intensity_rec.png"],
}
EXPECTED_SKIPS = ["skipped unseating_margins for rec: the cube stores no unseating margin",
                  "skipped spectra for own: no w0_over_wg axis"]


def sections(summary):
    """{heading: [table rows as lists of cells]} of summary.md."""
    out, heading, rows = {}, None, []
    for line in summary.splitlines():
        if line.startswith("## "):
            heading = line[3:].strip()
            out[heading] = rows = []
        elif line.startswith("|") and not line.startswith("|---") and heading:
            rows.append([c.strip() for c in line.strip().strip("|").split("|")])
    return {k: v[1:] for k, v in out.items()}  # without the header row


def number(text):
    return 0.0 if text == "0" else float(text)


def same4(printed, value):
    """A value printed with 4 significant digits ({:.4g}) equals `value`."""
    if abs(value) < 1e-9:
        return printed == "0"
    return printed == f"{value:.4g}"


def check_images(out, log):
    pngs = sorted(f for f in os.listdir(out) if f.endswith(".png"))
    wanted = sorted(f for names in EXPECTED.values() for f in names)
    assert pngs == wanted, f"PNG files {pngs}, expected {wanted}"
    for name in pngs:
        img = matplotlib.image.imread(os.path.join(out, name))
        grey = img[..., :3].mean(axis=2)
        assert grey.var() > 1e-3 and np.mean(grey < 0.95) > 0.02, f"{name}: blank"
        assert img.shape[0] >= 300 and img.shape[1] >= 500, f"{name}: {img.shape}"
    for skip in EXPECTED_SKIPS:
        assert skip in log, f"report.log lacks '{skip}'"
    print(f"{len(pngs)} figures, none blank")


def check_sweep(path, summary):
    with h5py.File(path, "r") as f:
        name = list(f["sweeps"])[0]
        g = f["sweeps"][name]
        order = [a.decode() if isinstance(a, bytes) else a for a in g.attrs["response_order"]]
        axes = [a.decode() if isinstance(a, bytes) else a for a in g.attrs["axis_order"]]
        table = {row[0]: row for row in summary[f"{name}: responses over the grid"]}
        checked = 0
        for r in order:
            values = g["responses"][r][()]
            # NaN is no value (a failed cell); inf is one (fewer than two impacts, a key intact).
            valued = values[~np.isnan(values)]
            row = table[r]
            unit = g["responses"][r].attrs["units"]
            unit = unit.decode() if isinstance(unit, bytes) else unit
            assert row[1] == {"m/s^2": "m/s²"}.get(unit, unit), (r, row[1], unit)
            if not len(valued):
                assert row[2] == "0", (r, row)
                continue
            assert int(row[2]) == len(valued), (r, row[2], len(valued))
            for printed, value in zip(row[3:6], (valued.min(), np.median(valued), valued.max())):
                if np.isinf(value):
                    assert printed == ("inf" if value > 0 else "-inf"), f"{name} {r}: {printed}"
                else:
                    assert same4(printed, float(value)), f"{name} {r}: {printed} vs {value:.6g}"
            k = np.unravel_index(int(np.argmax(np.where(np.isnan(values), -np.inf, values))),
                                 values.shape)
            for axis, i in zip(axes, k):
                coord = g["axes"][axis][i]
                if len(g["axes"][axis]) < 2:
                    continue
                text = coord.decode() if isinstance(coord, bytes) else f"{coord:g}"
                assert text in row[6], f"{name} {r}: cell of the max '{row[6]}' lacks {text}"
            checked += 1
        print(f"{name}: {checked} responses: min, median, max and the cell of the max agree")

        margins = sorted(r for r in order if re.fullmatch(r"margin_m_d\d+", r))
        if margins:
            rows = summary[f"{name}: unseating (margin_m)"]
            assert len(rows) == len(margins), rows
            for row, r in zip(rows, margins):
                values = g["responses"][r][()]
                assert row[0] == r.rsplit("_d", 1)[1], (row, r)
                assert int(row[2]) == int(np.count_nonzero(values < 0)), (row, r)
                assert same4(row[4], float(np.nanmin(values))), (row, np.nanmin(values))
            print(f"{name}: unseating table agrees for {len(margins)} deck(s)")

        fixed = {row[0]: row for row in summary[f"{name}: fixed parameters"]
                 } if summary.get(f"{name}: fixed parameters") else {}
        keys = [k.decode() if isinstance(k, bytes) else k for k in g["fixed"].attrs.get("keys", [])]
        units = [u.decode() if isinstance(u, bytes) else u for u in g["fixed"].attrs.get("units", [])]
        for key, unit in zip(keys, units):
            v = g["fixed"].attrs[key]
            v = v.decode() if isinstance(v, bytes) else v
            assert key in fixed, f"{name}: fixed {key} not in summary.md"
            expect = v if isinstance(v, str) else f"{float(v):.4g}"
            assert fixed[key][1] == expect, (key, fixed[key], expect)
            shown = {"deg": "°"}.get(unit, unit)
            assert fixed[key][2] == (shown if unit not in ("",) else "–"), (key, fixed[key], unit)
        if "records" in g:
            rows = summary[f"{name}: records"]
            labels = [x.decode() for x in g["records/label"][()]]
            assert [row[0] for row in rows] == labels, ([row[0] for row in rows], labels)
            for row, pga, tm in zip(rows, g["records/pga_mps2"][()], g["records/T_m_s"][()]):
                assert same4(row[3], float(pga)) and same4(row[6], float(tm)), (row, pga, tm)
            print(f"{name}: record table agrees ({len(labels)} records)")
            rows = summary[f"{name}: responses against the PGA of each record"]
            pga = g["responses/pga"][()]
            for row in rows:
                r = {"x_m": "x_m_d0", "y_m": "y_m_d0", "θ_m": "theta_m_d0",
                     "θ_end": "theta_end_d0", "impacts": "impacts"}[row[0]]
                y = g["responses"][r][()]
                y = np.where(np.abs(y) < 1e-9, 0.0, y)
                ok = np.isfinite(y) & np.isfinite(pga)
                rho = scipy.stats.spearmanr(pga[ok], y[ok]).statistic
                assert int(row[1]) == int(ok.sum()), (row, ok.sum())
                assert (row[2] == "–" and not np.isfinite(rho)) or same4(row[2], float(rho)), \
                    (row, rho)
            print(f"{name}: Spearman r_s of {len(rows)} responses with PGA agree with scipy")


def check_curves(paths):
    """The first curve of the first panel of every response figure against the cube."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                    "scripts"))
    from skewbridge_report import common, data, generic, planning  # noqa: E402
    import matplotlib.pyplot as plt  # noqa: E402
    for path in paths:
        sweep = data.load_cube(path)[0]
        drawn, _ = planning.drawn_quantities(sweep)
        for x in planning.numeric_axes(sweep):
            layout = generic.layouts(sweep, x)[0]
            q = drawn[0]
            captured = {}
            save = common.save
            common.save = lambda fig, *a: captured.setdefault("fig", fig) and ""
            try:
                generic.response_vs_axis(sweep, layout, drawn, "/nonexistent", "x", False)
            finally:
                common.save = save
            fig = captured["fig"]
            ax = fig.axes[0]
            drawn_y = np.asarray(ax.lines[0].get_ydata(), dtype=float)
            with h5py.File(path, "r") as f:
                g = f["sweeps"][sweep.name]
                stacked = np.stack([g["responses"][n][()] for n in q.names])
            env = stacked.max(axis=0)  # x_m: the largest over the decks
            # along x; the first curve and the first column are index 0 of the other axes
            # (over a record axis, the first line drawn is the first record's)
            index = [slice(None) if key == x else 0 for key in sweep.axis_order]
            expect = env[tuple(index)]
            factor = {"[mm]": 1e3, "[µm]": 1e6}.get(re.search(r"\[.*?\]", ax.get_ylabel())
                                                     .group(0), 1.0)
            assert np.allclose(drawn_y, expect * factor, rtol=1e-12, atol=1e-12), \
                f"{sweep.name} {x}: drawn {drawn_y} vs cube {expect * factor}"
            plt.close(fig)
            print(f"{sweep.name}: {q.base} against {x}: the drawn curve is the cube's "
                  f"({'worst of ' + str(len(q.names)) + ' decks' if len(q.names) > 1 else 'one deck'})")


def main(argv):
    out, log_path, paths = argv[1], argv[2], argv[3:]
    with open(log_path, encoding="utf-8") as f:
        log = f.read()
    with open(os.path.join(out, "summary.md"), encoding="utf-8") as f:
        summary = sections(f.read())
    check_images(out, log)
    for path in paths:
        check_sweep(path, summary)
    check_curves(paths)
    print("check_generic: ok")


if __name__ == "__main__":
    main(sys.argv)
