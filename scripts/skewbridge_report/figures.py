"""One function per figure kind of the dimensionless study (spectra, the Π_δ family, rotation
against η_0, the record correlations, time histories). Each writes NAME.png (and NAME.pdf with
pdf=True) at a fixed pixel size (FIGSIZE_IN x DPI, no tight bounding box, so the size is known
in advance) and returns the Markdown table rows that go with it in the summary. The style, the
symbols and the captions are common.py's."""
import os
import tomllib

import matplotlib.lines
import matplotlib.pyplot as plt
import numpy as np

from . import common, stats
from .common import (AXIS_LABEL, AXIS_TEXT, AXIS_UNIT, LINESTYLES, MAX_LEGEND, RESPONSE_LABEL,
                     RESPONSE_TEXT, ZERO, caption, curve_key_legend, curve_styles, integer_axis,
                     log_axis, no_data, peak_of, select, select_array)

FIGSIZE_IN = {"spectra": (10.0, 9.0), "rotation_vs_eta0": (10.0, 9.0),
              "correlation_theta_vs_Le": (12.0, 4.8), "correlation_rotation_vs_w0x": (12.0, 4.8),
              "history": (10.0, 11.0)}


def axis_value_label(key, value):
    """A legend entry such as `α = 30°` or `Π_δ = 0.5`."""
    return f"{AXIS_LABEL.get(key, key)} = {value:g}{AXIS_UNIT.get(key, '')}"


def _pulses(sweep):
    if sweep.has_axis("pulse"):
        return list(enumerate(sweep.axes["pulse"]))
    return [(0, sweep.param("pulse") or "")]


def _w0_label(sweep):
    return r"$\omega_{0x}/\omega_g$" if sweep.family == "pilot-bridge" else AXIS_LABEL["w0_over_wg"]


# The caption entry of each axis or fixed parameter.
_SYMBOL_OF = {"a_deg": "alpha", "eta0": "eta0", "Pi_delta": "Pi", "W0_over_w0": "w0",
              "eps_N": "eps", "mu": "eps", "xi": "eps"}


def _caption_keys(sweep, base, *keys):
    out = list(base)
    for key in list(keys) + list(sweep.fixed):
        sym = _SYMBOL_OF.get(key)
        if sym and sym not in out:
            out.append(sym)
    return out


def spectra(sweep, curve_key, out_dir, name, pdf, title=None):
    """x, y, theta maxima against w0/w_g: one curve per value of curve_key (or one curve),
    one column per pulse; a panel whose curves take their largest value at an end of the grid
    says so (no peak inside it). `title` replaces the sweep's name and fixed values above
    the panels. Returns table rows (pulse, curve, response, peak, w0/w_g at peak, at the grid
    edge, no response)."""
    rows_resp = [r for r in ("x_norm", "y_norm", "theta_norm") if r in sweep.responses]
    pulses = _pulses(sweep)
    fig, axes = plt.subplots(len(rows_resp), len(pulses), figsize=FIGSIZE_IN["spectra"],
                             squeeze=False, sharex=True, constrained_layout=True)
    w = sweep.axes["w0_over_wg"]
    curves = list(sweep.axes[curve_key]) if curve_key else [None]
    many = len(curves) > MAX_LEGEND
    styles = curve_styles(len(curves))
    table = []
    for col, (ip, pulse) in enumerate(pulses):
        for row, resp in enumerate(rows_resp):
            ax = axes[row][col]
            keep = ([curve_key] if curve_key else []) + ["w0_over_wg"]
            data = select(sweep, resp, keep, {"pulse": ip})
            if not curve_key:
                data = data[np.newaxis, :]
            # round-off (1e-16) of a deck that does not move is drawn as the 0 it is
            data = np.where(np.abs(data) < ZERO, 0.0, data)
            at_edge = set()
            for ic, value in enumerate(curves):
                label = axis_value_label(curve_key, value) if curve_key else None
                color, marker, ls = styles[ic]
                if many:
                    ax.plot(w, data[ic], color=color, lw=1.0)
                else:
                    # markers staggered per curve, so that coinciding curves (alpha and
                    # 90 deg - alpha without rotation) each keep visible markers
                    step = max(1, len(w) // 8)
                    ax.plot(w, data[ic], color=color, ls=ls, marker=marker, ms=4,
                            markevery=(ic % step, step), label=label)
                peak, at, _, edge, zero = peak_of(data[ic], w)
                if edge:
                    at_edge.add(at)
                if np.isfinite(peak) or zero:
                    table.append((pulse, "" if value is None else f"{value:g}", resp, peak, at,
                                  edge, zero))
            if not np.any(np.isfinite(data)):
                no_data(ax)
            elif not np.any(data[np.isfinite(data)]):
                ax.text(0.5, 0.6, f"no response: 0 everywhere (below {ZERO:g})",
                        transform=ax.transAxes, ha="center", color="0.4", fontsize=11)
            if at_edge:  # the largest value at an end of the grid: no peak inside it
                ends = " and ".join(f"{v:g}" for v in sorted(at_edge))
                ax.text(0.98, 0.96, f"largest at the grid's end {ends}:\nno peak inside the grid",
                        transform=ax.transAxes, ha="right", va="top", color="0.3", fontsize=8.5)
            log_axis(ax, "x")
            ax.set_ylabel(RESPONSE_LABEL[resp])
            if row == 0:
                ax.set_title(f"{pulse} pulse" if pulse else sweep.name)
            if row == len(rows_resp) - 1:
                ax.set_xlabel(_w0_label(sweep))
    curve_key_legend(fig, axes, curve_key, curves)
    fig.suptitle(title or f"{sweep.name}: {_fixed_text(sweep)}", fontsize=10)
    caption(fig, _caption_keys(sweep, ["x", "rho", "ag", "w0"], curve_key))
    return common.save(fig, out_dir, name, pdf), table


def rotation_vs_eta0(sweep, curve_key, out_dir, name, pdf):
    """The largest theta rho w_g^2/a_g over w0/w_g against eta0, one curve per curve_key value,
    with the w0/w_g where it occurs and the impacts of that cell. Returns table rows
    (pulse, curve, eta0, peak, w0/w_g at peak, impacts, at the grid edge, no response)."""
    pulses = _pulses(sweep)
    has_w = sweep.has_axis("w0_over_wg")
    rows = 3 if (has_w and "impacts" in sweep.responses) else (2 if has_w else 1)
    fig, axes = plt.subplots(rows, len(pulses), figsize=FIGSIZE_IN["rotation_vs_eta0"],
                             squeeze=False, sharex=True, constrained_layout=True)
    eta = sweep.axes["eta0"]
    curves = list(sweep.axes[curve_key]) if curve_key else [None]
    many = len(curves) > MAX_LEGEND
    styles = curve_styles(len(curves))
    table = []
    keep = ([curve_key] if curve_key else []) + ["eta0"] + (["w0_over_wg"] if has_w else [])
    w_grid = sweep.axes["w0_over_wg"] if has_w else np.array([np.nan])
    for col, (ip, pulse) in enumerate(pulses):
        theta = select(sweep, "theta_norm", keep, {"pulse": ip})
        theta = np.where(np.abs(theta) < ZERO, 0.0, theta)  # round-off of no rotation
        impacts = select(sweep, "impacts", keep, {"pulse": ip}) if rows == 3 else None
        if not curve_key:
            theta = theta[np.newaxis]
            impacts = impacts[np.newaxis] if impacts is not None else None
        if not has_w:
            theta = theta[..., np.newaxis]
        for ic, value in enumerate(curves):
            t = theta[ic]
            peak = np.full(len(eta), np.nan)
            where = np.full(len(eta), np.nan)
            n_imp = np.full(len(eta), np.nan)
            for ie in range(len(eta)):
                p, at, k, edge, zero = peak_of(t[ie], w_grid)
                peak[ie] = p
                if k >= 0:
                    where[ie] = at
                    if impacts is not None:
                        n_imp[ie] = impacts[ic][ie][k]
                table.append((pulse, "" if value is None else f"{value:g}", eta[ie], p,
                              where[ie], n_imp[ie], edge and has_w, zero))
            label = axis_value_label(curve_key, value) if curve_key else None
            color, marker, ls = styles[ic]
            kw = dict(color=color, lw=1.0) if many else dict(color=color, ls=ls, marker=marker,
                                                             ms=4)
            axes[0][col].plot(eta, peak, label=None if many else label, **kw)
            if rows >= 2:
                axes[1][col].plot(eta, where, **kw)
            if rows == 3:
                axes[2][col].plot(eta, n_imp, **kw)
        axes[0][col].set_ylabel(r"$\max_{\omega_0/\omega_g}\ \theta_m\,\rho\,\omega_g^2/a_g$")
        axes[0][col].set_title(f"{pulse} pulse" if pulse else sweep.name)
        for r in range(rows):
            axes[r][col].axvline(1.0, color="0.5", lw=0.9, ls=(0, (4, 3)))
        if not np.any(np.isfinite(theta)):
            no_data(axes[0][col])
        if rows >= 2:
            log_axis(axes[1][col], "y")
            axes[1][col].set_ylabel(r"$\omega_0/\omega_g$ at the maximum")
            if not np.any(np.isfinite(where)):
                no_data(axes[1][col], "no rotation")
        if rows == 3:
            axes[2][col].set_ylabel("impacts at the maximum")
            integer_axis(axes[2][col])
        axes[-1][col].set_xlabel(AXIS_LABEL["eta0"] + r" $= \sin 2\alpha\,/\,(2W/L)$")
    ref = matplotlib.lines.Line2D([], [], color="0.5", lw=0.9, ls=(0, (4, 3)))
    curve_key_legend(fig, axes, curve_key if curve_key else None, curves, [ref],
                     [r"$\eta_0 = 1$: onset of rotation" + "\n(full-edge impact)"])
    fig.suptitle(f"{sweep.name}: {_fixed_text(sweep)}", fontsize=10)
    caption(fig, _caption_keys(sweep, ["x", "rho", "ag", "w0", "eta0"], curve_key),
            "A point with no rotation has no ω_0/ω_g of its maximum and is not drawn in the "
            "lower panels.")
    return common.save(fig, out_dir, name, pdf), table


def band_of(sweep, w0x):
    """The w0x/w_g group of each cell, band k for edges[k-1] <= w0x/w_g < edges[k]: the cube's
    `band` response and its band_edges when stored, else DEFAULT_BAND_EDGES.
    Returns (band array, labels, edges)."""
    edges = sweep.response_attrs.get("band", {}).get("band_edges")
    if "band" in sweep.responses and edges is not None:
        band = sweep.responses["band"]
    else:
        edges = DEFAULT_BAND_EDGES
        band = np.digitize(w0x, edges).astype(float)
        band[~np.isfinite(w0x)] = np.nan
    bounds = [0.0] + [float(e) for e in edges] + [np.inf]
    labels = [f"{bounds[b]:g} ≤ ω0x/ωg < {bounds[b + 1]:g}" if np.isfinite(bounds[b + 1])
              else f"ω0x/ωg ≥ {bounds[b]:g}" for b in range(len(bounds) - 1)]
    return band, labels, list(edges)


def band_legend_label(label):
    """A band label of band_of() in mathtext."""
    return "$" + label.replace("≤", r"\leq").replace("≥", r"\geq").replace(
        "ω0x/ωg", r"\omega_{0x}/\omega_g") + "$"


# The w0x/w_g groups of the pilot-bridge study when the cube stores no `band` response:
# [0, 0.5), [0.5, 1), [1, 2), [2, inf), the default of docs/hdf5-layout.md.
DEFAULT_BAND_EDGES = (0.5, 1.0, 2.0)


def _pi_values(sweep):
    if sweep.has_axis("Pi_delta"):
        return list(enumerate(sweep.axes["Pi_delta"]))
    return [(0, sweep.param("Pi_delta"))]


def strikes(sweep, keep, at):
    """Per record: True when it strikes an abutment (impacts > 0); all True without `impacts`."""
    if "impacts" not in sweep.responses:
        return None
    return select(sweep, "impacts", keep, at) > 0


def correlation_theta_vs_le(sweep, out_dir, name, pdf, title=None, responses=("theta_m",)):
    """theta_m (and any other response in `responses`, one row of panels each) against L_e over
    the records, one panel per Pi_delta, log-log. The records that strike an abutment and those
    that never do (whose rotation comes from the eccentric stiffness alone) are two
    populations: each is drawn and fitted apart (least squares of log10 of the response on
    log10 L_e), and the panel states Spearman's rank correlation rho_s of the response with L_e
    for each and for all records, the one correlation statistic of the pilot study
    (docs/validation.md). Returns rows of the first response (Pi_delta, statistics over all,
    statistics over those that strike or None, stored)."""
    pis = _pi_values(sweep)
    width, height = FIGSIZE_IN["correlation_theta_vs_Le"]
    fig, axes = plt.subplots(len(responses), len(pis), squeeze=False, sharey="row",
                             figsize=(width, height + 4.0 * (len(responses) - 1)),
                             constrained_layout=True)
    keep = ["record"]
    table = []
    handles = {}
    for irow, resp in enumerate(responses):
        for col, (ipi, pi) in enumerate(pis):
            ax = axes[irow][col]
            at = {"Pi_delta": ipi}
            le = select(sweep, "L_e", keep, at)
            value = select(sweep, resp, keep, at)
            row = stats.correlation_row(le, value)
            hits = strikes(sweep, keep, at)
            row_hit = stats.correlation_row(le[hits], value[hits]) if hits is not None else None
            row_miss = (stats.correlation_row(le[~hits], value[~hits]) if hits is not None
                        else None)
            positive = value > 0
            hit = positive & (hits if hits is not None else True)
            miss = positive & ~hits if hits is not None else np.zeros_like(positive)
            handles["hit"], = ax.loglog(le[hit], value[hit], "o", ms=5, color="C0")
            if np.any(miss):
                handles["miss"], = ax.loglog(le[miss], value[miss], "s", ms=5, mfc="none",
                                             color="0.4")
            fits = (("fit_hit", row_hit, hit, dict(color="C0", ls="--")),
                    ("fit_miss", row_miss, miss, dict(color="0.4", ls=":")))
            if hits is None:
                fits = (("fit_all", row, positive, dict(color="C3", ls="-")),)
            for key, r, sel, style in fits:
                if r is None or not np.isfinite(r["slope"]) or np.count_nonzero(sel) < 3:
                    continue
                xs = np.geomspace(np.nanmin(le[sel]), np.nanmax(le[sel]), 20)
                handles[key], = ax.loglog(xs, 10 ** (r["slope"] * np.log10(xs) +
                                                     r["intercept"]), lw=1.6, **style)
            if not np.any(positive):
                no_data(ax, "no record moves" if resp != "theta_m" else "no record rotates")
            else:
                log_axis(ax, "x")
                log_axis(ax, "y")
            zero = int(np.count_nonzero(value == 0))
            lines = [f"{AXIS_LABEL['Pi_delta']} = {pi:g}: " + _fit_text("all", row)]
            if row_hit is not None:
                lines += [_fit_text("strike", row_hit), _fit_text("never strike", row_miss)]
            if zero:
                lines[-1] += f"; {zero} at 0 not drawn"
            ax.set_title("\n".join(lines), fontsize=9)
            if irow == len(responses) - 1:
                ax.set_xlabel(RESPONSE_LABEL["L_e"])
            if col == 0:
                ax.set_ylabel(RESPONSE_LABEL[resp])
            if irow == 0:
                table.append((pi, row, row_hit, stored_correlation(sweep, ipi)))
    names = {"hit": "strikes an abutment", "miss": "never strikes\n(eccentricity only)",
             "fit_all": "log-log fit, all records", "fit_hit": "log-log fit, records\nthat strike",
             "fit_miss": "log-log fit, records\nthat never strike"}
    keys = [k for k in names if k in handles]
    axes[0][-1].legend([handles[k] for k in keys], [names[k] for k in keys], loc="upper left",
                       bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    fig.suptitle(title or f"{sweep.name}: rotation against the persistency of each record",
                 fontsize=10)
    what = " and ".join(RESPONSE_TEXT[r].split(" [")[0] for r in responses)
    caption(fig, ["x", "Le", "Pi"] if len(responses) > 1 else ["Le", "Pi"],
            f"ρ_s: Spearman's rank correlation of {what} with L_e over the records named (in "
            "brackets, their number), the one statistic stated; the lines are least-squares fits "
            "of the logarithms, one per group, drawn as a guide to the eye.")
    return common.save(fig, out_dir, name, pdf), table


def _fit_text(group, row):
    """`group (n): rho_s = ...` (the one statistic a panel states), or that the group is too
    small for a correlation."""
    if row["n"] < 3 or not np.isfinite(row["spearman"]):
        return f"{group}: {row['n']} records, too few"
    return f"{group} ({row['n']}): $\\rho_s$ = {row['spearman']:+.2f}"


def stored_correlation(sweep, ipi):
    """The statistics the cube stores for Pi_delta index ipi (correlation/ group), or None."""
    corr = sweep.extra.get("correlation")
    if not corr:
        return None
    out = {}
    for key, value in corr.items():
        if key == "attrs" or key.endswith("@attrs") or isinstance(value, dict):
            continue
        arr = np.atleast_1d(np.asarray(value))
        if arr.dtype.kind in "fiu" and arr.ndim == 1 and ipi < len(arr):
            out[key] = float(arr[ipi])
    return out or None


def correlation_rotation_vs_w0x(sweep, out_dir, name, pdf, title=None,
                                responses=("theta_norm",)):
    """theta rho w_g^2/a_g (and any other response in `responses`, one row of panels each)
    against w0x/w_g, one panel per Pi_delta, by frequency-ratio group (colour and marker);
    records that never strike drawn open. Groups with no record are left out of the legend and
    the table. Returns rows of the first response (Pi_delta, band label, count, median, max)."""
    pis = _pi_values(sweep)
    width, height = FIGSIZE_IN["correlation_rotation_vs_w0x"]
    fig, axes = plt.subplots(len(responses), len(pis), squeeze=False, sharey="row",
                             sharex=True, figsize=(width, height + 3.6 * (len(responses) - 1)),
                             constrained_layout=True)
    w0x_all = sweep.responses["w0x_over_wg"]
    band_all, labels, _ = band_of(sweep, w0x_all)
    styles = curve_styles(len(labels), "plasma")
    table = []
    shown = {}
    for irow, resp in enumerate(responses):
        for col, (ipi, pi) in enumerate(pis):
            ax = axes[irow][col]
            at = {"Pi_delta": ipi}
            w0x = select(sweep, "w0x_over_wg", ["record"], at)
            value = select(sweep, resp, ["record"], at)
            band = select_array(sweep, band_all, ["record"], at)
            hits = strikes(sweep, ["record"], at)
            if hits is None:
                hits = np.ones(len(value), dtype=bool)
            for b, label in enumerate(labels):
                mask = band == b
                color, marker, _ = styles[b]
                if np.any(mask & hits):
                    shown[b], = ax.plot(w0x[mask & hits], value[mask & hits], marker, ms=5,
                                        color=color, ls="none")
                if np.any(mask & ~hits):
                    h, = ax.plot(w0x[mask & ~hits], value[mask & ~hits], marker, ms=5,
                                 mfc="none", color=color, ls="none")
                    shown.setdefault(b, h)
                finite = value[mask][np.isfinite(value[mask])]
                if not len(finite) or irow:  # an empty group is neither drawn nor listed
                    continue
                table.append((pi, label, len(finite), float(np.median(finite)),
                              float(np.max(finite))))
            if not np.any(np.isfinite(value)):
                no_data(ax)
            ax.axvline(2.0, color="0.5", lw=0.9, ls=(0, (4, 3)))
            log_axis(ax, "x")
            if irow == len(responses) - 1:
                ax.set_xlabel(r"$\omega_{0x}/\omega_g$")
            if col == 0:
                ax.set_ylabel(RESPONSE_LABEL[resp])
            if irow == 0:
                ax.set_title(f"{AXIS_LABEL['Pi_delta']} = {pi:g}")
    ref = matplotlib.lines.Line2D([], [], color="0.5", lw=0.9, ls=(0, (4, 3)))
    open_marker = matplotlib.lines.Line2D([], [], marker="o", mfc="none", color="0.3",
                                          ls="none")
    keys = sorted(shown)
    axes[0][-1].legend([shown[b] for b in keys] + [open_marker, ref],
                       [band_legend_label(labels[b]) for b in keys] + ["open: never strikes",
                                                    r"$\omega_{0x}/\omega_g = 2$: rotations" +
                                                    "\nfade above it (paper, §4)"],
                       loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    fig.suptitle(title or f"{sweep.name}: dimensionless rotation by frequency-ratio group",
                 fontsize=10)
    caption(fig, (["x"] if len(responses) > 1 else []) + ["rho", "ag", "w0x", "Pi"])
    return common.save(fig, out_dir, name, pdf), table


G_MPS2 = 9.80665
_UNIT_MPS2 = {"mps2": 1.0, "g": G_MPS2, "cmps2": 0.01}


def model_of(run):
    """The model file a run file stores (its model_text) as a dict; None when it does not parse."""
    try:
        return tomllib.loads(run.model_text)
    except (tomllib.TOMLDecodeError, TypeError):
        return None


def ground_acceleration(run):
    """(a_g(t) in m/s^2 at run.t_s, direction text): the samples the run applied when the run
    file stores them (origin/ground_acceleration: a record of `run --record`, a cube's cell),
    linear between samples as the solver takes them; else rebuilt from the run's model text
    for a pulse or inline samples; (None, reason) for an excitation file the run file does not
    hold."""
    if run.ground is not None and len(run.ground):
        times = np.arange(len(run.ground)) * run.ground_dt_s
        ax = np.interp(run.t_s, times, run.ground[:, 0], right=0.0)
        ay = np.interp(run.t_s, times, run.ground[:, 1], right=0.0)
        if not np.any(ay):
            return ax, "along x"
        if not np.any(ax):
            return ay, "along y"
        # One direction for every sample (the model file's): the signed value along it.
        k = int(np.argmax(np.hypot(run.ground[:, 0], run.ground[:, 1])))
        d = run.ground[k] / np.hypot(*run.ground[k])
        return ax * d[0] + ay * d[1], f"at {np.degrees(np.arctan2(d[1], d[0])):.0f}° from x"
    model = model_of(run)
    ex = (model or {}).get("excitation")
    if not ex:
        return None, "no excitation in the run file's model text"
    t = run.t_s
    direction = (f"at {ex['angle_deg']:g}° from x" if "angle_deg" in ex
                 else f"along {ex.get('direction', 'x')}")
    if ex.get("kind") == "pulse":
        a_g = ex["a_g"] if "a_g" in ex else ex["a_g_g"] * G_MPS2
        w_g = ex["w_g"] if "w_g" in ex else 2.0 * np.pi / ex["T_g"]
        phase = w_g * t
        a = a_g * (np.cos(phase) if ex.get("shape") == "cosine" else np.sin(phase))
        return np.where(t <= 2.0 * np.pi / w_g, a, 0.0), direction
    if ex.get("kind") == "sampled" and "values" in ex:
        values = np.asarray(ex["values"], dtype=float)
        values = values * _UNIT_MPS2.get(ex.get("units", "mps2"), 1.0) * ex.get("scale", 1.0)
        times = np.arange(len(values)) * float(ex["dt_s"])
        return np.interp(t, times, values, right=0.0), direction
    return None, "a record file: its samples are not stored in the run file"


def tangential_velocity(run):
    """gamma_T = w_T^T u of each contact at run.t_s (m/s), w_T = (t, t . R'(theta) p) with the
    corner p and the face tangent t of docs/theory.md §2, for one deck against its abutments;
    None for a multi-span model or a run without velocities."""
    model = model_of(run)
    deck = (model or {}).get("deck")
    if run.u is None or not isinstance(deck, dict) or run.n_bodies != 1:
        return None
    a = np.radians(deck.get("skew_deg", 0.0))
    length = float(deck["L"])
    width = float(deck["W"]) if "W" in deck else length * np.sin(2 * a) / (2 * deck["eta0"])
    half_l, half_w, shift = length / 2, width / 2, width / 2 * np.tan(a)
    corners = {"P1": ((half_l + shift, half_w), 1), "P2": ((half_l - shift, -half_w), 1),
               "P3": ((-half_l - shift, -half_w), -1), "P4": ((-half_l + shift, half_w), -1)}
    if not all(c in corners for c in run.contact_names):
        return None
    theta = run.q[:, 2]
    out = np.empty((len(run.t_s), len(run.contact_names)))
    for c, cname in enumerate(run.contact_names):
        (px, py), side = corners[cname]
        tx, ty = side * np.sin(a), side * np.cos(a)
        dpx = -np.sin(theta) * px - np.cos(theta) * py  # R'(theta) p
        dpy = np.cos(theta) * px - np.sin(theta) * py
        out[:, c] = tx * run.u[:, 0] + ty * run.u[:, 1] + (tx * dpx + ty * dpy) * run.u[:, 2]
    return out


def origin_text(run):
    """What a run ran, from its origin group: the cube's cell with its coordinates, or the
    record with its scale factor; "" for a model file as written."""
    o = run.origin or {}
    if o.get("kind") == "cube-cell":
        return (f"sweep '{o['sweep']}' of {os.path.basename(str(o['cube']))}, "
                f"cell {int(o['cell_index'])} ({o['coordinates']}), "
                f"scale factor {float(o['scale_factor']):.4g}")
    if o.get("kind") == "record":
        rec = o.get("record_label") or os.path.basename(str(o.get("record_file", "")))
        text = f"record {rec} x {float(o['scale_factor']):.4g}"
        if "target_g" in o:
            text += f" ({o['scaled_to'].split(':')[0]} = {float(o['target_g']):g} g)"
        return text
    return ""


def origin_title(run):
    """The history figure's title: the run file's name, then what it ran."""
    text = origin_text(run)
    return os.path.basename(run.path) + (f": {text}" if text else "")


def history(run, out_dir, name, pdf, title=None):
    """The ground acceleration, x, y, theta of each body, the gaps g_N and tangential velocities
    gamma_T of the contacts against t, with impacts (open circles) and plastic closures (filled)
    on the curves, and a contact timeline: persistent contact (state != 0) filled, impacts
    open; `title` (the parameters of the run) before the status line. Returns rows (quantity,
    max abs, time of max)."""
    has_gap = run.gap is not None
    gamma_t = tangential_velocity(run)
    a_g, a_note = ground_acceleration(run)
    panels = ["a_g", "x", "y", "theta"] + (["gap"] if has_gap else []) + ["gamma_T", "contact"]
    ratios = [0.7, 1, 1, 1] + ([1] if has_gap else []) + [1, 0.7]
    fig, axes = plt.subplots(len(panels), 1, figsize=FIGSIZE_IN["history"], sharex=True,
                             constrained_layout=True, gridspec_kw={"height_ratios": ratios})
    ax_of = dict(zip(panels, axes))
    t = run.t_s
    impact = run.kind_code("impact")
    closure = run.kind_code("plastic-closure")
    t_imp = np.unique(run.event_t_s[run.event_kind == impact]) if impact is not None else []
    t_pc = np.unique(run.event_t_s[run.event_kind == closure]) if closure is not None else []
    table = []
    ax = ax_of["a_g"]
    if a_g is None:
        no_data(ax, "ground acceleration not shown: " + a_note)
    else:
        ax.plot(t, a_g, color="0.2")
        ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_ylabel(r"$a_g$ [m/s$^2$]" + "\n" + (a_note if a_g is not None else ""), fontsize=10)
    labels = {"x": r"$x$ [mm]", "y": r"$y$ [mm]", "theta": r"$\theta$ [mrad]"}
    legend = {}
    for body in range(run.n_bodies):
        for k, key in enumerate(("x", "y", "theta")):
            ax = ax_of[key]
            series = run.q[:, 3 * body + k] * 1e3
            if np.max(np.abs(run.q[:, 3 * body + k])) < ZERO:  # round-off of a zero motion
                series = np.zeros_like(series)
                no_data(ax, f"{('x', 'y', 'θ')[k]} = 0 (|value| below {ZERO:g} in SI units)",
                        y=0.75)
            h, = ax.plot(t, series, color=f"C{body}", ls=LINESTYLES[body % len(LINESTYLES)])
            if run.n_bodies > 1:
                legend.setdefault(f"deck {body}", h)
            if len(t_imp):
                legend["impact"], = ax.plot(t_imp, np.interp(t_imp, t, series), "o", ms=7,
                                            mfc="none", mec="C3", mew=1.4)
            if len(t_pc):
                legend["plastic closure (contact persists)"], = ax.plot(
                    t_pc, np.interp(t_pc, t, series), "o", ms=6, color="k")
            ax.set_ylabel(labels[key])
            i = int(np.argmax(np.abs(series)))
            table.append((("x [m]", "y [m]", "θ [rad]")[k]
                          + (f" (deck {body})" if run.n_bodies > 1 else ""),
                          float(run.max_abs_q[3 * body + k]), float(t[i])))
    # Contact colours apart from the deck's (C0, C1, ...) and from the impact marker (C3).
    palette = ["C2", "C4", "C6", "C8", "C9", "C5", "C7", "C1"]
    contact_legend = {}
    for key, values, unit, scale in (("gap", run.gap, "[mm]", 1e3),
                                     ("gamma_T", gamma_t, "[m/s]", 1.0)):
        if key not in ax_of:
            continue
        ax = ax_of[key]
        if values is None:
            no_data(ax, "γ_T not shown: computed for one deck against its abutments only")
        else:
            for c, cname in enumerate(run.contact_names):
                h, = ax.plot(t, values[:, c] * scale, color=palette[c % len(palette)],
                             ls=LINESTYLES[c % len(LINESTYLES)])
                contact_legend.setdefault(f"corner {cname}", h)
            ax.axhline(0.0, color="0.6", lw=0.6)
        ax.set_ylabel((r"$g_N$ " if key == "gap" else r"$\gamma_T$ ") + unit)
    ax = ax_of["contact"]
    for c, cname in enumerate(run.contact_names):
        closed = run.state[:, c] != 0
        if np.any(closed):
            legend["persistent contact"], = ax.plot(t[closed], np.full(np.count_nonzero(closed), c),
                                                    "s", ms=3.5, color="k")
        mine = (run.event_kind == impact) & (run.event_contact == c)
        if np.any(mine):
            ax.plot(run.event_t_s[mine], np.full(np.count_nonzero(mine), c), "o", ms=8,
                    mfc="none", mec="C3", mew=1.4)
    if not np.any(run.state != 0) and not len(t_imp):
        no_data(ax, "no contact: the gaps never close")
    ax.set_yticks(range(len(run.contact_names)))
    ax.set_yticklabels(run.contact_names)
    ax.set_ylim(-0.7, len(run.contact_names) - 0.3)
    ax.grid(False, axis="y")
    ax.set_ylabel("contact")
    ax.set_xlabel(r"$t$ [s]")
    for key, entries in (("x", legend), ("gap" if has_gap else "gamma_T", contact_legend)):
        if entries:
            ax_of[key].legend(list(entries.values()), list(entries.keys()), loc="upper left",
                              bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    fig.suptitle(f"{title or origin_title(run)}\nstatus {run.status}, "
                 f"{int(run.summary_attrs.get('impacts', 0))} impacts", fontsize=10)
    caption(fig, ["gap"], "x, y, θ: displacements and rotation of the deck relative to the "
            "ground; a_g: ground acceleration. The corners of one end share their face's "
            "tangent, so their γ_T differ only by the lever-arm term r_i θ' sin θ and nearly "
            "overlap.")
    return common.save(fig, out_dir, name, pdf), table


# What each family's figures show, named in their titles: the subsystem is one abutment, not a
# bridge [docs/theory.md §6].
FAMILY_TEXT = {
    "subsystem": "single-abutment subsystem (corners P1, P2)",
    "pilot-bridge": "pilot bridge, both abutments",
}


def _fixed_text(sweep):
    """The figure title's tail: the family's model, then the sweep's fixed parameters."""
    parts = [FAMILY_TEXT[sweep.family]] if sweep.family in FAMILY_TEXT else []
    for key in ("a_deg", "eta0", "Pi_delta", "W0_over_w0", "xi", "eps_N", "mu", "pulse"):
        if key in sweep.fixed:
            v = sweep.fixed[key]
            if isinstance(v, float):
                parts.append(f"{AXIS_LABEL.get(key, key)} = {v:g}{AXIS_UNIT.get(key, '')}")
            else:
                parts.append(f"{AXIS_TEXT.get(key, key)}: {v}")
    return ", ".join(parts) if parts else sweep.family
