"""The `scripts/report` command: read cubes and run files, decide which figures each sweep
supports from its axes (planning.py), write them and a Markdown summary (summary.md) with the
tables."""
import argparse
import os
import re
import sys

import numpy as np

from . import (common, figures, fragility, generic, ida, incidence, planning, response_spectra,
               risk)
from . import plan as plan_view
from .data import ReportError, as_text, load_cube, load_run

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))


def _safe(name):
    return re.sub(r"[^A-Za-z0-9_.-]", "_", name)


def _fmt(v):
    if isinstance(v, str):
        return v
    if v is None or (isinstance(v, float) and not np.isfinite(v)):
        return "–"
    if isinstance(v, (bool, np.bool_)):
        return "yes" if v else "no"
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    if abs(v) < common.ZERO:
        return "0"
    return f"{v:.4g}"


def _table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(_fmt(v) for v in row) + " |" for row in rows]
    return "\n".join(lines)


def _status_counts(sweep):
    codes, counts = np.unique(sweep.status, return_counts=True)
    return ", ".join(f"{sweep.status_names.get(int(c), str(int(c)))} {int(n)}"
                     for c, n in zip(codes, counts))


# The cube's correlation/ datasets (docs/hdf5-layout.md) and the report's own statistics.
STORED_STATISTICS = {"pearson_theta_Le": "pearson", "spearman_theta_Le": "spearman",
                     "loglog_slope": "slope", "loglog_intercept": "intercept",
                     "loglog_r2": "r2", "n": "n", "loglog_n": "n_log"}


def _compare_stored(own, stored):
    """'agree' when every stored statistic equals the report's to 1e-9 (NaN equal to NaN),
    else the ones that differ with both values."""
    differ = []
    for name, key in STORED_STATISTICS.items():
        if name not in stored:
            continue
        a, b = float(stored[name]), float(own[key])
        same = (np.isnan(a) and np.isnan(b)) or abs(a - b) <= 1e-9 * max(1.0, abs(a), abs(b))
        if not same:
            differ.append(f"{name} {a:.6g} (report {b:.6g})")
    return "agree" if not differ else "differ: " + "; ".join(differ)


# The section heading of each figure kind in summary.md.
KIND_TITLE = {"spectra": "spectra", "pi_delta_family": "the Π_δ family",
              "rotation_vs_eta0": "rotation against η_0",
              "correlation_theta_vs_Le": "θ_m against the persistency L_e",
              "correlation_rotation_vs_w0x": "θ_m ρ ω_g²/a_g against ω_0x/ω_g by group"}


def _peak_cells(peak, at, edge, zero):
    """The two cells of a peak: its value and where it is, "no response" for a curve that is 0
    everywhere, the abscissa flagged when the peak sits at the edge of the grid."""
    if zero:
        return ["0", "no response"]
    if peak is None:
        return [None, None]
    return [peak, _fmt(at) + (" (grid edge)" if edge else "")]


def _tables_for(kind, sweep, rows, curve_key):
    curve = common.AXIS_TEXT.get(curve_key, curve_key or "")
    w_label = "ω_0x/ω_g" if sweep.family == "pilot-bridge" else "ω_0/ω_g"
    if kind in ("spectra", "pi_delta_family"):
        by_key = {}
        for pulse, value, resp, peak, w, edge, zero in rows:
            by_key.setdefault((pulse, value), {})[resp] = (peak, w, edge, zero)
        out = []
        for (pulse, value), d in by_key.items():
            row = [pulse, value]
            for resp in ("x_norm", "y_norm", "theta_norm"):
                row += _peak_cells(*d.get(resp, (None, None, False, False)))
            out.append(row)
        header = ["pulse", curve or "-"]
        for resp in ("x_norm", "y_norm", "theta_norm"):
            header += [f"max {common.RESPONSE_TEXT[resp]}", f"{w_label} at max"]
        return _table(header, out)
    if kind == "rotation_vs_eta0":
        out = [[pulse, value, eta] + _peak_cells(peak, where, edge, zero) + [n_imp]
               for pulse, value, eta, peak, where, n_imp, edge, zero in rows]
        return _table(["pulse", curve or "-", "η_0", "max θ_m ρ ω_g²/a_g", f"{w_label} at max",
                       "impacts at max"], out)
    if kind == "correlation_theta_vs_Le":
        out = []
        stored_any = any(stored for _, _, _, stored in rows)
        for pi, own, own_hit, stored in rows:
            for group, stats_row in (("all records", own), ("records that strike", own_hit)):
                if stats_row is None:
                    continue
                row = [pi, group, stats_row["n"], stats_row["pearson"], stats_row["spearman"],
                       stats_row["slope"], stats_row["intercept"], stats_row["r2"],
                       stats_row["n_log"]]
                if stored_any:
                    row.append(_compare_stored(own, stored) if stored and stats_row is own
                               else "–")
                out.append(row)
        header = ["Π_δ", "group", "records", "Pearson r", "Spearman r_s", "log-log slope",
                  "intercept", "R²", "pairs with θ_m > 0"]
        if stored_any:
            header.append("the cube's correlation/ statistics")
        return _table(header, out)
    if kind == "correlation_rotation_vs_w0x":
        return _table(["Π_δ", "group", "records", "median θ_m ρ ω_g²/a_g", "max"], rows)
    return ""


SYMBOLS_MD = ["## Symbols", "",
              *[f"- {text}" for text in common.SYMBOLS.values()],
              "- A normalised maximum is dimensionless: x_m ω_g²/a_g, y_m ω_g²/a_g, "
              "θ_m ρ ω_g²/a_g.",
              f"- Values below {common.ZERO:g} in magnitude are printed as 0; a curve whose "
              "largest value is 0 is marked \"no response\" and has no abscissa of its maximum.",
              "- \"(grid edge)\": the maximum sits at the first or last grid value, so the true "
              "peak may lie outside the grid.", ""]


def _unique(name, used):
    name = _safe(name)
    while name in used:
        name += "_"
    used.add(name)
    return name


def generic_sections(sweep, args, used, written, skipped_all):
    """The generic figures of one sweep (planning.plan_generic) and its tables: the fixed
    parameters, every response over the grid, the unseating margins, the record table."""
    md = []
    fixed = [(k, _fmt(v), generic.axis_unit(sweep, k) or
              ("1" if sweep.fixed_units.get(k) == "1" else "–"))
             for k, v in sweep.fixed.items()]
    md += [f"## {sweep.name}: fixed parameters", "",
           _table(["parameter", "value", "unit"], fixed) if fixed else
           "None: the parameters on no axis take the family's defaults.", ""]
    if sweep.floored_cells:
        md += [f"Rotations below the cube's round-off floor round_off_floor_rad = "
               f"{sweep.round_off_floor_rad:g} rad are 0 in every figure and table "
               f"({sweep.floored_cells} values, with their normalised twins; on a log axis a 0 "
               "is not drawn).", ""]
    todo, skipped = planning.plan_generic(sweep)
    for kind, reason in skipped:
        skipped_all.append((sweep.name, kind, reason))
    drawn, margins = planning.drawn_quantities(sweep)
    for kind, x in todo:
        if kind == "response_vs_intensity":
            name = _unique(f"{kind}_{sweep.name}", used)
            path, rows = generic.response_vs_intensity(sweep, drawn, args.out, name, args.pdf)
            written.append(path)
            text = generic.intensity_of(sweep)[2]
            md += [f"## {sweep.name}: responses against the {text} of each record", "",
                   f"![{name}]({os.path.basename(path)})", "",
                   _table(["response", "cells", f"Spearman r_s with the {text}"], rows), ""]
            continue
        if kind == "response_vs_axis":
            pages = generic.layouts(sweep, x, hold=planning.limit_state_axes(sweep))
            qs, _ = planning.drawn_against(sweep, x, drawn)
        else:
            pages = generic.layouts(sweep, x)
        title = (f"responses against {x}" if kind == "response_vs_axis"
                 else f"unseating margins against {x}")
        md += [f"## {sweep.name}: {title}", ""]
        for page, layout in enumerate(pages):
            name = _unique(f"{kind}_{x}_{sweep.name}" + (f"_p{page + 1}" if len(pages) > 1
                                                        else ""), used)
            if kind == "response_vs_axis":
                path, _ = generic.response_vs_axis(sweep, layout, qs, args.out, name,
                                                   args.pdf)
            else:
                path, _ = generic.unseating_margins(sweep, layout, margins[0], args.out, name,
                                                    args.pdf)
            written.append(path)
            md += [f"![{name}]({os.path.basename(path)})", ""]
        if len(pages) > 1:
            md += [f"{len(pages)} pages of at most {generic.MAX_COLUMNS} columns each.", ""]
    md += [f"## {sweep.name}: responses over the grid", "",
           _table(["response", "unit", "cells with a value", "min", "median", "max",
                   "cell of the max"], generic.response_table(sweep)), ""]
    for q in margins:
        md += [f"## {sweep.name}: unseating ({q.base})", "",
               _table(["deck", "cells", "cells unseated (margin < 0)", "share",
                       f"smallest margin [{common.unit_text(q.unit) or '1'}]",
                       "cell of the smallest"], generic.unseating_table(sweep, q)), ""]
    records = generic.record_table(sweep)
    if records:
        md += [f"## {sweep.name}: records", "", _table(*records), ""]
    return md


def fragility_sections(sweep, args, used, written):
    """The fragility curves, the demand-IM cloud and the table of fits of a sweep with limit
    states (fragility/ of the cube)."""
    if "fragility" not in sweep.extra:
        return []
    if ida.is_ida(sweep):
        name = _unique(f"ida_curves_{sweep.name}", used)
        md = [f"## {sweep.name}: IDA curves", ""]
        for path in ida.curves(sweep, args.out, name, args.pdf):
            written.append(path)
            stem = os.path.splitext(os.path.basename(path))[0]
            used.add(stem)
            md += [f"![{stem}]({os.path.basename(path)})", ""]
        name = _unique(f"fragility_{sweep.name}", used)
        path, rows = ida.fragility(sweep, args.out, name, args.pdf)
        written.append(path)
        return md + [f"## {sweep.name}: fragility from the IDA capacities", "",
                     f"![{name}]({os.path.basename(path)})", "",
                     _table(ida.table_header(sweep), rows), ""]
    name = _unique(f"fragility_{sweep.name}", used)
    path, rows = fragility.fragility_curves(sweep, args.out, name, args.pdf)
    written.append(path)
    md = [f"## {sweep.name}: fragility functions", "", f"![{name}]({os.path.basename(path)})",
          "", _table(fragility.table_header(sweep), rows), ""]
    name = _unique(f"cloud_{sweep.name}", used)
    path = fragility.cloud(sweep, args.out, name, args.pdf)
    if path:
        written.append(path)
        md += [f"## {sweep.name}: demand against intensity (cloud)", "",
               f"![{name}]({os.path.basename(path)})", ""]
    return md


def incidence_sections(sweep, args, used, written):
    """The demand against the incidence angle and the fragility per angle and at the worst
    angle of a sweep with an incidence_deg axis (over_incidence/, fragility_worst_incidence/)."""
    if not incidence.has_incidence(sweep) or not incidence._demand_names(sweep):
        return []
    name = _unique(f"incidence_{sweep.name}", used)
    path, rows = incidence.response_figure(sweep, args.out, name, args.pdf)
    written.append(path)
    md = [f"## {sweep.name}: demand against the incidence angle", "",
          f"![{name}]({os.path.basename(path)})", "",
          _table(["combination", "limit state", "stripe", "angle of the largest median [°]",
                  "largest median D/C", "median of the records' worst D/C"], rows), ""]
    if "fragility_worst_incidence" not in sweep.extra:
        return md
    name = _unique(f"fragility_incidence_{sweep.name}", used)
    path, rows = incidence.fragility_figure(sweep, args.out, name, args.pdf)
    written.append(path)
    return md + [f"## {sweep.name}: fragility per incidence angle and at the worst angle", "",
                 f"![{name}]({os.path.basename(path)})", "",
                 _table(incidence.table_header(sweep), rows), ""]


def risk_sections(sweep, args, used, written):
    """The annual rates of a sweep with risk/ (skewbridge risk): per limit state with a rate
    the hazard, fragility and integrand on shared IM axes, then the table of rates."""
    if not risk.has_risk(sweep) or "fragility" not in sweep.extra:
        return []
    md = [f"## {sweep.name}: annual rates over the hazard curve", ""] + risk.notes(sweep) + [""]
    for ls in (as_text(n) for n in sweep.extra["risk"]["attrs"]["limit_states"]):
        rates = np.asarray(sweep.extra["risk"][ls]["rate_per_yr"], dtype=float)
        if not np.isfinite(rates).any():
            continue
        name = _unique(f"risk_{sweep.name}_{ls}", used)
        path = risk.figure(sweep, ls, args.out, name, args.pdf)
        written.append(path)
        md += [f"![{name}]({os.path.basename(path)})", ""]
    return md + [_table(*risk.table(sweep)), ""]


def main(argv):
    parser = argparse.ArgumentParser(
        prog="report", description="Figures and a Markdown summary from skewbridge cubes "
        "(skewbridge sweep) and run files (skewbridge run --out).")
    parser.add_argument("cubes", nargs="*", metavar="CUBE.h5")
    parser.add_argument("--run", action="append", default=[], metavar="RUN.h5",
                        help="a run file with histories (repeatable)")
    parser.add_argument("--model", action="append", default=[], metavar="MODEL.toml",
                        help="a model file to draw in plan (repeatable)")
    parser.add_argument("--exe", default=os.path.join(ROOT, "build", "release", "skewbridge"),
                        help="the skewbridge program that reads --model files")
    parser.add_argument("--spectra", action="append", default=[], metavar="SPECTRA.h5",
                        help="response spectra of `skewbridge records spectrum --out` "
                        "(repeatable)")
    parser.add_argument("--out", required=True, metavar="DIR", help="output folder")
    parser.add_argument("--pdf", action="store_true", help="also write each figure as PDF")
    parser.add_argument("--generic", action="store_true",
                        help="draw the responses against every numeric axis for every sweep "
                        "(by default: model-file and multi-span sweeps, and sweeps that get no "
                        "other figure)")
    parser.add_argument("--allow-partial", action="store_true",
                        help="accept incomplete cubes (complete = 0); missing cells are NaN")
    args = parser.parse_args(argv)
    try:
        return run(args)
    except ReportError as err:
        print(f"report: error: {err}", file=sys.stderr)
        return 2


def run(args):
    if not args.cubes and not args.run and not args.model and not args.spectra:
        raise ReportError("nothing to do: give at least one CUBE.h5, --run RUN.h5, "
                          "--model MODEL.toml or --spectra SPECTRA.h5")
    sweeps = [s for path in args.cubes for s in load_cube(path, args.allow_partial)]
    runs = [load_run(path) for path in args.run]
    spectra = [response_spectra.load_spectra(path) for path in args.spectra]
    if os.path.exists(args.out) and not os.path.isdir(args.out):
        raise ReportError(f"--out {args.out}: exists and is not a folder")
    os.makedirs(args.out, exist_ok=True)

    md = ["# skewbridge report", ""]
    if sweeps:
        md += ["## Sweeps", "", _table(
            ["file", "sweep", "family", "axes", "cells", "complete", "status"],
            [(os.path.basename(s.path), s.name, s.family,
              " × ".join(f"{k} ({len(s.axes[k])})" for k in s.axis_order), s.cells(),
              "yes" if s.complete else "no", _status_counts(s)) for s in sweeps]), ""]
    written, skipped_all, used = [], [], set()
    for sweep in sweeps:
        todo, skipped = planning.plan(sweep)
        for kind, reason in skipped:
            skipped_all.append((sweep.name, kind, reason))
        for kind, curve_key in todo:
            name = f"{kind}_{_safe(sweep.name)}"
            while name in used:
                name += "_"
            used.add(name)
            if kind in ("spectra", "pi_delta_family"):
                path, rows = figures.spectra(sweep, curve_key, args.out, name, args.pdf)
            elif kind == "rotation_vs_eta0":
                path, rows = figures.rotation_vs_eta0(sweep, curve_key, args.out, name, args.pdf)
            elif kind == "correlation_theta_vs_Le":
                path, rows = figures.correlation_theta_vs_le(sweep, args.out, name, args.pdf)
            else:
                path, rows = figures.correlation_rotation_vs_w0x(sweep, args.out, name, args.pdf)
            written.append(path)
            md += [f"## {sweep.name}: {KIND_TITLE[kind]}", "",
                   f"![{name}]({os.path.basename(path)})", "",
                   _tables_for(kind, sweep, rows, curve_key), ""]
        if planning.draws_generic(sweep, todo, args.generic):
            md += generic_sections(sweep, args, used, written, skipped_all)
        md += fragility_sections(sweep, args, used, written)
        md += incidence_sections(sweep, args, used, written)
        md += risk_sections(sweep, args, used, written)
    for r in runs:
        name = "history_" + _safe(os.path.splitext(os.path.basename(r.path))[0])
        while name in used:
            name += "_"
        used.add(name)
        path, rows = figures.history(r, args.out, name, args.pdf)
        written.append(path)
        energy = [(k, v) for k, v in sorted(r.energy.items())]
        origin = figures.origin_text(r)
        md += [f"## Run {os.path.basename(r.path)}: time histories", "",
               *([f"Ran {origin}.", ""] if origin else []),
               f"![{name}]({os.path.basename(path)})", "",
               _table(["quantity", "max abs (integrator)", "t of the sampled max [s]"], rows), "",
               _table(["impacts", "plastic closures", "min impact separation [s]"],
                      [(int(r.summary_attrs.get("impacts", 0)),
                        int(r.summary_attrs.get("plastic_closures", 0)),
                        generic.infinite_text(float(
                            r.summary_attrs.get("min_impact_separation_s", np.inf))))]), "",
               _table(["energy term", "J"], energy), ""]
    for model_path in args.model:
        name = "plan_" + _safe(os.path.splitext(os.path.basename(model_path))[0])
        while name in used:
            name += "_"
        used.add(name)
        path, rows = plan_view.draw_plan(plan_view.load_plan(args.exe, model_path), args.out,
                                         name, args.pdf)
        written.append(path)
        md += [f"## Model {os.path.basename(model_path)} in plan", "",
               f"![{name}]({os.path.basename(path)})", "", _table(["item", "value"], rows), ""]
    for sp in spectra:
        stem = _safe(os.path.splitext(os.path.basename(sp["path"]))[0])
        for set_name, members in response_spectra.groups(sp):
            name = f"response_spectra_{stem}_{_safe(set_name)}"
            while name in used:
                name += "_"
            used.add(name)
            path, rows = response_spectra.figure(sp, set_name, members, args.out, name, args.pdf)
            written.append(path)
            md += [f"## Response spectra of {set_name} ({os.path.basename(sp['path'])})", "",
                   f"![{name}]({os.path.basename(path)})", "",
                   _table(["set", "ξ", "records", "peak of the median S_a [g]", "at T [s]",
                           "16 % there [g]", "84 % there [g]"], rows), ""]
        for set_name, members in response_spectra.pair_groups(sp):
            name = f"pair_spectra_{stem}_{_safe(set_name)}"
            while name in used:
                name += "_"
            used.add(name)
            path, rows = response_spectra.pair_figure(sp, set_name, members, args.out, name,
                                                      args.pdf)
            written.append(path)
            md += [f"## Spectra of the record pairs of {set_name} "
                   f"({os.path.basename(sp['path'])})", "",
                   f"![{name}]({os.path.basename(path)})", "",
                   _table(["set", "ξ", "pairs", "measure", "median [g] at T*", "T* [s]",
                           "median of measure / RotD50 at T*"], rows), "",
                   "T*: the period where the median RotD50 of the pairs peaks.", ""]
    md += SYMBOLS_MD
    if skipped_all:
        md += ["## Figures not made", "",
               _table(["sweep", "figure", "why"], skipped_all), ""]
    summary = os.path.join(args.out, "summary.md")
    with open(summary, "w", encoding="utf-8") as f:
        f.write("\n".join(md))
    for path in written:
        print(f"wrote {path}")
    print(f"wrote {summary}")
    for name, kind, reason in skipped_all:
        print(f"skipped {kind} for {name}: {reason}")
    return 0
