#!/usr/bin/python3
"""The frictional full-edge impact criterion of docs/theory.md §4 (fact 2) against an independent
computation, and the solver's impacts against the same computation, over a grid of skew angle a,
skew ratio eta0, friction mu, restitution eps and incoming velocity direction phi.

The independent computation shares no code with the solver: it writes the impact of a free
translating deck (theta = 0, both corners P1 and P2 of the +x end on the face) in the paper's
closed forms (lever arms r_1, r_2, r_T; both corners have the same tangential Jacobian
(t, r_T), so their slip after the impact is one number) and enumerates every mode of the impact
laws: each corner active (Newton: gamma_N,E = -eps gamma_N,A) or not (no impulse, separating),
and the common slip after the impact positive, negative (Coulomb: the total friction impulse
T = -/+ mu P) or zero (stick, |T| <= mu P). Each mode is a 3 x 3 linear system in
(Lambda_N1, Lambda_N2, T); its solutions that satisfy every inequality are all the outcomes the
laws allow.

Asserted, per grid point:
1. the solver's outcome (SOLVER_EXE, tests/contact/full_edge_impact.cpp) is one of them;
2. when the deck slips through the impact (|gamma_T,A| > mu (1 + eps) |gamma_N,A|), with
   sigma = -sign(gamma_T,A) the sign of the friction impulse along t, an outcome without rotation
   exists iff r_2 + sigma mu r_T <= 0 <= r_1 + sigma mu r_T, i.e. iff
   -1 <= eta0 (1 + sigma mu / tan a) <= 1; above 1 every outcome turns the deck
   counter-clockwise with the acute corner P1 free of impulse, below -1 (possible only for
   mu > tan a) clockwise with P2 free;
3. when the deck sticks (|gamma_T,A| < mu (1 + eps) |gamma_N,A|), an outcome without rotation
   exists iff (r_T / (1 + eps)) tan psi lies in [r_2, r_1] (psi = a + phi);
4. a purely longitudinal approach (phi = 0) slips along +t (sigma = -1) whenever
   tan a > mu (1 + eps); sigma = +1 needs phi < -a - atan(mu (1 + eps)).

usage: check_full_edge_impact.py SOLVER_EXE"""
import itertools
import subprocess
import sys

import numpy as np

L = 30.0  # m, deck length of full_edge_impact.cpp (unit mass, unit approach speed)


def deck(a, eta0):
    """Lever arms r1, r2, rT (m) and rho^2 (m^2) of the uniform deck of length L."""
    W = L * np.sin(2 * a) / (2 * eta0)
    r1 = 0.5 * (L * np.sin(a) + W / np.cos(a))
    r2 = 0.5 * (L * np.sin(a) - W / np.cos(a))
    rT = 0.5 * L * np.cos(a)
    rho2 = (L**2 + W**2 / np.cos(a) ** 2) / 12.0
    return r1, r2, rT, rho2


def outcomes(a, eta0, mu, eps, phi):
    """Every outcome (L1, L2, T, vx, vy, omega) the impact laws allow, by mode enumeration."""
    r1, r2, rT, rho2 = deck(a, eta0)
    n = np.array([-np.cos(a), np.sin(a)])
    t = np.array([np.sin(a), np.cos(a)])
    v = np.array([np.cos(phi), np.sin(phi)])
    gN, gT = n @ v, t @ v
    # Post-impact velocities are affine in z = (L1, L2, T): gamma = g0 + G z.
    r = np.array([r1, r2])
    GN = np.array([[1 + r[i] * r1 / rho2, 1 + r[i] * r2 / rho2, r[i] * rT / rho2]
                   for i in range(2)])
    GT = np.array([rT * r1 / rho2, rT * r2 / rho2, 1 + rT * rT / rho2])
    scale = 1.0 + abs(gN) + abs(gT)
    tol = 1e-9 * scale
    found = []
    for active, slip in itertools.product(itertools.product((True, False), repeat=2),
                                          (+1, -1, 0)):
        A, b = [], []
        for i in range(2):
            if active[i]:
                A.append(GN[i]), b.append(-eps * gN - gN)  # Newton
            else:
                A.append(np.eye(3)[i]), b.append(0.0)      # no impulse
        if slip == 0:
            A.append(GT), b.append(-gT)                     # stick
        else:
            A.append([mu * slip, mu * slip, 1.0]), b.append(0.0)  # T = -slip mu P
        A, b = np.array(A), np.array(b)
        if abs(np.linalg.det(A)) < 1e-12 * np.abs(A).max() ** 3:
            continue
        z = np.linalg.solve(A, b)
        L1, L2, T = z
        P = L1 + L2
        gNE = gN + GN @ z
        gTE = gT + GT @ z
        ok = L1 >= -tol and L2 >= -tol and all(gNE[i] >= -eps * gN - tol for i in range(2))
        ok = ok and (slip != 0 or abs(T) <= mu * P + tol)
        ok = ok and (slip == 0 or slip * gTE >= -tol)
        if ok:
            vE = v + n * P + t * T
            omega = (r1 * L1 + r2 * L2 + rT * T) / rho2
            found.append(np.array([L1, L2, T, vE[0], vE[1], omega]))
    return found, gN, gT


def main():
    exe = sys.argv[1]
    grid = [(a_deg, eta0, mu, eps, phi_deg)
            for a_deg in (10, 20, 30, 45, 60, 70)
            for eta0 in (0.5, 0.8, 0.87, 0.95, 1.02, 1.07, 1.2, 1.5, 2.0, 3.0)
            for mu in (0.0, 0.05, 0.08, 0.1, 0.2, 0.3)
            for eps in (0.0, 0.5)
            for phi_deg in range(-85, 90, 10)
            if np.cos(np.radians(a_deg + phi_deg)) > 0.05]  # approaching the face
    text = "".join(f"{a} {e} {m} {p} {f}\n" for a, e, m, p, f in grid)
    out = subprocess.run([exe], input=text, capture_output=True, text=True, check=True).stdout
    solver = np.array([[float(s) for s in line.split()] for line in out.splitlines()])
    assert solver.shape == (len(grid), 7), solver.shape
    failures, counts = [], {"slip_no_rotation": 0, "slip_rotation": 0, "stick": 0,
                            "several_outcomes": 0, "skipped_borderline": 0, "clockwise": 0}
    for (a_deg, eta0, mu, eps, phi_deg), row in zip(grid, solver):
        a, phi = np.radians(a_deg), np.radians(phi_deg)
        found, gN, gT = outcomes(a, eta0, mu, eps, phi)
        where = f"a {a_deg} eta0 {eta0} mu {mu} eps {eps} phi {phi_deg}"
        if not found:
            failures.append(f"{where}: the enumeration found no outcome")
            continue
        counts["several_outcomes"] += len(found) > 1
        # 1. The solver's outcome is one the laws allow (sum of its tangential impulses).
        mine = np.array([row[0], row[1], row[2] + row[3], row[4], row[5], row[6]])
        if not any(np.allclose(mine, f, rtol=1e-7, atol=1e-8) for f in found):
            failures.append(f"{where}: solver {mine} not among {found}")
        # 2. The criterion, where the deck slips through the impact.
        r1, r2, rT, rho2 = deck(a, eta0)
        margin = abs(gT) - mu * (1 + eps) * abs(gN)
        sigma = -np.sign(gT)
        lever2, lever1 = r2 + sigma * mu * rT, r1 + sigma * mu * rT
        if margin < -1e-6:
            # Stick: no rotation iff (r_T / (1 + eps)) tan psi lies in [r_2, r_1].
            counts["stick"] += 1
            arm = rT * gT / ((1 + eps) * abs(gN))
            if min(abs(arm - r2), abs(arm - r1)) < 1e-6 * L:
                continue
            still = any(abs(f[5]) <= 1e-9 for f in found)
            if still != (r2 < arm < r1):
                failures.append(f"{where}: stick, r_T tan psi / (1 + eps) = {arm} against "
                                f"[{r2}, {r1}], an outcome without rotation: {still}")
            continue
        if margin < 1e-6 or min(abs(lever2), abs(lever1)) < 1e-6 * L:
            counts["skipped_borderline"] += 1
            continue
        eta_sigma = eta0 * (1 + sigma * mu / np.tan(a))
        if (lever2 <= 0) != (eta_sigma <= 1) or (lever1 >= 0) != (eta_sigma >= -1):
            failures.append(f"{where}: levers {lever2}, {lever1} but eta0 (1 + sigma mu / tan a)"
                            f" = {eta_sigma}")
        still = [f for f in found if abs(f[5]) <= 1e-9]
        if lever2 <= 0 <= lever1:
            counts["slip_no_rotation"] += 1
            if not still:
                failures.append(f"{where}: predicted no rotation, every outcome turns: {found}")
        else:
            counts["slip_rotation"] += 1
            if still:
                failures.append(f"{where}: predicted rotation, an outcome does not turn: {still}")
            # eta_sigma > 1: P1 free, counter-clockwise; eta_sigma < -1 (mu > tan a only): P2
            # free, clockwise.
            free, sense = (0, 1.0) if lever2 > 0 else (1, -1.0)
            counts["clockwise"] += sense < 0
            for f in found:
                if not (sense * f[5] > 0 and abs(f[free]) <= 1e-9):
                    failures.append(f"{where}: rotating outcome {f}: expected P{free + 1} free "
                                    f"of impulse and omega of sign {sense:+g}")
        # 4. The slip direction of a purely longitudinal approach.
        if phi_deg == 0 and np.tan(a) > mu * (1 + eps) and sigma != -1:
            failures.append(f"{where}: a longitudinal approach slips along -t")
        if sigma == +1 and not phi < -a - np.arctan(mu * (1 + eps)):
            failures.append(f"{where}: sigma = +1 outside phi < -a - atan(mu (1 + eps))")
    print(f"{len(grid)} impacts: {counts}")
    for f in failures[:20]:
        print("FAIL", f)
    if failures:
        print(f"{len(failures)} failures")
        return 1
    # The grid must exercise both sides of the criterion with both slip directions.
    assert counts["slip_no_rotation"] > 100 and counts["slip_rotation"] > 100, counts
    return 0


if __name__ == "__main__":
    sys.exit(main())
