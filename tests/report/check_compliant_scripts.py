#!/usr/bin/python3
"""scripts/compliant/approach_speeds.py and equivalent_restitution.py (docs/compliant.md §5) on
a small rigid study of the pilot bridge made by the real `skewbridge sweep` on 2 ranks, checked
against quantities computed here:

- approach_speeds.py with --fix eps_N=0.66 runs exactly the cells of that coordinate (every
  record, stripe and skew), and each row's impact count is the cube's stored `impacts` of that
  cell (the sweep's own count, not the re-run's events); the same cells at eps_N = 0.5 count
  differently somewhere, so a row taken from the wrong coordinate fails;
- equivalent_restitution.py's percentile rows are numpy's 16/50/84 % of the first-impact speeds
  and `skewbridge restitution` struck at those speeds; its energy-equivalent restitution
  eps_E^2 = sum v^2 e(v)^2 / sum v^2 (interpolated on a 60-strike grid) equals the same sum
  with one strike at every impact's own speed to 2e-4, and differs by more than that from
  the speed-weighted mean sum v e / sum v (a wrong weight fails); its figure is written.

usage: check_compliant_scripts.py SKEWBRIDGE MPIEXEC PROJECT_DIR WORK_DIR
"""
import csv
import io
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

LAW = ["--k-max-Npm", "393008000", "--r-f", "0.7", "--f-ult-N", "6311360"]
MASS = "1547e3"


def fail(what):
    sys.exit(f"check_compliant_scripts: {what}")


def strikes(exe, speeds):
    out = subprocess.run([exe, "restitution", "--mass-kg", MASS, *LAW, "--csv", "--velocity-mps",
                          *[repr(float(v)) for v in speeds]],
                         check=True, capture_output=True, text=True).stdout
    return list(csv.DictReader(io.StringIO(out)))


def main():
    exe, mpiexec, project, work = sys.argv[1:5]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    os.chdir(work)
    scripts = os.path.join(project, "scripts", "compliant")
    with open("spec.toml", "w") as f:
        f.write(f"""[sweep]
name = "rigid"
family = "model-file"
model = "{project}/docs/examples/pilot-bridge.toml"
[records]
set = "{project}/tests/data/records/two-records.toml"
scale_to = {{ measure = "Sa", period = "T1", xi = 0.05 }}
max_scale = 40.0
[axes]
record = "*"
im_g = [1.5, 3.0, 4.5]
a_deg = [20, 40]
eps_N = [0.5, 0.66]
""")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    subprocess.run([mpiexec, "--oversubscribe", "-n", "2", exe, "sweep", "spec.toml", "--out",
                    "rigid.h5", "--quiet"], check=True, env=env)
    subprocess.run(["/usr/bin/python3", os.path.join(scripts, "approach_speeds.py"), exe,
                    "rigid.h5", "--out", "speeds.csv", "--fix", "eps_N=0.66", "--jobs", "2"],
                   check=True, stdout=subprocess.DEVNULL)

    with h5py.File("rigid.h5", "r") as f:
        g = f["sweeps/rigid"]
        order = [a.decode() if isinstance(a, bytes) else a for a in g.attrs["axis_order"]]
        axes = {a: g["axes/" + a][()] for a in order}
        shape = [len(axes[a]) for a in order]
        impacts = g["responses/impacts"][()].reshape(-1)
    rows = list(csv.DictReader(open("speeds.csv")))
    e = order.index("eps_N")
    want = [i for i in range(int(np.prod(shape))) if np.unravel_index(i, shape)[e] == 1]
    got = [int(r["cell"]) for r in rows]
    if sorted(got) != want:
        fail(f"cells run {sorted(got)}, the eps_N = 0.66 cells are {want}")
    twin_differs = False
    for r in rows:
        i = int(r["cell"])
        idx = np.unravel_index(i, shape)
        for a in ("im_g", "a_deg"):
            if abs(float(r[a]) - float(axes[a][idx[order.index(a)]])) > 1e-12:
                fail(f"cell {i}: {a} {r[a]} against the axis' {axes[a][idx[order.index(a)]]}")
        if int(r["impacts"]) != int(impacts[i]):
            fail(f"cell {i}: {r['impacts']} impacts in the re-run, {impacts[i]} in the cube")
        twin = list(idx)
        twin[e] = 0
        twin_differs |= int(impacts[np.ravel_multi_index(twin, shape)]) != int(impacts[i])
    if not twin_differs:
        fail("eps_N 0.5 and 0.66 give the same impact counts: the check cannot tell them apart")
    first = np.array([float(r["first_speed_mps"]) for r in rows])
    first = first[np.isfinite(first)]
    every = np.array([float(x) for r in rows for x in r["speeds_mps"].split(";") if x])
    if first.size < 4 or every.size < 10:
        fail(f"{first.size} runs with impacts and {every.size} impacts: too few to check")

    subprocess.run(["/usr/bin/python3", os.path.join(scripts, "equivalent_restitution.py"), exe,
                    "--out", "eq", "--bridge", "pilot", "speeds.csv", MASS, " ".join(LAW)],
                   check=True, stdout=subprocess.DEVNULL)
    table = list(csv.DictReader(open("eq/restitution.csv")))
    at = strikes(exe, np.percentile(first, [16, 50, 84]))
    for q, direct in zip((16, 50, 84), at):
        row = [r for r in table if r["percentile"] == str(q)]
        if len(row) != 1:
            fail(f"no single {q} % row in restitution.csv")
        v = float(row[0]["approach_mps"])
        if abs(v - np.percentile(first, q)) > 1e-8 * v:  # 9 digits in the CSV
            fail(f"{q} %: speed {v} against numpy's {np.percentile(first, q)}")
        if row[0]["restitution"] != direct["restitution"]:
            fail(f"{q} %: eps_N {row[0]['restitution']} against a strike's {direct['restitution']}")
    e_of = {float(r["approach_mps"]): float(r["restitution"]) for r in strikes(exe, every)}
    e_every = np.array([e_of[min(e_of, key=lambda s: abs(s - v))] for v in every])
    brute = np.sqrt(np.sum(every**2 * e_every**2) / np.sum(every**2))
    wrong = np.sum(every * e_every) / np.sum(every)
    energy = float([r for r in table if r["percentile"] == "energy"][0]["restitution"])
    print(f"eps_E {energy:.6f}, one strike per impact {brute:.6f}, speed-weighted mean "
          f"{wrong:.6f}; {every.size} impacts in {first.size} runs")
    if abs(energy - brute) > 2e-4:
        fail(f"eps_E {energy} against {brute} from a strike at every impact's speed")
    if abs(wrong - brute) <= 2e-4:
        fail("the speed-weighted mean is as close as eps_E: the check cannot tell them apart")
    png = "eq/restitution_pilot.png"
    if not os.path.exists(png) or os.path.getsize(png) < 20000:
        fail(f"{png} missing or nearly empty")


if __name__ == "__main__":
    main()
