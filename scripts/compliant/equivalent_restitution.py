#!/usr/bin/python3
"""The equivalent restitution of a backfill over the approach speeds a rigid study produced
(docs/compliant.md §5): `skewbridge restitution --csv` over a range of speeds and at the
16/50/84 % of the first-impact speeds that scripts/compliant/approach_speeds.py collected, and
the energy-equivalent restitution of all the impacts, eps_E^2 = sum v^2 e(v)^2 / sum v^2 (the rigid
law at eps_E takes out of those impacts the kinetic energy the backfill would absorb at their
speeds), and one figure per bridge: eps_N, contact duration and permanent set against the
approach speed, with the distribution of the speeds beneath.

    scripts/compliant/equivalent_restitution.py build/release/skewbridge --out DIR \
        --bridge NAME SPEEDS.csv MASS_KG "LAW OPTIONS" [--bridge ...]

LAW OPTIONS are the options of `skewbridge restitution` that give the law, e.g.
"--k-max-Npm 393008000 --r-f 0.7 --f-ult-N 6311360". Writes DIR/restitution_NAME.png and
DIR/restitution.csv (one row per bridge and percentile).
"""
import argparse
import csv
import io
import os
import shlex
import subprocess

import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def restitution(exe, mass, law, speeds):
    cmd = [exe, "restitution", "--mass-kg", repr(mass), *shlex.split(law), "--csv",
           "--velocity-mps", *[repr(float(v)) for v in speeds]]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return list(csv.DictReader(io.StringIO(out)))


def energy_equivalent(exe, mass, law, every, first):
    """The energy-equivalent restitution eps_E of the impacts at the speeds `every` (m/s),
    eps_E^2 = sum v^2 e(v)^2 / sum v^2, with e(v) interpolated in log v between 60 strikes on a
    geometric grid over the speeds of `every` and `first`; returns (eps_E, the grid's rows of
    `skewbridge restitution --csv`, the grid's ends lo and hi)."""
    lo, hi = max(min(every.min(), first.min()) * 0.9, 1e-3), max(every.max(), first.max()) * 1.1
    g = restitution(exe, mass, law, np.geomspace(lo, hi, 60))
    v = np.array([float(r["approach_mps"]) for r in g])
    e_of = np.array([float(r["restitution"]) for r in g])
    e_every = np.interp(np.log(every), np.log(v), e_of)
    return float(np.sqrt(np.sum(every**2 * e_every**2) / np.sum(every**2))), g, lo, hi


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("exe")
    p.add_argument("--out", required=True)
    p.add_argument("--bridge", nargs=4, action="append", required=True,
                   metavar=("NAME", "SPEEDS_CSV", "MASS_KG", "LAW"))
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    table = []
    for name, speeds_csv, mass, law in a.bridge:
        mass = float(mass)
        rows = list(csv.DictReader(open(speeds_csv)))
        first = np.array([float(r["first_speed_mps"]) for r in rows])
        first = first[np.isfinite(first)]
        every = np.array([float(x) for r in rows for x in r["speeds_mps"].split(";") if x])
        pct = np.percentile(first, [16, 50, 84])
        at = restitution(a.exe, mass, law, pct)
        for q, r in zip((16, 50, 84), at):
            table.append({"bridge": name, "percentile": q, **r})
            print(f"{name}: first-impact speed {q} % {float(r['approach_mps']):.4g} m/s: "
                  f"eps_N {float(r['restitution']):.4f}, contact {float(r['contact_duration_s']):.4g} s, "
                  f"permanent set {1e3 * float(r['permanent_set_m']):.4g} mm")
        e_energy, g, lo, hi = energy_equivalent(a.exe, mass, law, every, first)
        v = np.array([float(r["approach_mps"]) for r in g])
        print(f"{name}: {every.size} impacts, {first.size} runs with impacts; speeds of every impact "
              f"16/50/84 % {np.percentile(every, 16):.3g} / {np.median(every):.3g} / "
              f"{np.percentile(every, 84):.3g} m/s; energy-equivalent eps_E = {e_energy:.4f}")
        table.append({"bridge": name, "percentile": "energy", "approach_mps": "",
                      "restitution": f"{e_energy:.9g}"})
        fig, ax = plt.subplots(4, 1, figsize=(7, 9), sharex=True,
                               gridspec_kw={"height_ratios": [2, 1.3, 1.3, 1.2]})
        ax[0].plot(v, [float(r["restitution"]) for r in g], "k-")
        for q, r in zip((16, 50, 84), at):
            ax[0].plot(float(r["approach_mps"]), float(r["restitution"]), "o", color="C3")
            ax[0].annotate(f"first impacts' {q} %: {float(r['restitution']):.2f}",
                           (float(r["approach_mps"]), float(r["restitution"])),
                           textcoords="offset points", xytext=(6, 6), fontsize=8)
        ax[0].axhline(0.5, color="0.6", ls="--", lw=0.8)
        ax[0].axhline(e_energy, color="C0", ls=":", lw=1.0)
        ax[0].text(v[0], e_energy - 0.06, f"energy-equivalent over every impact: {e_energy:.2f}",
                   fontsize=8, color="C0")
        ax[0].text(v[0], 0.51, "eps_N = 0.5 (the rigid studies' default)", fontsize=8, color="0.4")
        ax[0].set_ylabel("equivalent eps_N")
        ax[0].set_ylim(0, 1)
        ax[0].set_title(f"{name}: a point mass of {mass / 1e3:.0f} t striking its backfill")
        ax[1].plot(v, [float(r["contact_duration_s"]) for r in g], "k-")
        ax[1].set_ylabel("contact (s)")
        ax[1].set_yscale("log")
        ax[1].yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax[1].yaxis.set_minor_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax[2].plot(v, [1e3 * float(r["permanent_set_m"]) for r in g], "k-")
        ax[2].set_ylabel("permanent set (mm)")
        ax[2].set_yscale("log")
        ax[3].hist(every, bins=np.geomspace(lo, hi, 40), color="0.75", label="every impact")
        ax[3].hist(first, bins=np.geomspace(lo, hi, 40), histtype="step", color="C3",
                   label="first impact of a run")
        ax[3].set_ylabel("impacts")
        ax[3].legend(fontsize=8)
        ax[3].set_xscale("log")
        ax[3].set_xlabel("approach speed normal to the backwall (m/s)")
        for x in ax:
            x.grid(True, which="both", lw=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(a.out, f"restitution_{name}.png"), dpi=110)
        plt.close(fig)
    with open(os.path.join(a.out, "restitution.csv"), "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(table[0].keys()), restval="")
        w.writeheader()
        w.writerows(table)


if __name__ == "__main__":
    main()
