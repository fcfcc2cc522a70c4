"""One function per figure kind. Each writes NAME.png (and NAME.pdf with pdf=True) at a fixed
pixel size (FIGSIZE_IN x DPI, no tight bounding box, so the size is known in advance) and
returns the Markdown table rows that go with it in the summary.

Fonts are at least 9 pt at 100 dpi (12.5 px), legible at 100 % zoom; axes carry the symbols of
method.md and their units."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402

from . import stats  # noqa: E402

DPI = 100
FIGSIZE_IN = {"spectra": (10.0, 9.0), "rotation_vs_eta0": (10.0, 9.0),
              "correlation_theta_vs_Le": (12.0, 4.8), "correlation_rotation_vs_w0x": (12.0, 4.8),
              "history": (10.0, 9.0)}

plt.rcParams.update({"font.size": 10, "axes.labelsize": 11, "axes.titlesize": 11,
                     "legend.fontsize": 9, "xtick.labelsize": 9.5, "ytick.labelsize": 9.5,
                     "figure.dpi": DPI, "savefig.dpi": DPI, "lines.linewidth": 1.4,
                     "axes.grid": True, "grid.alpha": 0.3})

RESPONSE_LABEL = {
    "x_norm": r"$x_m\,\omega_g^2/a_g$",
    "y_norm": r"$y_m\,\omega_g^2/a_g$",
    "theta_norm": r"$\theta_m\,\rho\,\omega_g^2/a_g$",
    "theta_m": r"$\theta_m$ [rad]",
    "L_e": r"$L_e = a_g/\omega_g^2$ [m]",
    "impacts": "impacts",
}
AXIS_LABEL = {
    "w0_over_wg": r"$\omega_0/\omega_g$",
    "a_deg": r"$\alpha$",
    "Pi_delta": r"$\Pi_\delta$",
    "eta0": r"$\eta_0$",
    "W0_over_w0": r"$\Omega_0/\omega_0$",
    "mu": r"$\mu$",
    "eps_N": r"$\varepsilon_N$",
    "xi": r"$\xi$",
    "delta_over_L": r"$\delta/L$",
    "W_over_L": r"$W/L$",
}
AXIS_UNIT = {"a_deg": "°"}

# The w0x/w_g groups of the pilot-bridge study when the cube stores no `band` response:
# [0, 0.5), [0.5, 1), [1, 2), [2, inf), the default of docs/hdf5-layout.md.
DEFAULT_BAND_EDGES = (0.5, 1.0, 2.0)


def axis_value_label(key, value):
    """A legend entry such as `α = 30°` or `Π_δ = 0.5`."""
    return f"{AXIS_LABEL.get(key, key)} = {value:g}{AXIS_UNIT.get(key, '')}"


def select(sweep, response, keep, at=None):
    """The response over the axes in `keep` (in that order), other axes at index at[key] or 0."""
    return select_array(sweep, sweep.responses[response], keep, at)


def select_array(sweep, values, keep, at=None):
    """select() for any array shaped like the sweep's cells."""
    at = at or {}
    order = list(sweep.axis_order)
    for key in list(order):
        if key not in keep:
            values = np.take(values, at.get(key, 0), axis=order.index(key))
            order.remove(key)
    return np.transpose(values, [order.index(k) for k in keep])


def _save(fig, out_dir, name, pdf):
    path = os.path.join(out_dir, name + ".png")
    fig.savefig(path, dpi=DPI)
    if pdf:
        fig.savefig(os.path.join(out_dir, name + ".pdf"))
    plt.close(fig)
    return path


def _pulses(sweep):
    if sweep.has_axis("pulse"):
        return list(enumerate(sweep.axes["pulse"]))
    return [(0, sweep.param("pulse") or "")]


def _colors(n):
    return plt.cm.viridis(np.linspace(0.0, 0.9, max(n, 1)))


def _w0_label(sweep):
    return r"$\omega_{0x}/\omega_g$" if sweep.family == "pilot-bridge" else AXIS_LABEL["w0_over_wg"]


def spectra(sweep, curve_key, out_dir, name, pdf):
    """x, y, theta maxima against w0/w_g: one curve per value of curve_key (or one curve),
    one column per pulse. Returns table rows (pulse, curve, response, peak, w0/w_g at peak)."""
    rows_resp = [r for r in ("x_norm", "y_norm", "theta_norm") if r in sweep.responses]
    pulses = _pulses(sweep)
    fig, axes = plt.subplots(len(rows_resp), len(pulses), figsize=FIGSIZE_IN["spectra"],
                             squeeze=False, sharex=True, constrained_layout=True)
    w = sweep.axes["w0_over_wg"]
    curves = list(sweep.axes[curve_key]) if curve_key else [None]
    colors = _colors(len(curves))
    table = []
    for col, (ip, pulse) in enumerate(pulses):
        for row, resp in enumerate(rows_resp):
            ax = axes[row][col]
            keep = ([curve_key] if curve_key else []) + ["w0_over_wg"]
            data = select(sweep, resp, keep, {"pulse": ip})
            if not curve_key:
                data = data[np.newaxis, :]
            for ic, value in enumerate(curves):
                label = axis_value_label(curve_key, value) if curve_key else None
                ax.plot(w, data[ic], color=colors[ic], label=label)
                finite = np.isfinite(data[ic])
                if np.any(finite):
                    k = int(np.nanargmax(data[ic]))
                    table.append((pulse, "" if value is None else f"{value:g}", resp,
                                  data[ic][k], w[k]))
            ax.set_xscale("log")
            ax.set_ylabel(RESPONSE_LABEL[resp])
            if row == 0:
                ax.set_title(f"{pulse} pulse" if pulse else sweep.name)
            if row == len(rows_resp) - 1:
                ax.set_xlabel(_w0_label(sweep))
    if curve_key:
        axes[0][-1].legend(loc="upper right", ncol=2 if len(curves) > 4 else 1)
    fig.suptitle(f"{sweep.name}: {_fixed_text(sweep)}", fontsize=10)
    return _save(fig, out_dir, name, pdf), table


def rotation_vs_eta0(sweep, curve_key, out_dir, name, pdf):
    """The largest theta rho w_g^2/a_g over w0/w_g against eta0, one curve per curve_key value,
    with the w0/w_g where it occurs and the impacts of that cell. Returns table rows
    (pulse, curve, eta0, peak, w0/w_g at peak, impacts)."""
    pulses = _pulses(sweep)
    has_w = sweep.has_axis("w0_over_wg")
    rows = 3 if (has_w and "impacts" in sweep.responses) else (2 if has_w else 1)
    fig, axes = plt.subplots(rows, len(pulses), figsize=FIGSIZE_IN["rotation_vs_eta0"],
                             squeeze=False, sharex=True, constrained_layout=True)
    eta = sweep.axes["eta0"]
    curves = list(sweep.axes[curve_key]) if curve_key else [None]
    colors = _colors(len(curves))
    table = []
    keep = ([curve_key] if curve_key else []) + ["eta0"] + (["w0_over_wg"] if has_w else [])
    for col, (ip, pulse) in enumerate(pulses):
        theta = select(sweep, "theta_norm", keep, {"pulse": ip})
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
            # Where the deck does not turn, the arg-max is round-off: no frequency is shown.
            floor = 1e-9 * max(np.nanmax(theta), 1e-300) if np.any(np.isfinite(theta)) else 0.0
            for ie in range(len(eta)):
                if np.any(np.isfinite(t[ie])):
                    peak[ie] = np.nanmax(t[ie])
                if np.any(np.isfinite(t[ie])) and np.nanmax(t[ie]) > floor:
                    k = int(np.nanargmax(t[ie]))
                    if has_w:
                        where[ie] = sweep.axes["w0_over_wg"][k]
                    if impacts is not None:
                        n_imp[ie] = impacts[ic][ie][k]
                table.append((pulse, "" if value is None else f"{value:g}", eta[ie], peak[ie],
                              where[ie], n_imp[ie]))
            label = axis_value_label(curve_key, value) if curve_key else None
            axes[0][col].plot(eta, peak, "o-", ms=3, color=colors[ic], label=label)
            if rows >= 2:
                axes[1][col].plot(eta, where, "o-", ms=3, color=colors[ic])
            if rows == 3:
                axes[2][col].plot(eta, n_imp, "o-", ms=3, color=colors[ic])
        axes[0][col].set_ylabel(r"$\max_{\omega_0/\omega_g}\ \theta_m\,\rho\,\omega_g^2/a_g$")
        axes[0][col].set_title(f"{pulse} pulse" if pulse else sweep.name)
        axes[0][col].axvline(1.0, color="0.5", lw=0.8, ls="--")
        if rows >= 2:
            axes[1][col].set_yscale("log")
            axes[1][col].set_ylabel(r"$\omega_0/\omega_g$ at the maximum")
        if rows == 3:
            axes[2][col].set_ylabel("impacts at the maximum")
        axes[-1][col].set_xlabel(AXIS_LABEL["eta0"] + r" $= \sin 2\alpha\,/\,(2W/L)$")
    if curve_key:
        axes[0][-1].legend(loc="upper left")
    fig.suptitle(f"{sweep.name}: {_fixed_text(sweep)}", fontsize=10)
    return _save(fig, out_dir, name, pdf), table


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


def _pi_values(sweep):
    if sweep.has_axis("Pi_delta"):
        return list(enumerate(sweep.axes["Pi_delta"]))
    return [(0, sweep.param("Pi_delta"))]


def correlation_theta_vs_le(sweep, out_dir, name, pdf):
    """theta_m against L_e over the records, one panel per Pi_delta, log-log with the fitted
    line. Returns rows (Pi_delta, own statistics dict, stored statistics dict or None)."""
    pis = _pi_values(sweep)
    fig, axes = plt.subplots(1, len(pis), figsize=FIGSIZE_IN["correlation_theta_vs_Le"],
                             squeeze=False, constrained_layout=True, sharey=True)
    keep = ["record"]
    table = []
    for col, (ipi, pi) in enumerate(pis):
        ax = axes[0][col]
        le = select(sweep, "L_e", keep, {"Pi_delta": ipi})
        theta = select(sweep, "theta_m", keep, {"Pi_delta": ipi})
        row = stats.correlation_row(le, theta)
        positive = theta > 0
        impacts = (select(sweep, "impacts", keep, {"Pi_delta": ipi}) > 0
                   if "impacts" in sweep.responses else np.ones_like(positive))
        hit, miss = positive & impacts, positive & ~impacts
        ax.loglog(le[hit], theta[hit], "o", ms=5, color="C0",
                  label=f"with impacts: {int(np.count_nonzero(hit))}")
        if np.any(miss):
            ax.loglog(le[miss], theta[miss], "o", ms=5, mfc="none", color="0.45",
                      label=f"no impact (eccentricity only): {int(np.count_nonzero(miss))}")
        if np.isfinite(row["slope"]):
            xs = np.geomspace(np.nanmin(le[positive]), np.nanmax(le[positive]), 20)
            ax.loglog(xs, 10 ** (row["slope"] * np.log10(xs) + row["intercept"]), "-",
                      color="C3", label=f"log-log fit: slope {row['slope']:.2f}, "
                                        f"$R^2$ = {row['r2']:.2f}")
        zero = int(np.count_nonzero(theta == 0))
        ax.set_title(f"{AXIS_LABEL['Pi_delta']} = {pi:g}: Pearson {row['pearson']:.2f}, "
                     f"Spearman {row['spearman']:.2f}" + (f", {zero} with θm = 0" if zero else ""),
                     fontsize=10)
        ax.set_xlabel(RESPONSE_LABEL["L_e"])
        if col == 0:
            ax.set_ylabel(RESPONSE_LABEL["theta_m"])
        ax.legend(loc="lower right")
        table.append((pi, row, stored_correlation(sweep, ipi)))
    fig.suptitle(f"{sweep.name}: rotation against the persistency of each record", fontsize=10)
    return _save(fig, out_dir, name, pdf), table


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


def correlation_rotation_vs_w0x(sweep, out_dir, name, pdf):
    """theta rho w_g^2/a_g against w0x/w_g, one panel per Pi_delta, coloured by band.
    Returns rows (Pi_delta, band label, count, median, max)."""
    pis = _pi_values(sweep)
    fig, axes = plt.subplots(1, len(pis), figsize=FIGSIZE_IN["correlation_rotation_vs_w0x"],
                             squeeze=False, constrained_layout=True, sharey=True)
    w0x_all = sweep.responses["w0x_over_wg"]
    band_all, labels, _ = band_of(sweep, w0x_all)
    colors = plt.cm.plasma(np.linspace(0.0, 0.8, len(labels)))
    table = []
    for col, (ipi, pi) in enumerate(pis):
        ax = axes[0][col]
        at = {"Pi_delta": ipi}
        w0x = select(sweep, "w0x_over_wg", ["record"], at)
        theta = select(sweep, "theta_norm", ["record"], at)
        band = select_array(sweep, band_all, ["record"], at)
        for b, label in enumerate(labels):
            mask = band == b
            ax.plot(w0x[mask], theta[mask], "o", ms=5, color=colors[b], label=label)
            finite = theta[mask][np.isfinite(theta[mask])]
            table.append((pi, label, len(finite),
                          float(np.median(finite)) if len(finite) else float("nan"),
                          float(np.max(finite)) if len(finite) else float("nan")))
        ax.axvline(2.0, color="0.5", lw=0.8, ls="--")
        ax.set_xscale("log")
        ax.xaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax.xaxis.set_minor_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax.set_xlabel(r"$\omega_{0x}/\omega_g$")
        if col == 0:
            ax.set_ylabel(RESPONSE_LABEL["theta_norm"])
        ax.set_title(f"{AXIS_LABEL['Pi_delta']} = {pi:g}")
    axes[0][-1].legend(loc="upper right")
    fig.suptitle(f"{sweep.name}: dimensionless rotation by frequency-ratio group", fontsize=10)
    return _save(fig, out_dir, name, pdf), table


def history(run, out_dir, name, pdf):
    """x, y, theta of each body against t with impacts (open circles), plastic closures and
    samples in persistent contact (filled) on the curves, and a contact timeline: persistent
    contact (state != 0) filled, impacts open. Returns rows (quantity, max abs, time of max)."""
    fig, axes = plt.subplots(4, 1, figsize=FIGSIZE_IN["history"], sharex=True,
                             constrained_layout=True,
                             gridspec_kw={"height_ratios": [1, 1, 1, 0.8]})
    t = run.t_s
    impact = run.kind_code("impact")
    closure = run.kind_code("plastic-closure")
    t_imp = np.unique(run.event_t_s[run.event_kind == impact]) if impact is not None else []
    t_pc = np.unique(run.event_t_s[run.event_kind == closure]) if closure is not None else []
    labels = [r"$x$ [mm]", r"$y$ [mm]", r"$\theta$ [mrad]"]
    table = []
    # Samples in persistent contact (any contact closed), thinned to at most 80 markers a curve.
    closed = np.flatnonzero(np.any(run.state != 0, axis=1))
    closed = closed[::max(1, len(closed) // 80)]
    for body in range(run.n_bodies):
        for k in range(3):
            ax = axes[k]
            series = run.q[:, 3 * body + k] * 1e3
            color = f"C{body}"
            ax.plot(t, series, color=color, label=f"deck {body}" if run.n_bodies > 1 else None)
            if len(t_imp):
                ax.plot(t_imp, np.interp(t_imp, t, series), "o", ms=7, mfc="none", mec="C3",
                        mew=1.4, label="impact" if body == 0 and k == 0 else None)
            if len(t_pc):
                ax.plot(t_pc, np.interp(t_pc, t, series), "o", ms=7, color="k",
                        label="plastic closure (contact persists)"
                        if body == 0 and k == 0 else None)
            if len(closed):
                ax.plot(t[closed], series[closed], "o", ms=3.5, color="k",
                        label="persistent contact" if body == 0 and k == 0 else None)
            ax.set_ylabel(labels[k])
            i = int(np.argmax(np.abs(series)))
            table.append((("x [m]", "y [m]", "θ [rad]")[k]
                          + (f" (deck {body})" if run.n_bodies > 1 else ""),
                          float(run.max_abs_q[3 * body + k]), float(t[i])))
    axes[0].legend(loc="upper right")
    ax = axes[3]
    for c, cname in enumerate(run.contact_names):
        closed = run.state[:, c] != 0
        ax.plot(t[closed], np.full(np.count_nonzero(closed), c), "s", ms=3.5, color="k",
                label="persistent contact" if c == 0 else None)
        mine = (run.event_kind == impact) & (run.event_contact == c)
        ax.plot(run.event_t_s[mine], np.full(np.count_nonzero(mine), c), "o", ms=8, mfc="none",
                mec="C3", mew=1.4, label="impact" if c == 0 else None)
    ax.set_yticks(range(len(run.contact_names)))
    ax.set_yticklabels(run.contact_names)
    ax.set_ylim(-0.7, len(run.contact_names) - 0.3)
    ax.set_ylabel("contact")
    ax.set_xlabel(r"$t$ [s]")
    ax.legend(loc="upper right", ncol=2)
    fig.suptitle(f"{os.path.basename(run.path)}: status {run.status}, "
                 f"{int(run.summary_attrs.get('impacts', 0))} impacts", fontsize=10)
    return _save(fig, out_dir, name, pdf), table


def _fixed_text(sweep):
    parts = []
    for key in ("a_deg", "eta0", "Pi_delta", "W0_over_w0", "xi", "eps_N", "mu", "pulse"):
        if key in sweep.fixed:
            v = sweep.fixed[key]
            parts.append(f"{key} = {v:g}" if isinstance(v, float) else f"{key} = {v}")
    return ", ".join(parts) if parts else sweep.family
