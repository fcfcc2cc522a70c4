#!/usr/bin/python3
"""Every documented axis of every family sweeps. The parameters each family takes are read from
docs/sweep-format.md (the family table, and the key table of the model-file family), so an axis
documented later without a case here fails this test. For each (family, key) a two-value axis
is swept with the real program: exit 0, a complete cube with the axis's coordinates, every cell
done with status ok, xarray opening the sweep (axes and responses side by side, a response
named like an axis as response_<name>); the model-file excitation axes also move the stored
scales as their definitions say (w_g = the axis, w_g = 2 pi / T_g, a_g proportional to scale).

usage: every_axis_test.py SKEWBRIDGE DOCS_SWEEP_FORMAT_MD WORK_DIR"""
import math
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np
import xarray as xr

exe, docs, work = sys.argv[1:4]

# Two coordinates of each parameter (inside the documented ranges).
VALUES = {
    "record": ["r1.txt", "r2.txt"], "pulse": ["cosine", "sine"], "spans": [1, 2],
    "a_g_g": [0.3, 0.5], "w_g": [10.0, 12.0], "T_g": [0.5, 0.7], "scale": [1.0, 2.0],
    "a_deg": [20.0, 40.0], "eta0": [1.0, 2.0], "W_over_L": [0.3, 0.5],
    "delta_over_L": [0.001, 0.002], "L_over_Le": [100.0, 250.0], "W0_over_w0": [0.8, 1.2],
    "xi": [0.02, 0.05], "eps_N": [0.3, 0.7], "mu": [0.0, 0.2], "Pi_delta": [0.5, 1.0],
    "gap_m": [0.02, 0.04], "k_factor": [1.0, 2.0], "seat_over_L": [0.02, 0.05],
    "seat_m": [0.5, 1.0], "incidence_deg": [0.0, 90.0],
    "w0_over_wg": [0.5, 2.0], "method": ["event-driven", "time-stepping"],
}

# The one-deck model of the model-file sweep tests (tests/data/models), beside docs/.
MODEL_FILE = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(docs))), "tests", "data",
                          "models", "one-deck-pulse.toml")


def documented_axes(path):
    """{family: [keys]} from the family table and the model-file key table."""
    text = open(path).read()
    families = {}
    for family in ("subsystem", "pilot-bridge", "multi-span"):
        row = re.search(r"^\| `%s` \|[^|]*\|([^\n]*)\|$" % re.escape(family), text, re.M)
        assert row, family
        keys = re.findall(r"`(\w+)`", row.group(1))
        families[family] = list(dict.fromkeys(keys))
    table = text[text.index("| key | what it replaces in the model file |"):]
    table = table[:table.index("\n\n")]
    keys = []
    for line in table.splitlines()[2:]:
        keys += re.findall(r"`(\w+)`", line.split("|")[1])
    families["model-file"] = list(dict.fromkeys(keys))
    return families


def toml_value(v):
    return '"%s"' % v if isinstance(v, str) else repr(v)


def spec_text(family, key):
    """A sweep of `family` over `key`, with what the family needs besides."""
    fixed = {}
    if family in ("subsystem", "multi-span") and key not in ("eta0", "W_over_L"):
        fixed["eta0"] = 1.5
    if family == "multi-span" and key == "method":
        fixed["spans"] = 2  # time-stepping and event-driven on a two-span row
    lines = ['[sweep]', 'name = "axis-%s"' % key, 'family = "%s"' % family]
    if family == "model-file":
        lines.append('model = "deck.toml"')
    if key == "record":
        lines += ['[records]', 'folder = "recs"', 'pattern = "r?.txt"', 'units = "m/s^2"',
                  'dt = 0.01']
    lines += ['[axes]', '%s = [%s]' % (key, ", ".join(toml_value(v) for v in VALUES[key]))]
    if fixed:
        lines.append('[fixed]')
        lines += ['%s = %s' % (k, toml_value(v)) for k, v in fixed.items()]
    return "\n".join(lines) + "\n"


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def check(family, key, cube):
    name = "axis-" + key
    with h5py.File(cube, "r") as f:
        g = f["sweeps/" + name]
        assert int(g.attrs["complete"]) == 1, (family, key)
        assert key in [text(k) for k in g.attrs["axis_order"]], (family, key)
        axis = g["axes/" + key]
        if h5py.check_string_dtype(axis.dtype):
            assert list(axis.asstr()[()]) == VALUES[key], (family, key, axis[()])
        else:
            assert np.allclose(axis[()], VALUES[key], rtol=0, atol=0), (family, key, axis[()])
        assert np.all(g["done"][()] == 1), (family, key)
        status = g["status"][()]
        assert np.all(status == 0), (family, key, status)
        order = [text(k) for k in g.attrs["axis_order"]]
        responses = [text(r) for r in g.attrs["response_order"]]
        links = [text(r) for r in g.attrs["response_links"]]
        for r, link in zip(responses, links):
            assert link == (("response_" + r) if r in order else r), (family, key, r, link)
        i = order.index(key)
        if family == "model-file" and key == "w_g":
            w = np.moveaxis(g["responses/w_g"][()], i, 0)
            assert np.allclose(w[0], 10.0, rtol=1e-12) and np.allclose(w[1], 12.0, rtol=1e-12)
        if family == "model-file" and key == "T_g":
            w = np.moveaxis(g["responses/w_g"][()], i, 0)
            assert np.allclose(w[0], 2 * math.pi / 0.5, rtol=1e-12), w
            assert np.allclose(w[1], 2 * math.pi / 0.7, rtol=1e-12), w
        if family == "model-file" and key == "scale":
            a = np.moveaxis(g["responses/a_g"][()], i, 0)
            assert np.allclose(a[1], 2 * a[0], rtol=1e-12), a
        ds = xr.open_dataset(cube, engine="h5netcdf", group="sweeps/" + name)
        assert list(ds.coords[key].values) == VALUES[key], (family, key)
        for r, link in zip(responses, links):
            assert np.array_equal(ds[link].values, g["responses/" + r][()], equal_nan=True), r
        ds.close()


def main():
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(os.path.join(work, "recs"))
    os.chdir(work)
    shutil.copyfile(MODEL_FILE, "deck.toml")
    for name, amp, period in (("r1.txt", 3.0, 0.5), ("r2.txt", 4.5, 0.8)):
        with open(os.path.join("recs", name), "w") as f:
            for k in range(300):
                t = 0.01 * k
                f.write("%.17g\n" % (amp * math.sin(2 * math.pi * t / period) * math.exp(-t)))
    families = documented_axes(docs)
    missing = [(fam, k) for fam, keys in families.items() for k in keys if k not in VALUES]
    assert not missing, "documented axes without values in this test: %s" % missing
    count = 0
    for family, keys in families.items():
        assert len(keys) >= 8, (family, keys)
        for key in keys:
            spec = "%s-%s.toml" % (family, key)
            with open(spec, "w") as f:
                f.write(spec_text(family, key))
            cube = "%s-%s.h5" % (family, key)
            done = subprocess.run([exe, "sweep", spec, "--out", cube, "--quiet"],
                                  capture_output=True, text=True)
            if done.returncode != 0:
                sys.exit("every_axis_test: FAIL: %s axis %s: exit %d: %s" %
                         (family, key, done.returncode, done.stderr.strip()))
            check(family, key, cube)
            count += 1
        print("%s: %s" % (family, ", ".join(keys)))
    print("every_axis_test: ok (%d axes)" % count)


main()
