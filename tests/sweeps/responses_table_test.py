#!/usr/bin/python3
"""The responses tables of docs/sweep-format.md are the responses the evaluators store. Each table
(the subsystem and pilot bridge's, the multi-span family's, the model-file family's and the one
that `[records] scale_to` adds) is read from the document; sweeps of one or two cells that switch
on every conditional response (seats, limit states, records scaled to an intensity, compliant
abutments with both walls and shear keys, compliant deck-deck joints) are run with the real
program, and the names and units of the cube's responses are compared with the tables both ways:
every stored response is documented, with the unit the table gives, and every documented response
is stored by one of the sweeps. Per-deck and per-joint names are matched by their pattern
(`x_m_d<i>`, `joint_force_j<i>`); a limit state's pair by `ls_<name>_demand` and `ls_<name>`,
as the section on limit states documents them.

usage: responses_table_test.py SKEWBRIDGE DOCS_SWEEP_FORMAT_MD WORK_DIR"""
import math
import os
import re
import shutil
import subprocess
import sys

import h5py

exe, docs, work = (os.path.abspath(p) for p in sys.argv[1:4])
root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# The tables, each found by the sentence that introduces it.
TABLES = {
    "spectra": "Responses, in this order",
    "multi-span": "Responses of the `multi-span` family",
    "model-file": "Responses, per deck with the suffix",
    "scale_to": "Responses added by `scale_to` or `im`",
}


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def read_table(doc, intro):
    """{pattern: unit or None} of the table after `intro`: every backquoted name of a row's first
    cell, paired with the units of its second cell (one for all, or one per name)."""
    at = doc.index(intro)
    start = doc.index("| response | unit | meaning |", at)
    assert start - at < 400, ("the table is not right after", intro)
    rows = doc[start:doc.index("\n\n", start)].splitlines()[2:]
    table = {}
    for row in rows:
        cells = [c.strip() for c in row.strip().strip("|").split("|")]
        names = re.findall(r"`([^`]+)`", cells[0])
        assert names, row
        units = [u.strip() for u in cells[1].split(",")]
        if len(units) == 1:
            units = units * len(names)
        assert len(units) == len(names), ("units do not pair with the names", row)
        for name, unit in zip(names, units):
            assert name not in table, ("documented twice", name)
            table[name] = unit
    return table


def pattern_of(name):
    """The table's form of a stored name: x_m_d0 -> x_m_d<i>, joint_def_j1 -> joint_def_j<i>."""
    return re.sub(r"_j\d+$", "_j<i>", re.sub(r"_d\d+$", "_d<i>", name))


def expected_unit(table, pattern):
    unit = table[pattern]
    m = re.fullmatch(r"as `(\w+)`", unit)
    if m:
        return expected_unit(table, m.group(1))
    return unit.split(" (")[0]  # "g (m/s for PGV)": the sweeps here scale to Sa, in g


def write(path, content):
    with open(path, "w") as f:
        f.write(content)


def edited(source, replacements):
    """The file `source` with each (old, new) replaced once, exactly as written."""
    content = open(source).read()
    for old, new in replacements:
        assert old in content, (source, old)
        content = content.replace(old, new, 1)
    return content


def records():
    os.makedirs("recs", exist_ok=True)
    for name, amp, period in (("r1.txt", 3.0, 0.5), ("r2.txt", 4.5, 0.8)):
        with open(os.path.join("recs", name), "w") as f:
            for k in range(300):
                t = 0.01 * k
                f.write("%.17g\n" % (amp * math.sin(2 * math.pi * t / period) * math.exp(-t)))


RECORDS = '[records]\nfolder = "recs"\npattern = "r?.txt"\nunits = "m/s^2"\ndt = 0.01\n'
SEATS = '[limit_states]\nunseating = true\nrotation = {above_rad = 0.001}\njoint_closing = true\n'

# (name, family's tables, spec text): every conditional response switched on by one of them.
SWEEPS = [
    ("subsystem", ["spectra"],
     '[sweep]\nname = "s"\nfamily = "subsystem"\n[axes]\nPi_delta = [0.5, 1.0]\n'
     '[fixed]\neta0 = 1.5\nseat_over_L = 0.05\n' + SEATS),
    ("pilot-records", ["spectra"],
     '[sweep]\nname = "s"\nfamily = "pilot-bridge"\n' + RECORDS +
     '[axes]\nrecord = "*"\n[fixed]\nseat_m = 0.1\n'),
    ("multi-span", ["multi-span"],
     '[sweep]\nname = "s"\nfamily = "multi-span"\n[axes]\nspans = [1, 2]\n'
     '[fixed]\neta0 = 1.5\nseat_over_L = 0.05\n' + SEATS),
    ("rigid-deck", ["model-file"],
     '[sweep]\nname = "s"\nfamily = "model-file"\nmodel = "deck.toml"\n[axes]\n'
     'scale = [1.0, 2.0]\n[fixed]\nseat_over_L = 0.05\n' + SEATS),
    ("rigid-deck-stripes", ["model-file", "scale_to"],
     '[sweep]\nname = "s"\nfamily = "model-file"\nmodel = "deck.toml"\n' + RECORDS +
     'scale_to = {measure = "Sa", period = "T1"}\nmax_scale = 5.0\n'
     '[axes]\nrecord = "*"\nim_g = [0.3]\n[fixed]\nseat_m = 0.1\n' + SEATS),
    ("compliant-keys", ["model-file"],
     '[sweep]\nname = "s"\nfamily = "model-file"\nmodel = "keys.toml"\n[axes]\n'
     'scale = [1.0]\n[fixed]\nseat_m = 0.1\n' + SEATS),
    ("compliant-joints", ["model-file"],
     '[sweep]\nname = "s"\nfamily = "model-file"\nmodel = "three-span.toml"\n[axes]\n'
     'scale = [1.0]\n[fixed]\nseat_m = 0.3\n' + SEATS),
]


def main():
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    os.chdir(work)
    records()
    shutil.copyfile(os.path.join(root, "tests", "data", "models", "one-deck-pulse.toml"),
                    "deck.toml")
    # The pilot bridge with compliant walls and shear keys at both abutments, under a pulse.
    write("keys.toml", edited(os.path.join(root, "docs", "examples",
                                           "pilot-bridge-compliant-keys.toml"),
                              [('kind = "sampled"\nfile = "pilot-signal.txt"', 'kind = "pulse"\n'
                                'shape = "cosine"\na_g_g = 0.8\nT_g = 0.6\n#'),
                               ('units = "mps2"', '')]))
    shutil.copyfile(os.path.join(root, "docs", "examples", "three-span-compliant.toml"),
                    "three-span.toml")
    doc = open(docs).read()
    tables = {k: read_table(doc, intro) for k, intro in TABLES.items()}
    for what in ("`ls_<name>_demand`", "`ls_<name>`"):
        assert what in doc, "the limit states' responses are not documented as " + what
    seen = {k: set() for k in tables}
    problems = []
    for name, families, spec in SWEEPS:
        write(name + ".toml", spec)
        done = subprocess.run([exe, "sweep", name + ".toml", "--out", name + ".h5", "--quiet"],
                              capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit("responses_table_test: FAIL: sweep %s: exit %d: %s" %
                     (name, done.returncode, done.stderr.strip()))
        with h5py.File(name + ".h5", "r") as f:
            g = f["sweeps/s"]
            assert int(g.attrs["complete"]) == 1, name
            responses = [text(r) for r in g.attrs["response_order"]]
            units = {r: text(g["responses/" + r].attrs["units"]) for r in responses}
        limit_states = re.findall(r"^(\w+) = ", spec[spec.index("[limit_states]"):], re.M) \
            if "[limit_states]" in spec else []
        stored = set()
        for r in responses:
            m = re.fullmatch(r"ls_(\w+?)(_demand)?", r)
            if m and m.group(1) in limit_states:
                continue
            pattern = pattern_of(r)
            stored.add(pattern)
            where = [k for k in families if pattern in tables[k]]
            if not where:
                problems.append("%s: the response %s (%s) is not in the table of %s" %
                                (name, r, pattern, " or ".join(families)))
                continue
            for k in where:
                seen[k].add(pattern)
            unit = expected_unit(tables[where[0]], pattern)
            if units[r] != unit:
                problems.append("%s: %s is stored in %s, documented in %s" %
                                (name, r, units[r], unit))
        for ls in limit_states:
            for r in ("ls_" + ls + "_demand", "ls_" + ls):
                if r not in responses:
                    problems.append("%s: no response %s for its limit state" % (name, r))
        print("%s: %d responses" % (name, len(responses)))
    for k, table in tables.items():
        for pattern in table:
            if pattern not in seen[k]:
                problems.append("the table of %s documents %s, which none of the sweeps stored" %
                                (k, pattern))
    if problems:
        sys.exit("responses_table_test: FAIL:\n  " + "\n  ".join(problems))
    print("responses_table_test: ok (%s)" %
          ", ".join("%s %d" % (k, len(t)) for k, t in tables.items()))


main()
