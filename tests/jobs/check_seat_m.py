#!/usr/bin/python3
"""Two cubes of one sweep, one with axis A and one with axis B in its place: every dataset
(responses, margins, limit-state outcomes, fits) is the same byte for byte, except the two axes
themselves, the inputs' checksums and the timings; at least one unseating margin and outcome is
compared.

usage: check_seat_m.py A.h5 B.h5 AXIS_A AXIS_B
"""
import sys

import h5py
import numpy as np


def datasets(f):
    out = {}
    f.visititems(lambda n, o: out.__setitem__(n, o) if isinstance(o, h5py.Dataset) else None)
    return out


def same(x, y):
    """Same dtype, shape and bytes (strings by their text)."""
    if x.dtype != y.dtype or x.shape != y.shape:
        return False
    u, v = np.asarray(x[()]), np.asarray(y[()])
    if u.dtype == object:
        return u.tolist() == v.tolist()
    return u.tobytes() == v.tobytes()


def main(a_path, b_path, axis_a, axis_b):
    a, b = datasets(h5py.File(a_path, "r")), datasets(h5py.File(b_path, "r"))
    skip = ("/" + axis_a, "/" + axis_b, "stats/wall_s")
    names = [n for n in a if not n.endswith(skip) and "/inputs/" not in n]
    bad = [n for n in names if n not in b or not same(a[n], b[n])]
    margins = [n for n in names if "margin_m" in n]
    outcomes = [n for n in names if "unseating" in n]
    exceeded = sum(int(np.sum(a[n][()] == 1)) for n in names if n.endswith("/ls_unseating"))
    if not margins or not outcomes or exceeded == 0:
        print("no unseating margin, outcome or unseated cell in %s" % a_path)
        return 1
    for n in bad:
        print("differs: %s" % n)
    print("%d datasets compared (%d margins, %d unseating), %d cells exceeded unseating"
          % (len(names), len(margins), len(outcomes), exceeded))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:5]))
