#!/usr/bin/python3
"""The approach speeds of a rigid study's impacts: every cell of a model-file cube is run again
(`skewbridge run --from-cube`, the sweep's own cell, bit for bit) and the normal relative speed
before each impact (`events/gamma_N_before`, docs/run-output.md) is collected. The speeds are
what a compliant abutment would be struck with, so they choose the speeds at which
`skewbridge restitution` turns a backfill into an equivalent eps_N (docs/compliant.md §5).

    scripts/compliant/approach_speeds.py build/release/skewbridge CUBE.h5 --out speeds.csv \
        [--sweep NAME] [--fix AXIS=VALUE ...] [--jobs 2]

Run it from the folder the sweep ran in (the cube's specification names its files relative to
it). Axes other than record, im_g and a_deg are fixed at their first coordinate unless --fix
names one (a seat width changes no run). One row per cell: the record, the stripe, the skew,
the number of impacts, the speed of the first impact (its fastest contact) and the fastest and
the median of all impact rows, and every impact row's speed.
"""
import argparse
import concurrent.futures
import csv
import itertools
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

KEEP = ("record", "im_g", "a_deg")


def decode(v):
    return v.decode() if isinstance(v, bytes) else v


def cells_to_run(group, fixed):
    """(index, coordinates) of the cells to run: every coordinate of the kept axes, the others
    at their fixed or first coordinate."""
    order = [decode(a) for a in group.attrs["axis_order"]]
    coords = {a: [decode(v) for v in group["axes"][a][...]] for a in order}
    choice = []
    for a in order:
        values = coords[a]
        if a in KEEP:
            choice.append(list(range(len(values))))
        elif a in fixed:
            match = [i for i, v in enumerate(values)
                     if (str(v) == fixed[a] or
                         (not isinstance(v, str) and abs(float(v) - float(fixed[a])) <=
                          1e-9 * abs(float(v))))]
            if not match:
                sys.exit(f"approach_speeds: --fix {a}={fixed[a]}: not a coordinate of {a} "
                         f"(allowed: {values})")
            choice.append(match[:1])
        else:
            choice.append([0])
    shape = [len(coords[a]) for a in order]
    for idx in itertools.product(*choice):
        flat = int(np.ravel_multi_index(idx, shape))
        yield flat, {a: coords[a][i] for a, i in zip(order, idx)}


def run_cell(exe, cube, sweep, index, folder):
    out = os.path.join(folder, f"cell_{index}.h5")
    cmd = [exe, "run", "--from-cube", cube, "--cell-index", str(index), "--out", out,
           "--output-interval", "0"]
    if sweep:
        cmd += ["--sweep", sweep]
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode not in (0, 3):
        raise RuntimeError(f"cell {index}: {' '.join(cmd)}: {done.stderr.strip()}")
    with h5py.File(out, "r") as f:
        ev = f["events"]
        kind = ev["kind"][...]
        t = ev["t_s"][...][kind == 0]
        v = np.abs(ev["gamma_N_before"][...][kind == 0])
    os.remove(out)
    first = float(v[t == t.min()].max()) if v.size else float("nan")
    return index, t, v, first


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("exe")
    p.add_argument("cube")
    p.add_argument("--out", required=True)
    p.add_argument("--sweep")
    p.add_argument("--fix", action="append", default=[], metavar="AXIS=VALUE")
    p.add_argument("--jobs", type=int, default=2)
    a = p.parse_args()
    fixed = dict(f.split("=", 1) for f in a.fix)
    with h5py.File(a.cube, "r") as f:
        names = list(f["sweeps"].keys())
        sweep = a.sweep or (names[0] if len(names) == 1 else None)
        if sweep is None:
            sys.exit(f"approach_speeds: the cube holds {names}: give --sweep")
        cells = list(cells_to_run(f["sweeps"][sweep], fixed))
    rows = {}
    with tempfile.TemporaryDirectory() as folder, \
            concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        jobs = [pool.submit(run_cell, a.exe, a.cube, a.sweep, i, folder) for i, _ in cells]
        for job in concurrent.futures.as_completed(jobs):
            index, t, v, first = job.result()
            rows[index] = (t, v, first)
    tmp = a.out + ".partial"
    with open(tmp, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["cell", "record", "im_g", "a_deg", "impacts", "first_speed_mps",
                    "max_speed_mps", "median_speed_mps", "speeds_mps"])
        for index, c in cells:
            t, v, first = rows[index]
            w.writerow([index, c.get("record", ""), c.get("im_g", ""), c.get("a_deg", ""),
                        len(np.unique(t)), f"{first:.9g}",
                        f"{v.max():.9g}" if v.size else "nan",
                        f"{np.median(v):.9g}" if v.size else "nan",
                        ";".join(f"{x:.6g}" for x in v)])
    os.replace(tmp, a.out)
    firsts = np.array([rows[i][2] for i, _ in cells])
    hit = firsts[np.isfinite(firsts)]
    print(f"{len(cells)} cells run, {hit.size} with impacts; first-impact speed (m/s): "
          + (f"16/50/84 % {np.percentile(hit, 16):.3g} / {np.median(hit):.3g} / "
             f"{np.percentile(hit, 84):.3g}, range {hit.min():.3g} - {hit.max():.3g}"
             if hit.size else "none"))


if __name__ == "__main__":
    main()
