#!/usr/bin/python3
"""Checks the cubes of stripes_test.sh with h5py, against quantities computed here.

usage: check_stripes.py ONE_RANK.h5 TWO_RANKS.h5 RECORDS_DIR FLAGGED_IN_SUMMARY

- T1 of each cell is 2 pi / (10 sqrt(k_factor)) s (the deck's w0 = 10 rad/s, W0 = 12 rad/s);
- im_unscaled is Sa(T1, 0.05) of the record in g, by scipy.signal.lsim (exact first-order hold;
  no code shared with the tool's recurrence), to 1e-6;
- im equals the stripe (axes/im_g) and scale_factor x im_unscaled, pga the record's PGA x factor;
- scaled_too_far is 1 exactly where scale_factor > max_scale, and its count is the cube's
  scaled_too_far_count and the summary's;
- the record table holds CAV (the integral of |a|, by numpy here) and NaN Sa(T1) (two T1);
- one and two ranks give the same cells.
"""
import os
import re
import sys

import h5py
import numpy as np
from scipy import signal

G = 9.80665


def read_at2(path):
    with open(path) as f:
        lines = f.read().splitlines()
    numbers = re.findall(r"[-+]?\d*\.?\d+(?:[eE][-+]?\d+)?", lines[3])
    npts, dt = int(float(numbers[0])), float(numbers[1])
    return np.array(" ".join(lines[4:]).split(), dtype=float)[:npts] * G, dt


def sa(acc, dt, period, xi=0.05):
    w = 2.0 * np.pi / period
    system = signal.StateSpace([[0.0, 1.0], [-w * w, -2.0 * xi * w]], [[0.0], [-1.0]],
                               [[1.0, 0.0]], [[0.0]])
    _, u, _ = signal.lsim(system, acc, dt * np.arange(acc.size), interp=True)
    return w * w * np.max(np.abs(u))


def cav(acc, dt):
    total = 0.0
    for a0, a1 in zip(acc[:-1], acc[1:]):
        if a0 * a1 < 0:
            total += dt * (a0 * a0 + a1 * a1) / (2 * (abs(a0) + abs(a1)))
        else:
            total += dt * abs(a0 + a1) / 2
    return total


def close(a, b, rel, what):
    if not abs(a - b) <= rel * max(abs(a), abs(b)):
        sys.exit(f"check_stripes: {what}: {a} against {b}")


def main():
    one, two, folder, flagged = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
    with h5py.File(one, "r") as f, h5py.File(two, "r") as h:
        g, g2 = f["sweeps/stripes"], h["sweeps/stripes"]
        assert list(g.attrs["axis_order"]) == ["record", "im_g", "k_factor"], g.attrs["axis_order"]
        assert g.attrs["im_measure"] == "Sa" and g.attrs["im_units"] == "g"
        assert g.attrs["im_scaled"] == 1 and g.attrs["max_scale"] == 1.5
        labels = g["axes/record"].asstr()[()]
        stripes, kf = g["axes/im_g"][()], g["axes/k_factor"][()]
        r = {k: g["responses/" + k][()] for k in ("T1", "im", "im_unscaled", "scale_factor",
                                                  "scaled_too_far", "pga")}
        for k, v in r.items():
            assert np.array_equal(v, g2["responses/" + k][()], equal_nan=True), k
        assert np.all(g["status"][()] == 0)
        for i, label in enumerate(labels):
            acc, dt = read_at2(os.path.join(folder, label))
            rec = g["records"]
            close(rec["CAV_mps"][i], cav(acc, dt), 1e-9, f"{label} CAV")
            assert np.isnan(rec["Sa_T1_mps2"][i]), "two T1: Sa(T1) must be NaN in the table"
            for k, factor in enumerate(kf):
                t1 = 2 * np.pi / (10 * np.sqrt(factor))
                own = sa(acc, dt, t1) / G
                for j, stripe in enumerate(stripes):
                    close(r["T1"][i, j, k], t1, 1e-12, "T1")
                    close(r["im_unscaled"][i, j, k], own, 1e-6, f"{label} Sa(T1 = {t1:.4f})")
                    close(r["im"][i, j, k], stripe, 1e-12, "im = stripe")
                    close(r["scale_factor"][i, j, k] * r["im_unscaled"][i, j, k],
                          r["im"][i, j, k], 1e-12, "factor x own")
                    close(r["pga"][i, j, k], r["scale_factor"][i, j, k] * np.max(np.abs(acc)),
                          1e-12, "pga")
        expect = (r["scale_factor"] > 1.5).astype(float)
        assert np.array_equal(r["scaled_too_far"], expect), (r["scaled_too_far"], expect)
        count = int(expect.sum())
        assert 0 < count < expect.size, count
        assert g.attrs["scaled_too_far_count"] == count == flagged, (count, flagged)
    print(f"check_stripes: ok ({count} of {expect.size} cells flagged)")


if __name__ == "__main__":
    main()
