#!/usr/bin/python3
"""Checks the scale-factor table of `skewbridge sweep --dry-run` against a cube of the same
specification and against `skewbridge records spectrum`.

usage: check_dry_run_scales.py DRY_RUN.txt CUBE.h5 SPECTRUM.csv

DRY_RUN.txt is the dry run's standard output, CUBE.h5 the cube the sweep wrote (axes record,
im_g, k_factor), SPECTRUM.csv the records' spectra at the cells' T1 (xi = 0.05). For every group
of the dry run (one per T1), each table row's own Sa(T1) must equal the cube's im_unscaled and
the spectrum's PSa_g, each factor the cube's scale_factor (to the 4 printed digits), each '*' a
cell the cube flags scaled_too_far; each stripe line's min / median / max / count must equal
numpy's over the cube's records; the closing count must equal the cube's.
"""
import csv
import re
import sys

import h5py
import numpy as np


def close(printed, exact, digits, what):
    # A number printed with `digits` significant digits lies within half a unit of the last.
    tol = 0.5 * 10.0 ** (np.floor(np.log10(abs(exact))) - digits + 1) * 1.0000001
    if not abs(printed - exact) <= tol:
        sys.exit(f"check_dry_run_scales: {what}: printed {printed}, expected {exact}")


def main():
    text = open(sys.argv[1]).read().splitlines()
    with h5py.File(sys.argv[2], "r") as f:
        g = next(iter(f["sweeps"].values()))
        labels = list(g["axes/record"].asstr()[()])
        stripes, kf = g["axes/im_g"][()], g["axes/k_factor"][()]
        factor = g["responses/scale_factor"][()]
        own = g["responses/im_unscaled"][()]
        t1 = g["responses/T1"][()]
        far = g["responses/scaled_too_far"][()]
        max_scale = float(g.attrs["max_scale"])
    spectrum = {}
    with open(sys.argv[3]) as f:
        for row in csv.DictReader(f):
            spectrum[(row["label"], float(row["T_s"]))] = float(row["PSa_g"])

    start = text.index(next(t for t in text if t.startswith("scale factors (records.scale_to)")))
    assert f"max_scale = {max_scale:g}" in text[start], text[start]
    groups = 0
    k = None
    i = start + 1
    while not text[i].startswith("responses:"):
        line = text[i]
        m = re.match(r"  T1 = (\S+) s for k_factor = (\S+): (\d+) record\(s\) x (\d+) stripe\(s\), "
                     r"(\d+) of (\d+) beyond max_scale$", line)
        if m:
            groups += 1
            k = int(np.flatnonzero(kf == float(m.group(2)))[0])
            close(float(m.group(1)), t1[0, 0, k], 5, "T1")
            assert int(m.group(3)) == len(labels) and int(m.group(4)) == len(stripes), line
            assert int(m.group(5)) == int(far[:, :, k].sum()), line
            i += 2  # the stripe lines' heading
            for j, stripe in enumerate(stripes):
                v = text[i].split()
                close(float(v[0]), stripe, 4, "stripe")
                col = factor[:, j, k]
                close(float(v[1]), col.min(), 4, f"min at {stripe}")
                close(float(v[2]), np.median(col), 4, f"median at {stripe}")
                close(float(v[3]), col.max(), 4, f"max at {stripe}")
                assert f"{int(far[:, j, k].sum())} of {len(labels)}" == " ".join(v[4:7]), text[i]
                i += 1
            assert text[i].split()[:2] == ["record", "own"], text[i]
            i += 1
            for r, label in enumerate(labels):
                v = text[i].split()
                assert v[0] == label, (v[0], label)
                close(float(v[1]), own[r, 0, k], 5, f"{label} own Sa")
                close(float(v[1]), spectrum[(label, t1[r, 0, k])], 5, f"{label} Sa spectrum")
                for j in range(len(stripes)):
                    cellv = v[2 + j]
                    close(float(cellv.rstrip("*")), factor[r, j, k], 4, f"{label} factor")
                    assert cellv.endswith("*") == bool(far[r, j, k]), (label, j, cellv)
                    assert (factor[r, j, k] > max_scale) == bool(far[r, j, k])
                i += 1
            continue
        m = re.match(r"  (\d+) of (\d+) cells beyond max_scale = \S+ \(largest factor (\S+)\)$",
                     line)
        if m:
            assert int(m.group(1)) == int(far.sum()) and int(m.group(2)) == far.size, line
            close(float(m.group(3)), factor.max(), 4, "largest factor")
        i += 1
    assert groups == len(kf), f"{groups} groups for {len(kf)} values of k_factor"
    print(f"check_dry_run_scales: ok ({groups} groups, {factor.size} factors)")


if __name__ == "__main__":
    main()
