#!/usr/bin/python3
"""The equivalent restitution of a backfill as a fixed point (docs/compliant.md §5): a rigid
study at eps_N gives the approach speeds of its impacts (scripts/compliant/approach_speeds.py),
the backfill struck at those speeds gives the energy-equivalent restitution eps_E(eps_N)
(scripts/compliant/equivalent_restitution.py), and the restitution that reproduces itself,
eps_E(eps*) = eps*, is the one a rigid study of that bridge and those records should take.

    scripts/compliant/restitution_fixed_point.py build/release/skewbridge SPEC.toml \
        --mass-kg M --law "LAW OPTIONS" --work DIR [--start 0.5] [--tol 0.005] \
        [--max-iterations 12] [--ranks 2] [--jobs 2]

SPEC is a model-file sweep of the rigid law (e.g. jobs/specs/compliant/pilot-rigid.toml); each
iterate runs it with its eps_N axis (or fixed value) replaced by the iterate alone, into
DIR/eps_<value>.h5, and every cell of it again for its impacts' speeds (the seat and the other
non-record axes at their first coordinate, as approach_speeds.py does). The iterates are
eps_{k+1} = eps_E(eps_k) until two successive ones differ by less than --tol; once the residual
r(eps) = eps_E(eps) - eps has changed sign, the next iterate is the secant of the bracket's ends
(regula falsi, the Illinois rule) instead, so that a map with a slope below -1 still settles. The
restitution at the median speed of the runs' first impacts is printed beside it; it is its own
fixed point (no restitution acts before a run's first impact, so its speed does not depend on
eps_N). One line per iterate on stdout and DIR/fixed_point.csv.
"""
import argparse
import concurrent.futures
import csv
import os
import re
import subprocess
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import approach_speeds  # noqa: E402
import equivalent_restitution  # noqa: E402

PATH_KEYS = ("model", "set", "folder")


def spec_at(spec_path, eps):
    """The specification's text with eps_N the single value `eps` and its relative paths made
    absolute (the copy lives in another folder)."""
    folder = os.path.dirname(os.path.abspath(spec_path))
    text = open(spec_path).read()
    lines, found = [], False
    for line in text.splitlines():
        m = re.match(r'^(\s*)(\w+)(\s*=\s*)"([^"]*)"(.*)$', line)
        if m and m.group(2) in PATH_KEYS and not os.path.isabs(m.group(4)):
            line = (f'{m.group(1)}{m.group(2)}{m.group(3)}'
                    f'"{os.path.normpath(os.path.join(folder, m.group(4)))}"{m.group(5)}')
        if re.match(r"^\s*eps_N\s*=", line):
            line, found = f"eps_N = [{eps!r}]", True
        lines.append(line)
    if not found:
        sys.exit(f"restitution_fixed_point: {spec_path} has no eps_N line to replace")
    return "\n".join(lines) + "\n"


def speeds_of(exe, spec_path, eps, work, ranks, jobs):
    """Every impact's approach speed and the first impact's speed of each run with impacts of
    the study at eps_N = `eps` (m/s)."""
    name = f"eps_{eps:.6f}"
    spec = os.path.join(work, name + ".toml")
    cube = os.path.join(work, name + ".h5")
    with open(spec, "w") as fh:
        fh.write(spec_at(spec_path, eps))
    if not os.path.exists(cube):
        subprocess.run(["mpiexec", "-n", str(ranks), "--oversubscribe", exe, "sweep", spec, "--out",
                        cube, "--quiet", "--force"], check=True, cwd=work)
    with h5py.File(cube, "r") as f:
        sweep = list(f["sweeps"].keys())[0]
        cells = list(approach_speeds.cells_to_run(f["sweeps"][sweep], {}))
    every, first = [], []
    with tempfile.TemporaryDirectory() as folder, \
            concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        for _, _, v, f1 in pool.map(
                lambda c: approach_speeds.run_cell(exe, cube, None, c[0], folder), cells):
            every.extend(v)
            if np.isfinite(f1):
                first.append(f1)
    return np.array(every), np.array(first), len(cells)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("exe")
    p.add_argument("spec")
    p.add_argument("--mass-kg", type=float, required=True)
    p.add_argument("--law", required=True, help="the law's options of `skewbridge restitution`")
    p.add_argument("--work", required=True)
    p.add_argument("--start", type=float, default=0.5)
    p.add_argument("--tol", type=float, default=0.005)
    p.add_argument("--max-iterations", type=int, default=12)
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--jobs", type=int, default=2)
    a = p.parse_args()
    exe = os.path.abspath(a.exe)
    a.work = os.path.abspath(a.work)
    os.makedirs(a.work, exist_ok=True)
    rows = []
    below, above = None, None  # (eps, residual) with residual < 0 and > 0
    side = 0                   # which end the last regula falsi step moved (Illinois rule)
    eps = a.start
    for k in range(a.max_iterations):
        every, first, runs = speeds_of(exe, a.spec, eps, a.work, a.ranks, a.jobs)
        e_energy, _, _, _ = equivalent_restitution.energy_equivalent(exe, a.mass_kg, a.law, every,
                                                                     first)
        median = float(np.median(first))
        e_first = float(equivalent_restitution.restitution(exe, a.mass_kg, a.law, [median])[0]
                        ["restitution"])
        image = e_energy
        residual = image - eps
        rows.append({"iterate": k, "eps_N": f"{eps:.6f}", "runs": runs,
                     "runs_with_impacts": first.size, "impacts": every.size,
                     "speed_median_mps": f"{np.median(every):.6g}",
                     "first_speed_median_mps": f"{median:.6g}",
                     "eps_energy": f"{e_energy:.6f}", "eps_first_median": f"{e_first:.6f}",
                     "residual": f"{residual:+.6f}"})
        print(f"eps_N = {eps:.4f}: {every.size} impacts in {first.size} of {runs} runs, median "
              f"speed {np.median(every):.3g} m/s (first impacts {median:.3g}); eps_E = "
              f"{e_energy:.4f}, eps at the first impacts' median = {e_first:.4f}; residual "
              f"{residual:+.4f}", flush=True)
        if abs(residual) < a.tol:
            break
        if residual < 0:
            below = (eps, residual)
        else:
            above = (eps, residual)
        if below is None or above is None:
            eps = image
            continue
        # Regula falsi on the bracket; the Illinois rule halves the stale end's residual.
        (x0, r0), (x1, r1) = below, above
        if residual < 0 and side == -1:
            r1 /= 2.0
            above = (x1, r1)
        elif residual > 0 and side == 1:
            r0 /= 2.0
            below = (x0, r0)
        side = -1 if residual < 0 else 1
        eps = x0 - r0 * (x1 - x0) / (r1 - r0)
        if abs(x1 - x0) < a.tol:
            break
    with open(os.path.join(a.work, "fixed_point.csv"), "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    last = rows[-1]
    print(f"fixed point: eps_N = {last['eps_N']} (residual {last['residual']}, {len(rows)} "
          f"iterates)")


if __name__ == "__main__":
    main()
