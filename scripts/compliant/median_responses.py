#!/usr/bin/python3
"""Medians over the records of a cube's responses at its stripes (docs/compliant.md §5): the numbers
the comparison of the joint laws quotes (the largest rotation, corner travel, translations, the
backfill's deformation, strikes), one Markdown row per cube, stripe and combination.

    scripts/compliant/median_responses.py "rigid=pilot-rigid.h5" "compliant=pilot-compliant.h5" \\
        --fix a_deg=20 --fix seat_over_L=0.0005 --fix eps_N=0.5 --stripes 5 8 11 \\
        --response theta_m_d0 --response travel_m_d0 --response x_m_d0

A cube is LABEL=FILE; --fix AXIS=VALUE picks a coordinate (ignored by a cube without that axis; an
axis left free takes its first coordinate); --stripes are indices of im_g. A response a cube does
not store prints "–". Lengths in m, rotations in rad, forces in N, as the cube stores them. A
break time (key_break_time_px, _mx) is inf where the keys were left intact and enters the median
as such: "inf" when more than half the records leave them intact (keys_broken counts the breaks).
"""
import argparse
import sys

import h5py
import numpy as np


def decode(v):
    return v.decode() if isinstance(v, bytes) else v


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("cubes", nargs="+", metavar="LABEL=FILE")
    p.add_argument("--fix", action="append", default=[], metavar="AXIS=VALUE")
    p.add_argument("--stripes", type=int, nargs="+", required=True)
    p.add_argument("--response", action="append", required=True)
    a = p.parse_args()
    fixed = dict(f.split("=", 1) for f in a.fix)
    head = ["cube"] + list(fixed) + ["IM"] + a.response
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for spec in a.cubes:
        label, path = spec.rsplit("=", 1)
        f = h5py.File(path, "r")
        s = f["sweeps"][list(f["sweeps"].keys())[0]]
        order = [decode(x) for x in s.attrs["axis_order"]]
        if order[:2] != ["record", "im_g"]:
            sys.exit(f"median_responses: {path}: expected the axes record, im_g first ({order})")
        for k in a.stripes:
            idx = [slice(None), k]
            for x in order[2:]:
                coords = s["axes"][x][...]
                if x in fixed:
                    hits = np.flatnonzero(np.abs(coords - float(fixed[x]))
                                          <= 1e-9 * np.abs(coords))
                    if hits.size == 0:
                        sys.exit(f"median_responses: {path}: {x}={fixed[x]}: not a coordinate")
                    idx.append(int(hits[0]))
                else:
                    idx.append(0)
            cells = [fixed[x] if x in order else "–" for x in fixed]
            values = [f"{np.median(s[r][tuple(idx)]):.3g}" if r in s else "–" for r in a.response]
            row = [label] + cells + [f"{s['axes']['im_g'][k]:.3g}"] + values
            print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()
