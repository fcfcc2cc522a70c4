#!/usr/bin/python3
"""Provenance of the cycling problems in lemke_test.cpp (TerminatesWhereIndexTieBreakingCycles).

Runs Lemke's method (covering vector e) in exact rational arithmetic with a naive tie-break of
the ratio test (first or last tied row, z0 preferred) on seeded random small-integer LCPs and
prints those on which the almost-complementary path revisits a (basis, entering variable) pair,
i.e. cycles forever. Run: /usr/bin/python3 tests/lcp/cycling_search.py
"""
import random
from fractions import Fraction as F


def lemke_naive(M, q, rule, max_pivots=60):
    n = len(q)
    rows = [[F(int(i == j)) for j in range(n)] + [F(-M[i][j]) for j in range(n)] + [F(-1), F(q[i])]
            for i in range(n)]
    basis, z0 = list(range(n)), 2 * n

    def pivot(r, col):
        p = rows[r][col]
        rows[r] = [x / p for x in rows[r]]
        for i in range(n):
            if i != r and rows[i][col] != 0:
                f = rows[i][col]
                rows[i] = [a - f * b for a, b in zip(rows[i], rows[r])]

    if min(q) >= 0:
        return 'trivial'
    q_min = min(r[-1] for r in rows)
    r = [i for i in range(n) if rows[i][-1] == q_min][0]
    leaving = basis[r]
    pivot(r, z0)
    basis[r], entering, seen = z0, leaving + n, set()
    for _ in range(max_pivots):
        key = (tuple(sorted(basis)), entering)
        if key in seen:
            return 'cycle'
        seen.add(key)
        rows_pos = [i for i in range(n) if rows[i][entering] > 0]
        if not rows_pos:
            return 'ray'
        ratio = min(rows[i][-1] / rows[i][entering] for i in rows_pos)
        ties = [i for i in rows_pos if rows[i][-1] / rows[i][entering] == ratio]
        z0_ties = [i for i in ties if basis[i] == z0]
        r = z0_ties[0] if z0_ties else (ties[0] if rule == 'first' else ties[-1])
        leaving = basis[r]
        pivot(r, entering)
        basis[r] = entering
        if leaving == z0:
            return 'solved'
        entering = leaving + n if leaving < n else leaving - n
    return 'limit'


random.seed(3)
found = 0
while found < 6:
    n = random.choice([3, 4])
    M = [[random.choice([-1, 0, 0, 1, 1, 2]) for _ in range(n)] for _ in range(n)]
    q = [random.choice([-1, -1, 0, 0, 1]) for _ in range(n)]
    if min(q) >= 0:
        continue
    for rule in ('first', 'last'):
        if lemke_naive(M, q, rule) == 'cycle':
            print(rule, M, q)
            found += 1
