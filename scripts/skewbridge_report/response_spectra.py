"""Response spectra files (`skewbridge records spectrum --out FILE.h5`, docs/hdf5-layout.md
"Response spectra"): one log-log figure of PSa against T per record set and damping ratio, the
records of the set in thin lines with their median and 16-84 % band."""
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
        return {"path": path, "label": _texts(g["label"][()]), "set": _texts(g["set"][()]),
                "period_s": g["period_s"][()], "xi": g["xi"][()], "psa_g": g["PSa_mps2"][()] / G,
                "command": str(g.attrs.get("command", ""))}


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
