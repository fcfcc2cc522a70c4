#!/usr/bin/python3
"""Record pairs of a folder set drive a sweep as the same pairs of [[record]] tables do.

usage: pair_folder_check.py SKEWBRIDGE PAIRS_DIR MODEL_FILE WORK_DIR

PAIRS_DIR holds the two real pairs RSN107 (H2 225 samples shorter) and RSN430 and PAIRS.csv,
their rows of the NGA-West2 table. Five sweeps of one model file, each record scaled to two
RotD50(T1) stripes at two incidence angles:
  A  [records] set = a manifest of two [[record]] pairs without labels;
  B  [records] folder = PAIRS_DIR, pattern = "RSN*.AT2", pairs = true (paired by name);
  C  [records] set = a manifest of the same two [[record]] pairs labelled RSN107 and RSN430;
  D  [records] folder = PAIRS_DIR, pattern = "*.AT2", pairs = "PAIRS.csv";
  E  [records] set = a folder manifest with pairs = "PAIRS.csv".
B equals A and D, E equal C: the record table (labels, components, npts, padding, the
records' measures, RotD50, RotD100 and GM at T1), every response of every cell (bit for bit),
and the record inputs of the cube (the four .AT2 files by name and SHA-256); D and E also have
PAIRS.csv as an input (role record-pairs) with its SHA-256, and a changed table changes their
identity. The canonical texts differ (records.set against records.folder), so the hashes do.
"""
import hashlib
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

skewbridge, pairs_dir, model, work = sys.argv[1:5]
pairs_dir, model = os.path.abspath(pairs_dir), os.path.abspath(model)
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
FILES = [("RSN107", "RSN107_OROVILLE_B-OAP180.AT2", "RSN107_OROVILLE_B-OAP270.AT2"),
         ("RSN430", "RSN430_SMART1.25_25M01EW.AT2", "RSN430_SMART1.25_25M01NS.AT2")]


def manifest(name, labelled):
    path = os.path.join(work, name)
    with open(path, "w") as f:
        for label, h1, h2 in FILES:
            f.write("[[record]]\n" + (f'label = "{label}"\n' if labelled else "") +
                    f'h1 = "{pairs_dir}/{h1}"\nh2 = "{pairs_dir}/{h2}"\n')
    return path


def sweep(name, records):
    spec = os.path.join(work, name + ".toml")
    with open(spec, "w") as f:
        f.write(f'[sweep]\nname = "pairs"\nfamily = "model-file"\nmodel = "{model}"\n'
                f'[records]\n{records}'
                'scale_to = {measure = "RotD50", period = "T1"}\n'
                '[axes]\nrecord = "*"\nim_g = [0.1, 0.4]\nincidence_deg = [0, 60]\n')
    cube = os.path.join(work, name + ".h5")
    subprocess.run([skewbridge, "sweep", spec, "--out", cube, "--quiet"], check=True,
                   stderr=subprocess.DEVNULL)
    return cube


def read(cube):
    """(record table, responses, record inputs by name, other inputs by role, hash)."""
    with h5py.File(cube, "r") as f:
        g = f["sweeps/pairs"]
        table = {k: v[()] for k, v in g["records"].items()}
        responses = {k: v[()] for k, v in g["responses"].items()}
        inputs = g["inputs"]
        rows = [(r.decode(), os.path.basename(p.decode()), s.decode())
                for r, p, s in zip(inputs["role"][()], inputs["file"][()], inputs["sha256"][()])]
        identity = g.attrs["spec_hash"]
    records = sorted((name, sha) for role, name, sha in rows if role == "record")
    others = sorted((role, name, sha) for role, name, sha in rows
                    if role not in ("record", "spec", "model"))
    return table, responses, records, others, identity


def same(a, b, what):
    ta, ra, ia, _, _ = read(a)
    tb, rb, ib, _, _ = read(b)
    assert set(ta) == set(tb), (what, set(ta) ^ set(tb))
    for k in ta:
        if k in ("file", "file_h2"):  # relative to the set's folder: compare the names
            na = [os.path.basename(x.decode()) for x in ta[k]]
            nb = [os.path.basename(x.decode()) for x in tb[k]]
            assert na == nb, (what, k, na, nb)
        else:
            assert np.array_equal(ta[k], tb[k], equal_nan=ta[k].dtype.kind == "f"), (what, k)
    assert set(ra) == set(rb), what
    for k in ra:
        assert ra[k].tobytes() == rb[k].tobytes(), (what, k)
    assert ia == ib and len(ia) == 4, (what, ia, ib)
    return len(ra)


a = sweep("A", f'set = "{manifest("default.toml", False)}"\n')
b = sweep("B", f'folder = "{pairs_dir}"\npattern = "RSN*.AT2"\npairs = true\n')
c = sweep("C", f'set = "{manifest("labelled.toml", True)}"\n')
d = sweep("D", f'folder = "{pairs_dir}"\npattern = "*.AT2"\npairs = "PAIRS.csv"\n')
folder_set = os.path.join(work, "folder.toml")
with open(folder_set, "w") as f:
    f.write(f'name = "pairs"\nfolder = "{pairs_dir}"\npattern = "*.AT2"\npairs = "PAIRS.csv"\n')
e = sweep("E", f'set = "{folder_set}"\n')
n = same(a, b, "by name")
same(c, d, "by table")
same(c, e, "by table in a manifest")
labels = [x.decode() for x in read(b)[0]["label"]]
assert labels == ["RSN107_OROVILLE_B-OAP", "RSN430_SMART1.25_25M01"], labels
assert [x.decode() for x in read(d)[0]["label"]] == ["RSN107", "RSN430"]
with open(os.path.join(pairs_dir, "PAIRS.csv"), "rb") as f:
    table_sha = hashlib.sha256(f.read()).hexdigest()
for cube in (d, e):
    others = read(cube)[3]
    assert ("record-pairs", "PAIRS.csv", table_sha) in others, others
assert read(a)[4] != read(b)[4]  # records.set against records.folder: other canonical texts

# The table is an input: a copy with one more (unused) column changes the identity.
copy = os.path.join(work, "copy")
shutil.copytree(pairs_dir, copy)
with open(os.path.join(copy, "PAIRS.csv")) as f:
    lines = f.read().splitlines()
with open(os.path.join(copy, "PAIRS.csv"), "w") as f:
    f.write("\n".join(line + (",note" if i == 0 else ",x") for i, line in enumerate(lines)) + "\n")
d2 = sweep("D2", f'folder = "{copy}"\npattern = "*.AT2"\npairs = "PAIRS.csv"\n')
same(d, d2, "a changed table's pairs")
assert read(d)[4] != read(d2)[4], "the pairs table is not part of the identity"
print(f"folder pairs by name and by PAIRS.csv: the record table, {n} responses and the 4 record "
      f"inputs equal the [[record]] form's bit for bit; PAIRS.csv is an input")
