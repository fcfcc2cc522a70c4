#!/usr/bin/python3
"""The response spectra of `skewbridge records spectrum` against an independent solution.

usage: spectrum_check.py SKEWBRIDGE RECORDS_DIR WORK_DIR [REPORT]

The oracle shares no code with the recurrence of records/measures.cpp [Nigam and Jennings 1969]:
the two real PEER records are read here from their text, and the oscillator
u'' + 2 xi w u' + w^2 u = -a(t) is solved by scipy.signal.lsim with interp=True, the exact
discretisation of a state-space system under first-order-hold (piecewise-linear) input by the
matrix exponential of an augmented matrix. Both are exact for linear-between-samples input, so
Sd, PSv = w Sd and PSa = w^2 Sd must agree to 1e-6 relative (they do to about 1e-12).
"""
import os
import re
import subprocess
import sys

import h5py
import numpy as np
from scipy import signal

G = 9.80665
RECORDS = ["NIS090.AT2", "RSN763_LOMAP_GIL067.AT2"]
PERIODS = "0.02,0.05,0.1,0.2,0.3,0.5,0.75,1,1.5,2,3,5,10"
XI = [0.0, 0.02, 0.05, 0.2]
TOLERANCE = 1e-6


def read_at2(path):
    """Samples (m/s^2) and dt (s) of a PEER .AT2 file: 3 header lines, NPTS and DT, values in g."""
    with open(path) as f:
        lines = f.read().splitlines()
    numbers = re.findall(r"[-+]?\d*\.?\d+(?:[eE][-+]?\d+)?", lines[3])
    npts, dt = int(float(numbers[0])), float(numbers[1])
    values = np.array(" ".join(lines[4:]).split(), dtype=float)[:npts]
    assert values.size == npts, path
    return values * G, dt


def oscillator_peak(acc, dt, period, xi):
    w = 2.0 * np.pi / period
    system = signal.StateSpace([[0.0, 1.0], [-w * w, -2.0 * xi * w]], [[0.0], [-1.0]],
                               [[1.0, 0.0]], [[0.0]])
    t = dt * np.arange(acc.size)
    _, u, _ = signal.lsim(system, acc, t, interp=True)
    return np.max(np.abs(u))


def main():
    skewbridge, folder, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    out = os.path.join(work, "spectra.h5")
    paths = [os.path.join(folder, name) for name in RECORDS]
    subprocess.run([skewbridge, "records", "spectrum", *paths, "--periods", PERIODS, "--xi",
                    ",".join(str(x) for x in XI), "--out", out], check=True)
    worst = 0.0
    with h5py.File(out, "r") as f:
        g = f["spectra"]
        labels = [s.decode() if isinstance(s, bytes) else s for s in g["label"][()]]
        assert labels == RECORDS, labels
        periods = g["period_s"][()]
        xis = g["xi"][()]
        assert np.allclose(xis, XI), xis
        sd, psv, psa = g["Sd_m"][()], g["PSv_mps"][()], g["PSa_mps2"][()]
        assert sd.shape == (len(RECORDS), len(XI), periods.size), sd.shape
        for r, name in enumerate(RECORDS):
            acc, dt = read_at2(paths[r])
            assert abs(g["pga_mps2"][r] - np.max(np.abs(acc))) <= 1e-12 * np.max(np.abs(acc))
            for x, xi in enumerate(xis):
                for p, period in enumerate(periods):
                    w = 2.0 * np.pi / period
                    peak = oscillator_peak(acc, dt, period, xi)
                    for value, oracle in ((sd[r, x, p], peak), (psv[r, x, p], w * peak),
                                          (psa[r, x, p], w * w * peak)):
                        error = abs(value - oracle) / oracle
                        worst = max(worst, error)
                        if error > TOLERANCE:
                            print(f"{name} xi={xi} T={period}: {value} against {oracle} "
                                  f"(relative {error:.2e})")
                            return 1
    if len(sys.argv) > 4:
        # scripts/report draws the file: one figure, and a table row per damping ratio saying
        # that two records get no median (drawn from three on).
        report = os.path.join(work, "report")
        subprocess.run(["/usr/bin/python3", sys.argv[4], "--spectra", out, "--out", report],
                       check=True)
        assert os.path.getsize(os.path.join(report, "response_spectra_spectra_records.png")) > 0
        with open(os.path.join(report, "summary.md"), encoding="utf-8") as f:
            summary = f.read()
        for xi in XI:
            assert f"| records | {xi:g} | 2 | – |" in summary, summary
    print(f"{len(RECORDS)} records x {len(XI)} damping ratios x {periods.size} periods: "
          f"largest relative difference {worst:.2e} (tolerance {TOLERANCE:g})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
