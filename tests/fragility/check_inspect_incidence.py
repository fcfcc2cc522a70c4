"""Checks what `skewbridge inspect` prints for a final cube with an incidence_deg axis against the
cube, read with h5py: the section of every group of fits (fragility/, fragility_worst_incidence/,
stripes or IDA) with one row per limit state and combination holding the stored theta and beta
(or "no fit"), and, for a stripe sweep, the section of over_incidence/ with each limit state's
cells exceeding it at some angle and at half the angles or more, counted here with numpy on the
cells' ls_<name> (not on the stored reduction), and its largest demand. A missing section, row
or number fails.

usage: check_inspect_incidence.py FILE.h5 SWEEP INSPECT.txt
"""
import itertools
import sys

import h5py
import numpy as np


def text(v):
    return v.decode() if isinstance(v, bytes) else v


def section(lines, start):
    """The rows (4-space indented) under the first 2-space header starting with `start`."""
    for i, line in enumerate(lines):
        if line.startswith("  " + start):
            rows = []
            for row in lines[i + 1:]:
                if not row.startswith("    "):
                    break
                rows.append(row.split())
            return line, rows
    raise AssertionError("inspect prints no section '%s'" % start)


def check_fits(g, group, header_start, lines):
    f = g[group]
    _, rows = section(lines, header_start)
    ida = text(f.attrs["method"]) == "ida"
    combo_axes = [text(a) for a in f.attrs["axis_order"]]
    coords = [g["axes/" + a][()] for a in combo_axes]
    checked = 0
    for name in f.attrs["limit_states"]:
        name = text(name)
        h = f[name]
        for flat, idx in enumerate(itertools.product(*[range(len(c)) for c in coords])):
            label = ",".join("%g" % c[i] for c, i in zip(coords, idx)) or "-"
            found = [r for r in rows if r[:2] == [name, label]]
            assert len(found) == 1, "%s: %d rows for %s %s" % (group, len(found), name, label)
            row = found[0]
            at = idx if idx else 0
            theta = float(h["theta"][at])
            count = h["n_records" if ida else "n_cells"][at]
            assert row[2] == "%.0f" % count, "%s %s %s: count %s, cube %s" % (
                group, name, label, row[2], count)
            if np.isfinite(theta):
                cols = row[5:7] if ida else row[4:6]
                assert cols == ["%.6g" % theta, "%.6g" % float(h["beta"][at])], (
                    "%s %s %s: %s, cube %.6g" % (group, name, label, row, theta))
                checked += 1
            else:
                assert "no" in row and "fit:" in row, "%s %s %s: %s" % (group, name, label, row)
    return checked


def main():
    path, sweep, out = sys.argv[1:4]
    lines = open(out, encoding="utf-8").read().splitlines()
    g = h5py.File(path, "r")["sweeps/" + sweep]
    assert "over_incidence" in g and "fragility_worst_incidence" in g, "the cube lacks a group"
    n = check_fits(g, "fragility", "fragility (fragility/", lines)
    w = check_fits(g, "fragility_worst_incidence",
                   "fragility at the worst incidence angle (fragility_worst_incidence/", lines)
    header, rows = section(lines, "over the incidence angle (over_incidence/")
    angles = g["axes/incidence_deg"][()]
    assert "%d angles" % len(angles) in header, header
    axes = [text(a) for a in g.attrs["axis_order"]]
    k = axes.index("incidence_deg")
    ok = (g["done"][()] == 1) & (g["status"][()] == 0)
    names = [text(n) for n in g["fragility"].attrs["limit_states"]]
    reduced = 0
    if text(g["fragility"].attrs["method"]) != "ida":
        for name in names:
            z = np.where(ok, g["responses/ls_" + name][()], np.nan)
            d = np.where(ok, g["responses/ls_" + name + "_demand"][()], np.nan)
            some = np.max(z, axis=k)
            half = np.median(z, axis=k)
            valid = np.isfinite(some)
            found = [r for r in rows if r[0] == name]
            assert len(found) == 1, "over_incidence: %d rows for %s" % (len(found), name)
            words = " ".join(found[0])
            expect = "exceeded at some angle in %d of %d cells, at half the angles or more in %d;" % (
                int((some[valid] == 1).sum()), int(valid.sum()), int((half[valid] >= 0.5).sum()))
            assert expect in words, "%s: '%s' not in '%s'" % (name, expect, words)
            largest = np.nanmax(d)
            assert "largest demand %.6g;" % largest in words, (name, largest, words)
            reduced += 1
    print("inspect of %s: %d fits per angle, %d at the worst angle, %d limit states over the angle"
          % (sweep, n, w, reduced))


if __name__ == "__main__":
    main()
