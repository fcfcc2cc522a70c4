"""Response spectra files (`skewbridge records spectrum --out FILE.h5`, docs/hdf5-layout.md
"Response spectra"): one log-log figure of PSa against T per record set and damping ratio, the
records of the set in thin lines with their median and 16-84 % band; and, where the file has
record pairs (/pairs), one figure per set of pairs: the median over the pairs of Sa of H1 and
of H2, their geometric mean GM, RotD50 and RotD100 [Boore 2010], and below them each measure
over RotD50."""
import os

import h5py
import matplotlib.pyplot as plt
import numpy as np

from . import common
from .data import ReportError

G = 9.80665
# A set gets its median and 16-84 % band from this many records on.
MIN_BAND_RECORDS = 3


def _texts(values):
    return [v.decode() if isinstance(v, bytes) else str(v) for v in values]


def load_spectra(path):
    """The spectra group of a file as a dict of arrays; ReportError for anything else."""
    if not os.path.isfile(path):
        raise ReportError(f"{path}: no such file")
    try:
        f = h5py.File(path, "r")
    except OSError as err:
        raise ReportError(f"{path}: not an HDF5 file ({err})") from None
    with f:
        if "spectra" not in f:
            raise ReportError(f"{path}: no /spectra group (not written by `skewbridge records "
                              "spectrum --out FILE.h5`)")
        g = f["spectra"]
        out = {"path": path, "label": _texts(g["label"][()]), "set": _texts(g["set"][()]),
               "period_s": g["period_s"][()], "xi": g["xi"][()], "psa_g": g["PSa_mps2"][()] / G,
               "command": str(g.attrs.get("command", "")), "pairs": None}
        if "pairs" in f:
            p = f["pairs"]
            out["pairs"] = {"label": _texts(p["label"][()]), "set": _texts(p["set"][()])}
            for measure, _, _ in PAIR_MEASURES:
                out["pairs"][measure] = p[f"{measure}_mps2"][()] / G
        return out


# The measures of a pair drawn by pair_figure: (dataset stem, legend, colour).
PAIR_MEASURES = [("Sa_H1", "$S_a$ of H1", "tab:blue"), ("Sa_H2", "$S_a$ of H2", "tab:cyan"),
                 ("GM", r"GM = $\sqrt{S_{a,H1} S_{a,H2}}$", "tab:green"),
                 ("RotD50", "RotD50", "black"), ("RotD100", "RotD100", "tab:red")]


def pair_groups(spectra):
    """(set name, pair indices) of the file's /pairs in order of first appearance; [] without."""
    pairs = spectra.get("pairs")
    if not pairs:
        return []
    out = {}
    for i, s in enumerate(pairs["set"]):
        out.setdefault(s or "pairs", []).append(i)
    return list(out.items())


def pair_figure(spectra, set_name, members, out_dir, name, pdf):
    """The pairs of one set: per damping ratio (columns) the median over the pairs of Sa H1,
    Sa H2, GM, RotD50 and RotD100 against T (top; each pair's RotD50 in thin grey lines, and
    with fewer than MIN_BAND_RECORDS pairs each pair's five curves thin), and the median of each
    measure over the pair's own RotD50 (bottom). Returns the path and the table rows (set, xi,
    pairs, measure, median at T*, T*, median ratio to RotD50 at T*), T* the period where the
    median RotD50 peaks."""
    pairs = spectra["pairs"]
    periods = spectra["period_s"]
    xis = spectra["xi"]
    fig, axes = plt.subplots(2, len(xis), figsize=(6.0 * len(xis) + 1.0, 9.0),
                             layout="constrained", squeeze=False,
                             gridspec_kw={"height_ratios": [2.0, 1.0]})
    rows = []
    few = len(members) < MIN_BAND_RECORDS
    for x, xi in enumerate(xis):
        ax, ratio_ax = axes[0, x], axes[1, x]
        rotd50 = pairs["RotD50"][members, x, :]
        for k in range(len(members)):
            ax.plot(periods, rotd50[k], color="0.7", lw=0.6,
                    label="RotD50 of a pair" if k == 0 and not few else None)
        peak = int(np.argmax(np.median(rotd50, axis=0)))
        for measure, legend, colour in PAIR_MEASURES:
            values = pairs[measure][members, x, :]
            median = np.median(values, axis=0)
            ratio = np.median(values / rotd50, axis=0)
            if few:
                for k in range(len(members)):
                    ax.plot(periods, values[k], color=colour, lw=0.7, ls=":")
            ax.plot(periods, median, color=colour, lw=2.0 if measure == "RotD50" else 1.4,
                    label=f"{legend} (median)")
            ratio_ax.plot(periods, ratio, color=colour, lw=1.4, label=legend)
            rows.append((set_name, float(xi), len(members), measure, float(median[peak]),
                         float(periods[peak]), float(ratio[peak])))
        common.log_axis(ax, "x")
        common.log_axis(ax, "y")
        ax.set_xlabel("period $T$ [s]")
        ax.set_ylabel(r"$S_a(T, \xi)$ [g]")
        ax.set_title(f"{set_name}: {len(members)} pairs, $\\xi$ = {xi:g}")
        ax.legend(loc="lower left", fontsize="small")
        common.log_axis(ratio_ax, "x")
        ratio_ax.axhline(1.0, color="0.5", lw=0.6)
        ratio_ax.set_xlabel("period $T$ [s]")
        ratio_ax.set_ylabel("measure / RotD50 (median)")
    extra = ("Pseudo-accelerations of the linear oscillator (Nigam and Jennings 1969) under each "
             "component of a pair; RotD50 and RotD100: median and largest over the angles "
             "0-179 deg of the peak of the two oscillator responses combined at the angle "
             "(Boore 2010). Medians over the pairs at each period"
             + (f"; dotted: each of the {len(members)} pairs" if few else "")
             + "; bottom: the median over the pairs of each measure over the pair's RotD50.")
    common.caption_text(fig, extra)
    return common.save(fig, out_dir, name, pdf), rows


def groups(spectra):
    """(set name, record indices) in order of first appearance; records alone form one group."""
    out = {}
    for i, s in enumerate(spectra["set"]):
        out.setdefault(s or "records", []).append(i)
    return list(out.items())


def figure(spectra, set_name, members, out_dir, name, pdf):
    """One figure per damping ratio side by side; returns the path and the table rows
    (set, xi, records, median PSa at its peak, T there, 16 % and 84 % there)."""
    periods = spectra["period_s"]
    xis = spectra["xi"]
    fig, axes = plt.subplots(1, len(xis), figsize=(6.0 * len(xis) + 1.0, 5.6),
                                     layout="constrained", squeeze=False)
    rows = []
    for x, xi in enumerate(xis):
        ax = axes[0, x]
        psa = spectra["psa_g"][members, x, :]
        for k, r in enumerate(members):
            ax.plot(periods, psa[k], color="0.6", lw=0.7,
                    label="a record" if k == 0 else None)
        if len(members) >= MIN_BAND_RECORDS:
            median = np.median(psa, axis=0)
            lo, hi = np.percentile(psa, [16, 84], axis=0)
            ax.fill_between(periods, lo, hi, color="tab:blue", alpha=0.25,
                            label="16-84 % of the records")
            ax.plot(periods, median, color="tab:blue", lw=2.2, label="median")
            peak = int(np.argmax(median))
            rows.append((set_name, float(xi), len(members), float(median[peak]),
                         float(periods[peak]), float(lo[peak]), float(hi[peak])))
        else:
            rows.append((set_name, float(xi), len(members), None, None, None, None))
        common.log_axis(ax, "x")
        common.log_axis(ax, "y")
        ax.set_xlabel("period $T$ [s]")
        ax.set_ylabel(r"$S_a(T, \xi)$ [g]")
        ax.set_title(f"{set_name}: {len(members)} records, $\\xi$ = {xi:g}")
        ax.legend(loc="lower left")
    extra = ("S_a: pseudo-acceleration ω² max|u| of the linear oscillator u'' + 2ξωu' + ω²u = "
             "-a(t), ω = 2π/T, exact for a ground acceleration linear between samples "
             "(Nigam and Jennings 1969); "
             "median and 16th-84th percentiles over the records at each period"
             + ("" if len(members) >= MIN_BAND_RECORDS
                else f" (drawn from {MIN_BAND_RECORDS} records on)") + ".")
    common.caption_text(fig, extra)
    return common.save(fig, out_dir, name, pdf), rows
