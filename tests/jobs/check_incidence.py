#!/usr/bin/python3
"""Two cubes of one sweep that differ only in how the excitation's angle is given.

usage: check_incidence.py same A.h5 B.h5    every dataset of A is in B with the same bytes
       check_incidence.py moved A.h5 B.h5   the responses y_m and theta_m differ

The inputs' checksums (another model file), the timings and the fixed value incidence_deg are
left out; `same` needs at least one cell with impacts, so that the comparison covers pounding.
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


def main(mode, a_path, b_path):
    a, b = datasets(h5py.File(a_path, "r")), datasets(h5py.File(b_path, "r"))
    if mode == "moved":
        for r in ("y_m", "theta_m"):
            name = [n for n in a if n.endswith("/" + r)][0]
            if np.array_equal(a[name][()], b[name][()]):
                print("%s: the same in %s and %s" % (r, a_path, b_path))
                return 1
        return 0
    names = [n for n in a if not n.endswith("stats/wall_s") and "/inputs/" not in n
             and "incidence" not in n]
    bad = [n for n in names if n not in b or not same(a[n], b[n])]
    impacts = [n for n in names if n.endswith("/impacts")]
    if not impacts or not np.any(a[impacts[0]][()] > 0):
        print("no cell with impacts in %s" % a_path)
        return 1
    for n in bad:
        print("differs: %s" % n)
    print("%d datasets compared" % len(names))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))
