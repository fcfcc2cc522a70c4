#!/usr/bin/python3
"""AvgSa of RotD50 as a sweep's scale_to measure against an independent numpy solution.

usage: avgsa_rotd50_check.py SKEWBRIDGE PAIRS_DIR MODEL_FILE WORK_DIR

A model-file sweep of the two real pairs of PAIRS_DIR with scale_to = {measure =
"AvgSa_RotD50", period = "T1"} (two cells, one small stripe) stores each pair's own measure in
the response im_unscaled. The oracle shares no code with records/measures.cpp: the pair is read
from the .AT2 text (the shorter component padded with zeros at its end), the 50 periods
0.2 T1 .. 3 T1 (equally spaced; T1 the cell's stored fundamental period) are numpy's linspace,
each component's oscillator u'' + 2 xi w u' + w^2 u = -a(t) is solved by scipy.signal.lsim
(interp=True, exact under piecewise-linear input), RotD50 is numpy's median over 0..179 deg of
the peak of |u1 cos theta + u2 sin theta| times w^2 [Boore 2010], and AvgSa is the geometric
mean of the 50 values [Eads et al. 2015]: equal to 1e-9 relative (measured 1.4e-14). Also: the
scale factor is the stripe over it, it is not RotD50(T1) alone nor the AvgSa of H1, the cell's
a_g is H1's PGA times the factor (not H2's), the stored description names the measure, and
AvgSa_RotD50 of a single record is refused in one line naming the record.
"""
import os
import re
import subprocess
import sys

import h5py
import numpy as np
from scipy import signal

skewbridge, pairs_dir, model, work = sys.argv[1:5]
os.makedirs(work, exist_ok=True)
pairs_dir = os.path.abspath(pairs_dir)
PAIRS = {"RSN107": ("RSN107_OROVILLE_B-OAP180.AT2", "RSN107_OROVILLE_B-OAP270.AT2"),
         "RSN430": ("RSN430_SMART1.25_25M01EW.AT2", "RSN430_SMART1.25_25M01NS.AT2")}
STRIPE_G = 0.05
G = 9.80665
XI = 0.05
TOLERANCE = 1e-9


def read_at2(path):
    """Samples (m/s^2) and dt (s) of a PEER .AT2 file: 3 header lines, NPTS and DT, values in g."""
    with open(path) as f:
        lines = f.read().splitlines()
    npts = int(re.search(r"NPTS=\s*(\d+)", lines[3]).group(1))
    dt = float(re.search(r"DT=\s*([0-9.Ee+-]+)", lines[3]).group(1))
    values = np.array(" ".join(lines[4:]).split(), dtype=float)
    assert values.size == npts, path
    return values * G, dt


def displacement(acc, dt, period):
    """The oscillator's displacement history under ground acceleration acc (m/s^2)."""
    w = 2.0 * np.pi / period
    system = signal.StateSpace([[0.0, 1.0], [-w * w, -2.0 * XI * w]], [[0.0], [-1.0]],
                               [[1.0, 0.0]], [[0.0]])
    _, u, _ = signal.lsim(system, acc, dt * np.arange(acc.size), interp=True)
    return u


def rotd50_and_h1(a1, a2, dt, period):
    """RotD50 and Sa of H1 (m/s^2) at one period: numpy's median over 0..179 deg."""
    u1, u2 = displacement(a1, dt, period), displacement(a2, dt, period)
    theta = np.radians(np.arange(180))
    peaks = np.abs(np.outer(np.cos(theta), u1) + np.outer(np.sin(theta), u2)).max(axis=1)
    w2 = (2.0 * np.pi / period) ** 2
    return w2 * np.median(peaks), w2 * np.abs(u1).max()

set_path = os.path.join(work, "pairs.toml")
with open(set_path, "w") as f:
    f.write('name = "two-pairs"\n')
    for label, (h1, h2) in PAIRS.items():
        f.write(f'[[record]]\nlabel = "{label}"\nh1 = "{pairs_dir}/{h1}"\nh2 = "{pairs_dir}/{h2}"\n')


def spec(set_file, measure="AvgSa_RotD50"):
    path = os.path.join(work, "spec.toml")
    with open(path, "w") as f:
        f.write(f'[sweep]\nname = "avg-rotd50"\nfamily = "model-file"\n'
                f'model = "{os.path.abspath(model)}"\n'
                f'[records]\nset = "{set_file}"\n'
                f'scale_to = {{measure = "{measure}", period = "T1"}}\n'
                f'[axes]\nrecord = "*"\nim_g = [{STRIPE_G}]\nincidence_deg = [30]\n')
    return path


cube = os.path.join(work, "cube.h5")
subprocess.run([skewbridge, "sweep", spec(set_path), "--out", cube, "--force", "--quiet"],
               check=True)
with h5py.File(cube, "r") as f:
    g = f["sweeps/avg-rotd50"]
    labels = [x.decode() if isinstance(x, bytes) else x for x in g["axes/record"][()]]
    own = g["im_unscaled"][()].reshape(len(labels))
    factor = g["scale_factor"][()].reshape(len(labels))
    t1 = g["T1"][()].reshape(len(labels))
    a_g = g["a_g"][()].reshape(len(labels))
    description = g.attrs.get("im_description", b"")
    if isinstance(description, bytes):
        description = description.decode()
assert labels == list(PAIRS), labels
assert np.all(t1 == t1[0]), t1
assert description.startswith("AvgSa_RotD50(T1, xi = 0.05)"), description

periods = t1[0] * np.linspace(0.2, 3.0, 50)
worst = 0.0
for i, label in enumerate(labels):
    a1, dt1 = read_at2(os.path.join(pairs_dir, PAIRS[label][0]))
    a2, dt2 = read_at2(os.path.join(pairs_dir, PAIRS[label][1]))
    assert dt1 == dt2, label
    n = max(a1.size, a2.size)
    a1, a2 = np.pad(a1, (0, n - a1.size)), np.pad(a2, (0, n - a2.size))
    values = np.array([rotd50_and_h1(a1, a2, dt1, t) for t in periods])
    expected = np.exp(np.mean(np.log(values[:, 0]))) / G
    rel = abs(own[i] - expected) / expected
    worst = max(worst, rel)
    assert rel < TOLERANCE, (label, own[i], expected, rel)
    assert abs(factor[i] - STRIPE_G / own[i]) <= 1e-15 * factor[i], (label, factor[i])
    # The cell's a_g is H1's PGA times the pair's one factor (H2 does not enter it).
    pga_h1, pga_h2 = np.abs(a1).max(), np.abs(a2).max()
    assert abs(a_g[i] - pga_h1 * factor[i]) <= 1e-12 * a_g[i], (label, a_g[i], pga_h1)
    assert abs(a_g[i] - pga_h2 * factor[i]) > 1e-3 * a_g[i], (label, a_g[i], pga_h2)
    # Neither RotD50 at T1 alone nor the AvgSa of H1: the measure is of the pair over a range.
    at_t1 = rotd50_and_h1(a1, a2, dt1, t1[0])[0] / G
    avgsa_h1 = np.exp(np.mean(np.log(values[:, 1]))) / G
    assert abs(at_t1 - own[i]) > 1e-3 * own[i], (label, at_t1, own[i])
    assert abs(avgsa_h1 - own[i]) > 1e-3 * own[i], (label, avgsa_h1, own[i])

# A single record is refused in one line, nothing written.
single = os.path.join(work, "single.toml")
with open(single, "w") as f:
    f.write(f'name = "one"\n[[record]]\nlabel = "H1"\nfile = "{pairs_dir}/{PAIRS["RSN430"][0]}"\n')
bad_cube = os.path.join(work, "bad.h5")
run = subprocess.run([skewbridge, "sweep", spec(single), "--out", bad_cube, "--force", "--quiet"],
                     capture_output=True, text=True)
lines = run.stderr.strip().splitlines()
assert run.returncode == 2, (run.returncode, run.stderr)
assert len(lines) == 1 and "records.scale_to.measure" in lines[0] and "'H1'" in lines[0] \
    and "AvgSa_RotD50" in lines[0], run.stderr
assert not os.path.exists(bad_cube), bad_cube
print(f"AvgSa_RotD50 of {len(labels)} pairs at T1 = {t1[0]:.6g} s: largest relative difference "
      f"{worst:.2e} against numpy and scipy.signal.lsim (tolerance {TOLERANCE:g})")
