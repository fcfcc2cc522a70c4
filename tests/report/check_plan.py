#!/usr/bin/python3
"""`skewbridge modes MODEL --plan` and `scripts/report --model MODEL` against the model files
read here with tomllib and numpy alone:

- the corners of docs/examples/pilot-elements.toml and subsystem.toml are those of
  solver/NOTATION.md (P1 = (L/2 + (W/2) tan a, W/2), ...), W from eta0 where the file gives it;
- every gap at rest is delta cos a;
- the centre of rigidity of pilot-elements.toml equals the one of K = sum_b A_b^T K_b A_b
  assembled here from its bearings, and is the paper's (-0.24, 0.01) m;
- the three-span model has three decks and its joints' faces move with a deck;
- `scripts/report --model` writes a non-blank plan PNG and its table, and a bad model file gives
  exit status 2 with one line naming it.

usage: check_plan.py SKEWBRIDGE SOURCE_ROOT WORK_DIR"""
import json
import os
import subprocess
import sys
import tomllib

import matplotlib.image
import numpy as np

exe, root, work = sys.argv[1:4]
os.makedirs(work, exist_ok=True)
examples = os.path.join(root, "docs", "examples")
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


def plan_of(name):
    out = subprocess.run([exe, "modes", os.path.join(examples, name), "--plan"],
                         capture_output=True, text=True, check=True).stdout
    return json.loads(out)


for name in ("pilot-elements.toml", "subsystem.toml"):
    with open(os.path.join(examples, name), "rb") as f:
        model = tomllib.load(f)
    deck = model["deck"]
    a = np.radians(deck["skew_deg"])
    L = deck["L"]
    W = deck["W"] if "W" in deck else L * np.sin(2 * a) / (2 * deck["eta0"])
    h, s = W / 2, W / 2 * np.tan(a)
    expected = np.array([[L / 2 + s, h], [L / 2 - s, -h], [-L / 2 - s, -h], [-L / 2 + s, h]])
    plan = plan_of(name)
    got = np.array(plan["decks"][0]["corners_m"])
    check(np.allclose(got, expected, atol=1e-12 * L), f"{name}: corners {got} != {expected}")
    gap = model["abutments"]["gap_m"]
    for c in plan["contacts"]:
        check(abs(c["gap_m"] - gap * np.cos(a)) < 1e-12, f"{name}: {c['name']} gap {c['gap_m']}")
        corner = expected[int(c["name"][1]) - 1]
        check(np.allclose(c["point_m"], corner, atol=1e-12 * L), f"{name}: {c['name']} point")

# The centre of rigidity from the bearings, assembled here.
with open(os.path.join(examples, "pilot-elements.toml"), "rb") as f:
    model = tomllib.load(f)
K = np.zeros((3, 3))
for b in model["substructure"]["bearing"]:
    ks = b.get("k_strong_Npm", b.get("k_Npm"))
    kw = b.get("k_weak_Npm", b.get("k_Npm"))
    phi = np.radians(b.get("strong_axis_deg", 0.0))
    R = np.array([[np.cos(phi), -np.sin(phi)], [np.sin(phi), np.cos(phi)]])
    A = np.array([[1.0, 0.0, -b["y_m"]], [0.0, 1.0, b["x_m"]]])
    K += A.T @ (R @ np.diag([ks, kw]) @ R.T) @ A
t = np.linalg.solve(K[:2, :2], K[:2, 2])
centre = np.array([t[1], -t[0]])
plan = plan_of("pilot-elements.toml")
got = np.array(plan["decks"][0]["centre_of_rigidity_m"])
check(np.allclose(got, centre, atol=1e-9), f"pilot-elements: centre {got} != {centre}")
check(np.allclose(got, [-0.24, 0.01], atol=5e-5), f"pilot-elements: centre {got} not the paper's")
check(len(plan["bearings"]) == len(model["substructure"]["bearing"]), "pilot-elements: bearings")

three = plan_of("three-span.toml")
check(len(three["decks"]) == 3, "three-span: decks")
check(any(c["face_deck"] is not None for c in three["contacts"]), "three-span: no joint face")
check(len(three["supports"]) >= 3, "three-span: supports")

# The drawing.
report = os.path.join(root, "scripts", "report")
out = os.path.join(work, "plan")
done = subprocess.run([report, "--model", os.path.join(examples, "pilot-elements.toml"),
                       "--model", os.path.join(examples, "three-span.toml"), "--exe", exe,
                       "--out", out], capture_output=True, text=True)
check(done.returncode == 0, f"report --model: exit {done.returncode}: {done.stderr}")
for name in ("plan_pilot-elements.png", "plan_three-span.png"):
    path = os.path.join(out, name)
    if not os.path.exists(path):
        failures.append(f"{name}: not written")
        continue
    img = matplotlib.image.imread(path)
    check(img.shape[0] > 300 and img.shape[1] > 1000, f"{name}: size {img.shape}")
    check(float(np.std(img[..., :3])) > 0.05, f"{name}: blank")
summary = open(os.path.join(out, "summary.md"), encoding="utf-8").read()
check("centre of rigidity from the mass centre | (-0.24, 0.009999) m" in summary,
      "summary.md: no centre of rigidity row")
bad = os.path.join(work, "bad.toml")
with open(bad, "w") as f:
    f.write("[deck]\nm = -1\n")
done = subprocess.run([report, "--model", bad, "--exe", exe, "--out", os.path.join(work, "x")],
                      capture_output=True, text=True)
check(done.returncode == 2 and len(done.stderr.strip().splitlines()) == 1 and
      "bad.toml" in done.stderr, f"bad model: exit {done.returncode}, '{done.stderr}'")

for f in failures:
    print("FAIL", f)
print("check_plan: ok" if not failures else f"{len(failures)} failures")
sys.exit(1 if failures else 0)
