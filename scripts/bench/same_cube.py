#!/usr/bin/python3
"""Compares two sweep cubes dataset by dataset, byte for byte.

usage: same_cube.py A.h5 B.h5

Every dataset of A must be in B with the same dtype, shape and bytes (NaNs compare by their
bits), except the timing datasets (stats/wall_s), which differ from run to run. Attributes are
not compared: they hold creation times, host names and run provenance. Exit status 0 when the
cubes are the same, 1 with one line per difference otherwise, 2 for an unreadable file.
"""
import sys

import h5py
import numpy as np

TIMING = ("stats/wall_s",)


def datasets(f):
    out = {}
    f.visititems(lambda name, obj: out.__setitem__(name, obj) if isinstance(obj, h5py.Dataset) else None)
    return out


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    try:
        a, b = h5py.File(argv[1], "r"), h5py.File(argv[2], "r")
    except OSError as e:
        print(f"same_cube: error: {e}", file=sys.stderr)
        return 2
    da, db = datasets(a), datasets(b)
    bad = []
    for name in sorted(set(da) | set(db)):
        if name.endswith(TIMING):
            continue
        if name not in da or name not in db:
            bad.append(f"{name}: only in {'A' if name in da else 'B'}")
            continue
        x, y = da[name][()], db[name][()]
        if x.dtype != y.dtype or np.shape(x) != np.shape(y):
            bad.append(f"{name}: dtype/shape {x.dtype}{np.shape(x)} vs {y.dtype}{np.shape(y)}")
        elif x.dtype.kind in "fiub" and x.tobytes() != y.tobytes():
            bad.append(f"{name}: {int(np.sum(x.view(np.uint8) != y.view(np.uint8)))} bytes differ")
        elif x.dtype.kind not in "fiub" and not np.array_equal(x, y):
            bad.append(f"{name}: values differ")
    for line in bad:
        print(line)
    if not bad:
        print(f"same: {len(da)} datasets (timings excluded)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
