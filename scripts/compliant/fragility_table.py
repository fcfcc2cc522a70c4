#!/usr/bin/python3
"""The rows of a fragility table (Markdown) from one or more cubes' stored fits (docs/compliant.md
§5): per limit state, per cube, per combination of the fit axes, the cells exceeded, the median
theta, its 95 % bootstrap interval and beta. An axis along which a limit state's fits are the same
bits (theta, beta and the cells exceeded) is printed once as "any", with the interval of its first
coordinate (rotation and joint closing do not depend on the seat; each combination's bootstrap
draws its own resamples). Rows are ordered by the axes every cube has, then by cube, so that the
cubes' rows of one combination stand together.

    scripts/compliant/fragility_table.py "pilot, rigid=pilot-rigid.h5" \\
        "pilot, compliant=pilot-compliant.h5" [--state unseating --state rotation] \\
        [--seat-length-m 89.14] [--skip-none]

A cube is LABEL=FILE; its fits are those of sweeps/NAME/fragility/ (the first sweep). The columns
are the limit state, the label and every fit axis of any cube ("–" where a cube lacks it); with
--seat-length-m a seat_over_L column is printed in mm as well. A fit that does not exist names
why in the theta column (no exceedance, or the stripes separating at one level, where the maximum
of the likelihood is a step: beta tends to 0 and the median is that level).
"""
import argparse
import itertools
import re
import sys

import h5py
import numpy as np


def decode(v):
    return v.decode() if isinstance(v, bytes) else v


def number(x):
    """A coordinate or a fit's number, short."""
    return f"{x:.3g}" if isinstance(x, (float, np.floating)) else str(x)


def open_cube(spec):
    """(label, sweep group, fit axes, their coordinates) of LABEL=FILE."""
    if "=" not in spec:
        sys.exit(f"fragility_table: {spec}: expected LABEL=FILE")
    label, path = spec.rsplit("=", 1)
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        sys.exit(f"fragility_table: {path}: {e}")
    sweep = f["sweeps"][list(f["sweeps"].keys())[0]]
    if "fragility" not in sweep:
        sys.exit(f"fragility_table: {path}: no fragility/ (not a final cube with limit states)")
    order = [decode(x) for x in sweep["fragility"].attrs["axis_order"]]
    coords = {x: [decode(v) for v in sweep["axes"][x][...]] for x in order}
    return label, sweep, order, coords


def same_along(g, axis):
    """Whether every dataset of a fit group is the same bits along one of its fit axes."""
    for name in ("theta", "beta", "n_exceeded"):
        a = g[name][...]
        if not all(np.array_equal(np.take(a, 0, axis), np.take(a, k, axis), equal_nan=True)
                   for k in range(1, a.shape[axis])):
            return False
    return True


def theta_text(g, idx, flat):
    """The median, or why there is none."""
    theta = g["theta"][idx]
    if np.isfinite(theta):
        return number(theta)
    reason = decode(g["reason"][flat])
    m = re.search(r"separate at IM = ([0-9.eE+-]+)", reason)
    if m:
        return f"– (steps at {float(m.group(1)):.3g})"
    return "–" if reason.startswith("no exceedance") or not reason else f"– ({reason})"


def expand_any(rows, shared, columns, seat_length_m):
    """The rows (key, exceeded, cells) with each row that is "any" (key -inf) along a shared axis
    where other rows have coordinates repeated at each of those coordinates, its cell the
    coordinate: a fit the same along an axis belongs to every combination of it."""
    out = list(rows)
    for i, x in enumerate(shared):
        values = sorted({k[i] for k, _, _ in out if k[i] != -np.inf})
        if not values:
            continue
        expanded = []
        for key, n, row in out:
            if key[i] != -np.inf:
                expanded.append((key, n, row))
                continue
            for v in values:
                cells = list(row)
                text = number(v)
                if x == "seat_over_L" and seat_length_m > 0:
                    text += f" ({1000 * v * seat_length_m:.0f} mm)"
                cells[2 + columns.index(x)] = text
                expanded.append((key[:i] + (v,) + key[i + 1:], n, cells))
        out = expanded
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("cubes", nargs="+", metavar="LABEL=FILE")
    p.add_argument("--state", action="append", help="limit states (default: every one stored)")
    p.add_argument("--skip-none", action="store_true",
                   help="leave out the combinations of the shared axes where no cube has an "
                   "exceeded cell")
    p.add_argument("--seat-length-m", type=float, default=0.0,
                   help="the deck length L: print seat_over_L in mm too")
    a = p.parse_args()
    cubes = [open_cube(c) for c in a.cubes]
    columns = []
    for _, _, order, _ in cubes:
        columns += [x for x in order if x not in columns]
    states = a.state or [decode(s) for s in cubes[0][1]["fragility"].attrs["limit_states"]]
    head = ["limit state", "cube"] + columns + ["cells exceeded", "θ", "θ 95 % (bootstrap)", "β"]
    shared = [x for x in columns if all(x in order for _, _, order, _ in cubes)]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for state in states:
        rows = []
        for c, (label, sweep, order, coords) in enumerate(cubes):
            if state not in sweep["fragility"]:
                sys.exit(f"fragility_table: {label}: no limit state {state}")
            g = sweep["fragility"][state]
            shape = g["theta"].shape
            any_axes = {x for i, x in enumerate(order) if shape[i] > 1 and same_along(g, i)}
            ranges = [range(1) if x in any_axes else range(n) for x, n in zip(order, shape)]
            for idx in itertools.product(*ranges):
                key = tuple(-np.inf if x in any_axes else float(coords[x][idx[order.index(x)]])
                            for x in shared) + (c, idx)
                flat = int(np.ravel_multi_index(idx, shape))
                cells = []
                for x in columns:
                    if x not in order:
                        cells.append("–")
                    elif x in any_axes:
                        cells.append("any")
                    else:
                        v = coords[x][idx[order.index(x)]]
                        text = number(v)
                        if x == "seat_over_L" and a.seat_length_m > 0:
                            text += f" ({1000 * float(v) * a.seat_length_m:.0f} mm)"
                        cells.append(text)
                lo, hi = g["boot_theta_lo"][idx], g["boot_theta_hi"][idx]
                beta = g["beta"][idx]
                row = [state, label] + cells + [
                    f"{int(g['n_exceeded'][idx])} / {int(g['n_cells'][idx])}",
                    theta_text(g, idx, flat),
                    f"{number(lo)}-{number(hi)}" if np.isfinite(lo) and np.isfinite(hi) else "",
                    f"{beta:.2f}" if np.isfinite(beta) else ""]
                rows.append((key, int(g["n_exceeded"][idx]), row))
        # A row that is "any" along a shared axis another cube's rows have coordinates of stands in
        # each of their combinations, with the coordinate (its fits are the same bits there).
        rows = expand_any(rows, shared, columns, a.seat_length_m)
        exceeded = {}
        for key, n, _ in rows:
            exceeded[key[:len(shared)]] = exceeded.get(key[:len(shared)], 0) + n
        for key, _, row in sorted(rows, key=lambda r: r[0]):
            if not a.skip_none or exceeded[key[:len(shared)]] > 0:
                print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()
