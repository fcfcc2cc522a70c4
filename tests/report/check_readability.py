#!/usr/bin/python3
"""Checks that scripts/report draws figures a journal would print, by running the report
in-process and inspecting each figure just before it is saved, then the saved image:

- no legend overlaps the data area of any panel, and none lists more than MAX_LEGEND curves plus
  its reference lines; a sweep with more curves gets a colour bar instead;
- every log axis has three or more plain tick labels in view (never a lone 10^0);
- axis labels, panel titles and legend entries use symbols, never identifiers (eta0, Pi_delta,
  eps_N, w0_over_wg, a_deg, W0_over_w0);
- every symbol used in a label (rho, eta_0, Pi_delta, alpha, omega_0, L_e, g_N, gamma_T) is
  defined in the figure's caption;
- panels of counts (impacts) have integer ticks; every dashed reference line is in a legend;
  every panel has data or says "no data"/"no ...";
- in the PNG, the caption band under the lowest axis label holds ink (the caption is drawn);
- the history figure's gamma_T agrees with a finite difference of the corner's tangential
  position t . ((x, y) + R(theta) p) computed here from q (an independent second method), and
  its ground acceleration with the model's samples.

With --paper it checks scripts/paper instead, run in-process on a work folder of finished cubes
(paper_test.sh's second run):

- every figure's title starts with the paper's figure number its file is named for ("Fig. 7",
  "Fig. 13a", "After Fig. 10" for an extension) and names no sweep of jobs/specs/;
- one correlation statistic per claim: the pilot-bridge sections of paper.md state Spearman's
  rho_s (paper_claims.STATISTIC) and no other (no Pearson r, log-log slope or R^2), and
  docs/validation.md states the same one for the same claims.

usage: check_readability.py SOURCE_ROOT OUT_DIR CUBE.h5... --run RUN.h5...
       check_readability.py SOURCE_ROOT --paper EXE MPIEXEC WORK_DIR OUT_DIR"""
import glob
import os
import re
import sys
import tomllib

import matplotlib.image
import numpy as np

ROOT = sys.argv[1]
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from skewbridge_report import cli, common, data, figures  # noqa: E402

IDENTIFIERS = re.compile(r"\b(eta0|Pi_delta|eps_N|w0_over_wg|a_deg|W0_over_w0)\b")
# A symbol in a label (mathtext source) and the text its caption definition starts with.
DEFINED = {r"\rho": "ρ:", r"\rho_s": "ρ_s:", r"\eta_0": "η_0", r"\Pi_\delta": "Π_δ", r"\alpha": "α:",
           r"\omega_0": "ω_0", r"L_e": "L_e", r"g_N": "g_N", r"\gamma_T": "γ_T",
           r"T_g": "T_g =", r"$K$ factor": "K factor:", r"\theta_{end}": "θ_end:",
           "worst deck": "worst deck:", "median of the records": "the median over the records"}

checked = []


def visible_texts(fig):
    """Axis labels, panel titles and legend entries (the suptitle names the sweep: not here)."""
    out = []
    for ax in fig.axes:
        out += [ax.get_xlabel(), ax.get_ylabel(), ax.get_title()]
        legend = ax.get_legend()
        if legend:
            out += [t.get_text() for t in legend.get_texts()]
    return [t for t in out if t]


def check_figure(fig, name):
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    data_axes = [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]
    caption = " ".join(t.get_text() for t in fig.texts)
    assert caption, f"{name}: no caption"
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend()]
    for legend in legends:
        box = legend.get_window_extent(renderer)
        for ax in data_axes:
            inter = box.intersection(box, ax.get_window_extent(renderer))
            assert inter is None or inter.width * inter.height < 1.0, \
                f"{name}: a legend overlaps the data of panel '{ax.get_title()}'"
        entries = len(legend.get_texts())
        assert entries <= common.MAX_LEGEND + 3, f"{name}: a legend of {entries} entries"
    labelled = {t.get_text() for legend in legends for t in legend.get_texts()}
    for text in visible_texts(fig):
        assert not IDENTIFIERS.search(text.replace("$", "")), f"{name}: identifier in '{text}'"
        for symbol, definition in DEFINED.items():
            # rho_s (Spearman's) is its own symbol, not the radius of gyration rho
            if symbol in (text.replace(r"\rho_s", "") if symbol == r"\rho" else text):
                assert definition in caption, f"{name}: '{symbol}' of '{text}' not in caption"
    for ax in data_axes:
        for axis, scale in ((ax.xaxis, ax.get_xscale()), (ax.yaxis, ax.get_yscale())):
            if scale != "log" or not ax.lines:
                continue
            lo, hi = sorted(axis.get_view_interval())
            ticks = [t for t in axis.get_major_locator()() if lo <= t <= hi]
            labels = [axis.get_major_formatter()(t) for t in ticks]
            assert len([t for t in labels if t]) >= 3, f"{name}: log axis labels {labels}"
        if "impacts" in ax.get_ylabel():
            ticks = ax.get_yticks()
            assert np.allclose(ticks, np.round(ticks)), f"{name}: fractional count ticks {ticks}"
        dashed = [line for line in ax.lines if line.get_linestyle() not in ("-", "None", "")
                  and len(line.get_xdata()) == 2 and line.get_label().startswith("_")]
        # an axvline/axhline is two points; a dashed one must be explained in some legend
        for line in dashed:
            xs = np.asarray(line.get_xdata(), dtype=float)
            if xs[0] == xs[1]:
                assert any("=" in t for t in labelled), f"{name}: unlabelled reference line"
        has_data = any(np.any(np.isfinite(np.asarray(line.get_ydata(), dtype=float)))
                       for line in ax.lines)
        says_no = any(t.get_text().startswith(("no ", "ground acceleration not"))
                      for t in ax.texts)
        assert has_data or says_no, f"{name}: empty panel '{ax.get_ylabel()}' without a note"
        if name.startswith(("response_vs_axis", "unseating_margins")):
            # the generic figures draw lengths and angles in mm/mrad or um/urad as needed, so
            # that no tick label carries a power of ten the eye has to apply
            offset = ax.yaxis.get_offset_text().get_text()
            assert not offset, f"{name}: y ticks scaled by '{offset}' in '{ax.get_ylabel()}'"
    colorbars = [ax for ax in fig.axes if ax.get_label() == "<colorbar>"]
    checked.append((name, len(legends), len(colorbars)))


def check_png(path):
    """The caption band: ink in the bottom 3 % of the image (the caption is drawn)."""
    img = matplotlib.image.imread(path)
    grey = img[..., :3].mean(axis=2)
    band = grey[-int(0.03 * grey.shape[0]):]
    assert np.mean(band < 0.8) > 0.002, f"{path}: no caption under the panels"


def check_gamma_t(run_path):
    """gamma_T of the figure's code against d/dt of t . ((x, y) + R(theta) p) by central
    differences over the samples, away from impacts (where gamma_T jumps)."""
    run = data.load_run(run_path)
    gamma = figures.tangential_velocity(run)
    assert gamma is not None, run_path
    model = figures.model_of(run)
    deck = model["deck"]
    a = np.radians(deck["skew_deg"])
    length = deck["L"]
    width = deck["W"] if "W" in deck else length * np.sin(2 * a) / (2 * deck["eta0"])
    t, q = run.t_s, run.q
    worst = 0.0
    for c, name in enumerate(run.contact_names):
        side = 1 if name in ("P1", "P2") else -1
        sign_y = 1 if name in ("P1", "P4") else -1
        px = side * length / 2 + sign_y * width / 2 * np.tan(a)
        py = sign_y * width / 2
        tangent = np.array([side * np.sin(a), side * np.cos(a)])
        rx = q[:, 0] + np.cos(q[:, 2]) * px - np.sin(q[:, 2]) * py
        ry = q[:, 1] + np.sin(q[:, 2]) * px + np.cos(q[:, 2]) * py
        s = tangent[0] * rx + tangent[1] * ry
        ds = (s[2:] - s[:-2]) / (t[2:] - t[:-2])
        near = np.zeros(len(t) - 2, dtype=bool)
        for te in run.event_t_s:
            near |= np.abs(t[1:-1] - te) < 3 * (t[1] - t[0])
        scale = np.max(np.abs(gamma[:, c]))
        err = np.max(np.abs(ds[~near] - gamma[1:-1, c][~near])) / scale
        worst = max(worst, err)
    # central differences at 5 ms on motions of about 0.5 s period: error ~ (w h)^2 / 6 ~ 0.1 %
    assert worst < 5e-3, f"{run_path}: gamma_T against finite differences: {worst:.2e}"
    print(f"{os.path.basename(run_path)}: gamma_T agrees with finite differences to {worst:.1e}")


def check_ground(run_path):
    run = data.load_run(run_path)
    a_g, _ = figures.ground_acceleration(run)
    ex = figures.model_of(run)["excitation"]
    values = np.asarray(ex["values"], dtype=float)
    k = np.searchsorted(run.t_s, np.arange(len(values)) * ex["dt_s"])
    hit = k < len(run.t_s)
    assert np.allclose(a_g[k[hit]], values[hit], atol=1e-9), (a_g[k[hit]], values[hit])
    print(f"{os.path.basename(run_path)}: ground acceleration matches the model's samples")


def figure_title(fig):
    """The figure's title: its suptitle, else the title of its first panel."""
    if fig._suptitle is not None and fig._suptitle.get_text():
        return fig._suptitle.get_text()
    return fig.axes[0].get_title() if fig.axes else ""


def paper_number(name):
    """The title prefix a figure file of scripts/paper must carry: fig07_... -> "Fig. 7",
    fig13a_... -> "Fig. 13a", fig13x_... -> "After Fig. 13", ext_... -> "After Fig. 10"."""
    if name.startswith("ext_"):
        return "After Fig. 10"
    m = re.match(r"fig(\d+)([a-z]?)_", name)
    assert m, f"{name}: not named after a figure of the paper"
    if m.group(2) == "x":
        return f"After Fig. {int(m.group(1))}"
    return f"Fig. {int(m.group(1))}{m.group(2)}"


def sweep_names(root):
    """The [sweep] names of every specification under jobs/specs/."""
    names = set()
    for path in glob.glob(os.path.join(root, "jobs", "specs", "**", "*.toml"), recursive=True):
        with open(path, "rb") as f:
            doc = tomllib.load(f)
        if "sweep" in doc and "name" in doc["sweep"]:
            names.add(doc["sweep"]["name"])
    return names


# Correlation statistics other than the one of the pilot-bridge claims.
OTHER_STATISTICS = re.compile(r"Pearson|r_log|log-log slope|slope|R²|R\^2|\br = ")


def check_statistic(md, validation, statistic):
    """One correlation statistic per claim: the Fig. 13 section of paper.md and its rows of the
    claim table name `statistic` (its symbol ρ_s) and no other; docs/validation.md's rows and
    section on the pilot bridge's persistency claim do the same."""
    section = md.split("\n## Fig. 13")[1].split("\n## ")[0]
    rows = [line for line in md.splitlines() if line.startswith("| pilot bridge")]
    assert statistic in section, f"paper.md: Fig. 13 does not name {statistic}"
    for text in [section] + rows:
        bad = OTHER_STATISTICS.search(text)
        assert not bad, f"paper.md: a second statistic '{bad.group(0)}' in '{text[:80]}...'"
        assert "ρ_s" in text or "persistency" not in text, f"paper.md: no ρ_s in '{text[:80]}'"
    pilot = validation.split("### The pilot bridge")[1].split("\n### ")[0] \
        if "### The pilot bridge" in validation else ""
    row = next(line for line in validation.splitlines()
               if line.startswith("| §6 pilot: theta_m grows with persistency"))
    for text in (row, pilot):
        assert text, "docs/validation.md: no pilot-bridge section"
        bad = OTHER_STATISTICS.search(text)
        assert not bad, f"docs/validation.md: a second statistic '{bad.group(0)}'"
        assert "ρ_s" in text, "docs/validation.md: the pilot claim does not state ρ_s"
    print(f"one statistic per claim: {statistic} in paper.md and docs/validation.md")


def paper_main(root, exe, mpiexec, work, out):
    from skewbridge_report import paper, paper_claims
    names = sweep_names(root)
    titles = []
    save = common.save

    def titled_save(fig, out_dir, name, pdf):
        title = figure_title(fig)
        want = paper_number(name)
        assert title.startswith(want + ":") or title.startswith(want + " ") or \
            title.startswith(want + ","), f"{name}: title '{title}' does not start '{want}'"
        named = [n for n in names if re.search(rf"(?<![\w-]){re.escape(n)}(?![\w-])", title)]
        assert not named, f"{name}: title names the sweep {named}: '{title}'"
        assert not IDENTIFIERS.search(title.replace("$", "")), f"{name}: identifier in title"
        titles.append((name, title))
        return save(fig, out_dir, name, pdf)

    common.save = titled_save
    try:
        status = paper.main(["--quick", "--exe", exe, "--mpiexec", mpiexec, "--work", work,
                             "--out", out])
    finally:
        common.save = save
    assert status == 0, f"scripts/paper --quick: status {status}"
    assert len(titles) >= 15, titles
    for name, title in titles:
        print(f"{name}: '{title[:60]}...'")
    with open(os.path.join(out, "paper.md"), encoding="utf-8") as f:
        md = f.read()
    with open(os.path.join(root, "docs", "validation.md"), encoding="utf-8") as f:
        validation = f.read()
    check_statistic(md, validation, paper_claims.STATISTIC)
    print("check_readability --paper: ok")


def main(argv):
    if argv[1] == "--paper":
        return paper_main(argv[0], *argv[2:6])
    out = argv[1]
    save = common.save

    def inspecting_save(fig, out_dir, name, pdf):
        check_figure(fig, name)
        return save(fig, out_dir, name, pdf)

    common.save = inspecting_save
    assert cli.main(argv[2:] + ["--out", out, "--allow-partial"]) == 0
    for f in sorted(os.listdir(out)):
        if f.endswith(".png"):
            check_png(os.path.join(out, f))
    for name, n_legends, n_colorbars in checked:
        print(f"{name}: {n_legends} legends, {n_colorbars} colour bars: readable")
    if any(os.path.basename(a) == "many.h5" for a in argv):
        many = [c for c in checked if c[0].startswith("spectra_many")]
        assert many and many[0][2] == 1, f"more than {common.MAX_LEGEND} curves: no colour bar"
    runs = [argv[i + 1] for i, a in enumerate(argv) if a == "--run"]
    for path in runs:
        check_gamma_t(path)
    if runs:
        check_ground(next(p for p in runs if "push" in p))
    print("check_readability: ok")


if __name__ == "__main__":
    main(sys.argv[1:])
