#!/usr/bin/python3
"""Fragility curves of one limit state side by side over one axis of a cube, and against further
cubes of the same records and stripes (docs/compliant.md §5): for each panel, a combination of the
other axes, the stored maximum-likelihood fits Phi(ln(IM / theta) / beta) and the stripes' exceeded
fractions, one colour per coordinate of the compared axis (e.g. eps_N) and one per further cube
(e.g. the compliant law, with its keys intact or absent), each with its own line style (dashed,
dotted, ...) and marker.

    scripts/compliant/compare_fragility.py CUBE.h5 --axis eps_N --out FIG.png \
        --panel "unseating seat_over_L=0.0005 a_deg=20" --panel "rotation a_deg=20" ... \
        [--with "compliant=OTHER.h5" ...] [--values 0.38 0.5] [--columns N]

A panel is a limit state followed by AXIS=VALUE for every other axis of its fit (the first
coordinate where an axis is left out). A further cube (--with LABEL=FILE) is read at the same
coordinates: the compared axis and every axis it lacks are ignored for it, an axis only it has
takes its first coordinate unless the panel names it. Reads only what the cubes store
(sweeps/NAME/fragility/).
"""
import argparse
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from scipy.stats import norm  # noqa: E402


def decode(v):
    return v.decode() if isinstance(v, bytes) else v


def open_sweep(path, name=None):
    """The sweep group of a cube (the named one, else the first)."""
    f = h5py.File(path, "r")
    names = list(f["sweeps"].keys())
    return f["sweeps"][name or names[0]]


def fit_axes_of(sweep):
    """The axes of a sweep's fits: every axis but the record and the stripes."""
    order = [decode(x) for x in sweep.attrs["axis_order"]]
    return [x for x in order if x not in ("record", "im_g", "im_mps")]


def coordinates(sweep, axes):
    """The coordinates of the named axes of a sweep, as numbers or strings."""
    return {x: [decode(v) for v in sweep["axes"][x][...]] for x in axes}


def index_of(sweep, axes, coords, fixed, free=None, k=None, where=""):
    """The fit index of a panel: the fixed coordinates, k on the free axis, else the first."""
    idx = []
    for x in axes:
        if x == free:
            idx.append(k)
        elif x in fixed:
            hits = [i for i, v in enumerate(coords[x])
                    if abs(float(v) - float(fixed[x])) <= 1e-9 * abs(float(v))]
            if not hits:
                sys.exit(f"compare_fragility: {where}{x}={fixed[x]}: not a coordinate "
                         f"({coords[x]})")
            idx.append(hits[0])
        else:
            idx.append(0)
    return tuple(idx)


# The further cubes' line styles and markers, one pair per cube (two cubes whose fractions
# coincide stay apart: a square around a triangle).
FURTHER = [("--", "s"), (":", "^"), ("-.", "D"), ((0, (5, 1, 1, 1)), "v")]


def draw(ax, g, idx, colour, label, units, style="-", marker="o"):
    """One curve: the stripes' exceeded fractions and the fit at one index of a fragility group."""
    im = g["stripe_im"][idx]
    frac = g["stripe_exceeded"][idx] / np.maximum(g["stripe_n"][idx], 1)
    theta, beta = g["theta"][idx], g["beta"][idx]
    ax.plot(im, frac, marker, color=colour, ms=4, mfc="none")
    if np.isfinite(theta):
        x = np.geomspace(im.min() * 0.7, im.max() * 1.5, 200)
        ax.plot(x, norm.cdf(np.log(x / theta) / beta), style, color=colour,
                label=f"{label}: θ = {theta:.3g} {units}, β = {beta:.2f}")
    else:
        ax.plot(im, frac, style, color=colour, lw=0.8, label=f"{label}: no fit")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("cube")
    p.add_argument("--sweep")
    p.add_argument("--axis", required=True)
    p.add_argument("--panel", action="append", required=True)
    p.add_argument("--with", dest="others", action="append", default=[],
                   metavar="LABEL=CUBE", help="a further cube drawn beside the axis's curves")
    p.add_argument("--values", type=float, nargs="+",
                   help="draw only these coordinates of the compared axis (default: all)")
    p.add_argument("--name", default="", help="a prefix of the main cube's labels (e.g. rigid)")
    p.add_argument("--columns", type=int, default=0, help="panels per row (default: all in one)")
    p.add_argument("--title", default="")
    p.add_argument("--out", required=True)
    a = p.parse_args()
    sweep = open_sweep(a.cube, a.sweep)
    fit_axes = fit_axes_of(sweep)
    if a.axis not in fit_axes:
        sys.exit(f"compare_fragility: --axis {a.axis}: not an axis of the fits ({fit_axes})")
    coords = coordinates(sweep, fit_axes)
    others = []
    for spec in a.others:
        if "=" not in spec:
            sys.exit(f"compare_fragility: --with {spec}: expected LABEL=CUBE")
        label, path = spec.split("=", 1)
        o = open_sweep(path)
        axes = fit_axes_of(o)
        if not np.allclose(o["axes"]["im_g"][...], sweep["axes"]["im_g"][...], rtol=1e-12):
            sys.exit(f"compare_fragility: --with {spec}: its stripes differ from {a.cube}'s")
        others.append((label, path, o, axes, coordinates(o, axes)))
    units = decode(sweep.attrs.get("im_units", "g"))
    cols = a.columns if a.columns > 0 else len(a.panel)
    rows = -(-len(a.panel) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.8 * rows), squeeze=False)
    for ax in axes.flat[len(a.panel):]:
        ax.set_visible(False)
    for ax, spec in zip(axes.flat, a.panel):
        words = spec.split()
        state, fixed = words[0], dict(w.split("=", 1) for w in words[1:])
        g = sweep["fragility"][state]
        for k, value in enumerate(coords[a.axis]):
            if a.values and not any(abs(float(value) - v) <= 1e-9 * abs(v) for v in a.values):
                continue
            idx = index_of(sweep, fit_axes, coords, fixed, a.axis, k)
            label = f"{a.axis} = {value:g}" if not isinstance(value, str) else value
            label = f"{a.name}, {label}" if a.name else label
            draw(ax, g, idx, f"C{k}", label, units)
        for j, (label, path, o, o_axes, o_coords) in enumerate(others):
            o_fixed = {x: v for x, v in fixed.items() if x in o_axes}
            idx = index_of(o, o_axes, o_coords, o_fixed, where=f"{path}: ")
            style, marker = FURTHER[j % len(FURTHER)]
            draw(ax, o["fragility"][state], idx, f"C{len(coords[a.axis]) + j}", label, units,
                 style, marker)
        ax.set_xscale("log")
        ax.set_ylim(-0.03, 1.03)
        ax.set_xlabel(f"{decode(sweep.attrs.get('im_description', 'IM')).split(':')[0]} [{units}]",
                      fontsize=8)
        ax.set_ylabel("P(exceeded | IM)")
        ax.set_title(spec, fontsize=9)
        ax.grid(True, which="both", lw=0.3)
        ax.legend(fontsize=7, loc="upper left")
    if a.title:
        fig.suptitle(a.title, fontsize=10)
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)

if __name__ == "__main__":
    main()
