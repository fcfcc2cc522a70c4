#!/usr/bin/python3
"""Fragility curves of one limit state side by side over one axis of a cube (docs/compliant.md
§5): for each panel, a combination of the other axes, the stored maximum-likelihood fits
Phi(ln(IM / theta) / beta) and the stripes' exceeded fractions, one colour per coordinate of the
compared axis (e.g. eps_N, or the joint law).

    scripts/compliant/compare_fragility.py CUBE.h5 --axis eps_N --out FIG.png \
        --panel "unseating seat_over_L=0.0005 a_deg=20" --panel "rotation a_deg=20" ...

A panel is a limit state followed by AXIS=VALUE for every other axis of its fit (the first
coordinate where an axis is left out). Reads only what the cube stores (sweeps/NAME/fragility/).
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


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("cube")
    p.add_argument("--sweep")
    p.add_argument("--axis", required=True)
    p.add_argument("--panel", action="append", required=True)
    p.add_argument("--title", default="")
    p.add_argument("--out", required=True)
    a = p.parse_args()
    f = h5py.File(a.cube, "r")
    names = list(f["sweeps"].keys())
    sweep = f["sweeps"][a.sweep or names[0]]
    order = [decode(x) for x in sweep.attrs["axis_order"]]
    fit_axes = [x for x in order if x not in ("record", "im_g", "im_mps")]
    if a.axis not in fit_axes:
        sys.exit(f"compare_fragility: --axis {a.axis}: not an axis of the fits ({fit_axes})")
    coords = {x: [decode(v) for v in sweep["axes"][x][...]] for x in fit_axes}
    units = decode(sweep.attrs.get("im_units", "g"))
    fig, axes = plt.subplots(1, len(a.panel), figsize=(4.2 * len(a.panel), 3.8), squeeze=False)
    for ax, spec in zip(axes[0], a.panel):
        words = spec.split()
        state, fixed = words[0], dict(w.split("=", 1) for w in words[1:])
        g = sweep["fragility"][state]
        for k, value in enumerate(coords[a.axis]):
            idx = []
            for x in fit_axes:
                if x == a.axis:
                    idx.append(k)
                elif x in fixed:
                    hits = [i for i, v in enumerate(coords[x])
                            if abs(float(v) - float(fixed[x])) <= 1e-9 * abs(float(v))]
                    if not hits:
                        sys.exit(f"compare_fragility: {x}={fixed[x]}: not a coordinate "
                                 f"({coords[x]})")
                    idx.append(hits[0])
                else:
                    idx.append(0)
            idx = tuple(idx)
            im = g["stripe_im"][idx]
            frac = g["stripe_exceeded"][idx] / np.maximum(g["stripe_n"][idx], 1)
            theta, beta = g["theta"][idx], g["beta"][idx]
            colour = f"C{k}"
            ax.plot(im, frac, "o", color=colour, ms=4, mfc="none")
            label = f"{a.axis} = {value:g}" if not isinstance(value, str) else value
            if np.isfinite(theta):
                x = np.geomspace(im.min() * 0.7, im.max() * 1.5, 200)
                ax.plot(x, norm.cdf(np.log(x / theta) / beta), "-", color=colour,
                        label=f"{label}: θ = {theta:.3g} {units}, β = {beta:.2f}")
            else:
                ax.plot([], [], "-", color=colour, label=f"{label}: no fit")
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
