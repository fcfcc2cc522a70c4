#!/usr/bin/python3
"""Checks the output of scripts/report on the cubes and run file made by report_test.sh:

- every expected figure exists as PNG and PDF, has the pixel size the figure kind fixes, and is
  not blank (grey-level variance above 1e-3, more than 2 % of pixels not white); no other PNG;
- the sweeps that cannot support a figure are listed with the reason;
- the summary's tables agree with the cube read directly by h5py (spectrum peaks, the maximum
  rotation over w0/w_g per eta0);
- the correlation statistics (Pearson, Spearman, log-log slope, intercept, R^2) agree with
  scipy.stats, an implementation independent of the report's own numpy code, and so do the
  statistics stored in the cube when it has a correlation/ group; a stored band response
  agrees with its band_edges.

usage: check_report.py OUT_DIR REPORT_LOG SPECTRA.h5 PIDELTA.h5 ETA0.h5 RECORDS.h5 RUN.h5 PUSH.h5"""
import os
import sys

import h5py
import matplotlib.image
import numpy as np
import scipy.stats

EXPECTED = {  # file -> (width, height) in pixels
    "spectra_spectra.png": (1000, 900),
    "pi_delta_family_pidelta.png": (1000, 900),
    "rotation_vs_eta0_eta0.png": (1000, 900),
    "correlation_theta_vs_Le_records.png": (1200, 480),
    "correlation_rotation_vs_w0x_records.png": (1200, 480),
    "history_run.png": (1000, 1100),
    "history_push.png": (1000, 1100),
}
EXPECTED_SKIPS = [
    "skipped spectra for eta0: 2 curve axes (eta0, W0_over_w0)",
    "skipped correlation for spectra: no record axis",
    "skipped rotation_vs_eta0 for spectra: no eta0 axis",
    "skipped spectra for records: no w0_over_wg axis",
]


def check_images(out):
    pngs = sorted(f for f in os.listdir(out) if f.endswith(".png"))
    assert pngs == sorted(EXPECTED), f"PNG files {pngs}, expected {sorted(EXPECTED)}"
    for name, (width, height) in EXPECTED.items():
        img = matplotlib.image.imread(os.path.join(out, name))
        assert img.shape[:2] == (height, width), f"{name}: {img.shape[1]}x{img.shape[0]} px"
        grey = img[..., :3].mean(axis=2)
        variance = float(grey.var())
        inked = float(np.mean(grey < 0.95))
        assert variance > 1e-3, f"{name}: blank (grey variance {variance:.2e})"
        assert inked > 0.02, f"{name}: blank ({inked:.1%} of pixels not white)"
        pdf = os.path.join(out, name[:-4] + ".pdf")
        assert os.path.getsize(pdf) > 1000, f"{pdf} missing or empty"
        print(f"{name}: {width}x{height} px, grey variance {variance:.3f}, {inked:.1%} inked")


def table_rows(summary, heading):
    """The data rows (lists of cells) of the first table after a heading."""
    lines = summary.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("## " + heading))
    rows, seen = [], False
    for line in lines[start + 1:]:
        if line.startswith("|"):
            seen = True
            cells = [c.strip() for c in line.strip("|").split("|")]
            if not cells[0].startswith("---") and not line.startswith("|---"):
                rows.append(cells)
        elif seen:
            break
    return rows[1:]  # without the header


def close(a, b, rel=2e-3):
    return abs(a - b) <= rel * max(abs(a), abs(b), 1e-300)


def check_spectra_table(summary, path):
    g = h5py.File(path, "r")["sweeps/spectra"]
    assert list(g.attrs["axis_order"]) == ["pulse", "a_deg", "w0_over_wg"]
    a = g["axes/a_deg"][()]
    w = g["axes/w0_over_wg"][()]
    theta = g["responses/theta_norm"][()]
    rows = table_rows(summary, "spectra: spectra")
    assert len(rows) == 4, rows
    for row in rows:
        ip = ["cosine", "sine"].index(row[0])
        ia = int(np.argmin(abs(a - float(row[1]))))
        k = int(np.nanargmax(theta[ip, ia]))
        if theta[ip, ia, k] < 1e-9:  # the deck does not turn: no abscissa, 0 printed
            assert row[6:8] == ["0", "no response"], row
            continue
        assert close(float(row[6]), theta[ip, ia, k]), (row, theta[ip, ia, k])
        assert close(float(row[7].split()[0]), w[k]), (row, w[k])
        at_edge = k in (0, len(w) - 1)
        assert ("(grid edge)" in row[7]) == at_edge, (row, k, len(w))


def check_eta0_table(summary, path):
    g = h5py.File(path, "r")["sweeps/eta0"]
    assert list(g.attrs["axis_order"]) == ["eta0", "W0_over_w0", "w0_over_wg"]
    theta = g["responses/theta_norm"][()]
    peak = np.nanmax(theta, axis=2)
    rows = table_rows(summary, "eta0: rotation against η_0")
    assert len(rows) == 6, rows
    for row in rows:
        iw = [1.0, 2.0].index(float(row[1]))
        ie = [0.5, 1.5, 3.0].index(float(row[2]))
        if peak[ie, iw] < 1e-9:  # below the stated threshold: printed as 0, no response
            assert row[3] == "0" and row[4] == "no response", (row, peak[ie, iw])
        else:
            assert close(float(row[3]), peak[ie, iw]), (row, peak[ie, iw])


def check_correlation(summary, path):
    sys.dont_write_bytecode = True
    sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts"))
    from skewbridge_report import stats
    g = h5py.File(path, "r")["sweeps/records"]
    order = list(g.attrs["axis_order"])
    assert order == ["record", "Pi_delta"], order
    le = g["responses/L_e"][()]
    theta = g["responses/theta_m"][()]
    hits = g["responses/impacts"][()] > 0
    rows = table_rows(summary, "records: θ_m against the persistency L_e")
    all_rows = [r for r in rows if r[1] == "all records"]
    hit_rows = [r for r in rows if r[1] == "records that strike"]
    assert len(all_rows) == 3 and len(hit_rows) == 3, rows
    # The records that strike, fitted apart from those that never do (scipy as the oracle).
    for ipi, row in enumerate(hit_rows):
        x, y = le[hits[:, ipi], ipi], theta[hits[:, ipi], ipi]
        assert int(row[2]) == len(x), (row, len(x))
        if len(x) >= 3 and np.ptp(x) > 0 and np.ptp(y) > 0:
            assert close(float(row[3]), scipy.stats.pearsonr(x, y)[0]), row
            pos = y > 0
            fit = scipy.stats.linregress(np.log10(x[pos]), np.log10(y[pos]))
            assert close(float(row[5]), fit.slope), (row, fit.slope)
    for ipi, row in enumerate(all_rows):
        x, y = le[:, ipi], theta[:, ipi]
        own = stats.correlation_row(x, y)
        ref_p = scipy.stats.pearsonr(x, y)[0]
        ref_s = scipy.stats.spearmanr(x, y)[0]
        pos = y > 0
        fit = scipy.stats.linregress(np.log10(x[pos]), np.log10(y[pos]))
        for key, ref in (("pearson", ref_p), ("spearman", ref_s), ("slope", fit.slope),
                         ("intercept", fit.intercept), ("r2", fit.rvalue ** 2)):
            assert abs(own[key] - ref) < 1e-10, (ipi, key, own[key], ref)
        assert close(float(row[3]), ref_p) and close(float(row[4]), ref_s), (row, ref_p, ref_s)
        print(f"Pi_delta index {ipi}: Pearson {ref_p:.4f}, Spearman {ref_s:.4f}, "
              f"slope {fit.slope:.4f}, R^2 {fit.rvalue ** 2:.4f} (scipy agrees)")
    if "correlation" in g:
        check_stored_correlation(g, le, theta)
        assert all(row[-1] == "agree" for row in all_rows), all_rows
    check_stored_band(g)


def check_stored_correlation(g, le, theta):
    """The cube's own statistics against scipy, matched by dataset name."""
    corr = g["correlation"]
    refs = {}
    for ipi in range(le.shape[1]):
        x, y = le[:, ipi], theta[:, ipi]
        pos = y > 0
        fit = scipy.stats.linregress(np.log10(x[pos]), np.log10(y[pos]))
        refs.setdefault("pearson", []).append(scipy.stats.pearsonr(x, y)[0])
        refs.setdefault("spearman", []).append(scipy.stats.spearmanr(x, y)[0])
        refs.setdefault("slope", []).append(fit.slope)
        refs.setdefault("intercept", []).append(fit.intercept)
        refs.setdefault("r2", []).append(fit.rvalue ** 2)
    matched = 0
    for name, ds in corr.items():
        if not isinstance(ds, h5py.Dataset):
            continue
        key = next((k for k in refs if k in name.lower()), None)
        if key is None or ds.shape != (le.shape[1],):
            continue
        assert np.allclose(ds[()], refs[key], rtol=1e-6, atol=1e-9), (name, ds[()], refs[key])
        matched += 1
    assert matched == 5, f"correlation/ holds {matched} of the 5 statistics by name"
    print(f"stored correlation/: {matched} statistics agree with scipy")


def check_stored_band(g):
    """responses/band, when stored, against numpy's digitize of w0x_over_wg by band_edges."""
    if "band" not in g["responses"]:
        print("no responses/band in this cube: the report used its default groups")
        return
    band = g["responses/band"]
    edges = band.attrs["band_edges"]
    w0x = g["responses/w0x_over_wg"][()]
    expected = np.digitize(w0x, edges).astype(float)
    expected[~np.isfinite(w0x)] = np.nan
    assert np.array_equal(band[()], expected, equal_nan=True), (band[()], expected)
    print(f"stored band agrees with the edges {list(edges)}")


def check_history_tables(summary, path):
    """Impacts in the summary against the distinct impact instants of the event log, and the
    persistent contact of the push run seen in its state history."""
    with h5py.File(path, "r") as f:
        kind = f["events/kind"][()]
        impacts = len(np.unique(f["events/t_s"][()][kind == 0]))
        closed = int(np.count_nonzero(f["histories/state"][()] != 0))
    name = os.path.basename(path)
    lines = summary.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith(f"## Run {name}"))
    row = next(line for line in lines[start:] if line.startswith("| ") and
               line.split("|")[1].strip().isdigit())
    assert int(row.split("|")[1]) == impacts, (row, impacts)
    print(f"{name}: {impacts} impacts, {closed} samples in persistent contact")
    return closed


def main(out, log, spectra, pidelta, eta0, records, run, push):
    check_images(out)
    text = open(log).read()
    for line in EXPECTED_SKIPS:
        assert line in text, f"report log lacks '{line}':\n{text}"
    summary = open(os.path.join(out, "summary.md"), encoding="utf-8").read()
    for name in EXPECTED:
        assert f"]({name})" in summary, f"summary.md does not show {name}"
    check_spectra_table(summary, spectra)
    check_eta0_table(summary, eta0)
    check_correlation(summary, records)
    check_history_tables(summary, run)
    assert check_history_tables(summary, push) > 0, "the push run has no persistent contact"
    del pidelta
    print("check_report: ok")


if __name__ == "__main__":
    main(*sys.argv[1:9])
