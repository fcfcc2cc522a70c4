"""The figures of scripts/paper, one function per figure of the paper (Dimitrakopoulos 2011,
Figs. 5 to 13) and two extensions, each keyed in BY_CLAIM by the claim it serves
(paper_claims.py). Each runs what it needs (paper_running.Runner), draws its figures into the
output folder and returns (paths, measurements): the numbers the claim is judged on, as a
dict, and nothing of the verdict."""
import os
import tomllib

import h5py
import matplotlib.lines
import matplotlib.pyplot as plt
import numpy as np

from . import common, figures, stats
from . import plan as plan_view
from .data import ReportError, as_text, load_cube, load_run
from .paper_running import (FIG05_MU, FIG06_CONFIG, G, PILOT_W_RADPS, ROOT, SPECS, W_G,
                            pulse_run, real_pilot_sweep)


def _rho(model):
    deck = model["deck"]
    a = np.radians(deck["skew_deg"])
    width = deck["L"] * np.sin(2 * a) / (2 * deck["eta0"])
    return np.sqrt((deck["L"] ** 2 + width ** 2 / np.cos(a) ** 2) / 12.0)


def self_similarity(runner, out):
    """Fig. 5: dimensional and dimensionless histories at three intensities, same Pi_delta,
    frictionless and with friction (mu = FIG05_MU). Measures, per mu, the largest difference of
    each dimensionless history (x, y, theta rho) from the one at the lowest intensity, in units
    of its peak ("worst"), the impacts of each run and the largest |theta| (rad) of each."""
    levels = [0.25, 0.5, 1.0]
    mus = [0.0, FIG05_MU]
    fig, grid = plt.subplots(3, 2 * len(mus), figsize=(16, 8.4), sharex="col",
                             constrained_layout=True)
    labels = [r"$x\,\omega_g^2/a_g$", r"$y\,\omega_g^2/a_g$", r"$\theta\,\rho\,\omega_g^2/a_g$"]
    dim_labels = [r"$x$ [mm]", r"$y$ [mm]", r"$\theta$ [mrad]"]
    measured = {}
    for im, mu in enumerate(mus):
        runs = [load_run(pulse_run(runner, f"fig05-ag{a}" + (f"-mu{mu:g}" if mu else ""), a,
                                   2.0, mu)) for a in levels]
        curves = []
        for (run, a_g_g), (color, _, ls) in zip(zip(runs, levels), common.curve_styles(3)):
            model = tomllib.loads(run.model_text)
            scale = W_G ** 2 / (a_g_g * G)
            norm = np.column_stack([run.q[:, 0] * scale, run.q[:, 1] * scale,
                                    run.q[:, 2] * _rho(model) * scale])
            curves.append(norm)
            for k in range(3):
                grid[k][2 * im].plot(run.t_s, run.q[:, k] * 1e3, color=color, ls=ls, lw=1.6)
                grid[k][2 * im + 1].plot(W_G * run.t_s, norm[:, k], color=color, ls=ls, lw=1.6,
                                         label=f"$a_g$ = {a_g_g:g} g" if k == 0 and im == 0
                                         else None)
        for k in range(3):
            grid[k][2 * im].set_ylabel(dim_labels[k])
            grid[k][2 * im + 1].set_ylabel(labels[k])
        grid[0][2 * im].set_title(f"μ = {mu:g}: dimensional, grows with a_g", fontsize=10)
        grid[0][2 * im + 1].set_title(f"μ = {mu:g}: dimensionless, one curve", fontsize=10)
        grid[-1][2 * im].set_xlabel(r"$t$ [s]")
        grid[-1][2 * im + 1].set_xlabel(r"$\omega_g t$")
        n = min(len(c) for c in curves)
        dev = [np.max(np.abs(c[:n] - curves[0][:n]), axis=0) /
               np.max(np.abs(curves[0][:n]), axis=0) for c in curves[1:]]
        measured[mu] = {"worst": np.max(dev, axis=0),
                        "impacts": [int(r.summary_attrs.get("impacts", 0)) for r in runs],
                        "theta": [float(r.max_abs_q[2]) for r in runs]}
    grid[0][-1].legend(*grid[0][1].get_legend_handles_labels(), loc="upper left",
                       bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    fig.suptitle(r"Fig. 5: self-similarity, $\Pi_\delta$ = 1, $\eta_0$ = 2, $\alpha$ = 30°, "
                 r"$\omega_0/\omega_g$ = 0.955, cosine pulse, without and with friction",
                 fontsize=10)
    common.caption(fig, ["rho", "ag", "Pi", "eta0", "alpha", "eps"],
                   "x, y, θ: displacements and rotation of the deck; the deck size is the same "
                   "at every a_g.")
    path = common.save(fig, out, "fig05_self_similarity", False)
    return [path], {"mus": mus, "runs": measured}


def two_decks(runner, out):
    """Fig. 6: histories of the paper's two decks, frictionless, cosine pulse: a = 30 deg,
    eta0 = 0.87 (no rotation) and a = 20 deg, eta0 = 1.07 (rotation). Measures the impacts and
    the largest |theta| (rad) of each, keyed "a30" and "a20"."""
    paths, measured = [], {}
    for key, name, a_deg, eta0 in (("a30", "fig06_a30_eta0-0.87", 30.0, 0.87),
                                   ("a20", "fig06_a20_eta0-1.07", 20.0, 1.07)):
        run = load_run(pulse_run(runner, name, 0.5, eta0, 0.0, a_deg=a_deg))
        title = (f"Fig. 6: α = {a_deg:g}°, η_0 = {eta0:g}, μ = 0, Π_δ = 1, "
                 f"ω_0/ω_g = 0.955, ε_N = 0.5, cosine pulse")
        path, _ = figures.history(run, out, name, False, title=title)
        paths.append(path)
        measured[key] = {"impacts": int(run.summary_attrs.get("impacts", 0)),
                         "theta": float(run.max_abs_q[2])}
    return paths, measured


def rotation_against_eta0(runner, out):
    """Fig. 7: the largest rotation over the spectrum against eta0 for several skew angles, one
    panel per Omega0/w0, and below each the ratio of the rotations of complementary angles
    (a and 90 deg - a share sin 2a). Measures the grids ("eta", "ratios", "angles"), the largest
    theta_norm and x_norm over w0/w_g per (a, Omega0/w0, eta0) ("peak", "xpeak") and the impacts
    of the cell of that largest rotation ("impacts"; NaN where the deck does not turn)."""
    sweep = load_cube(runner.sweep(os.path.join(SPECS, "paper", "fig07-rotation-eta0.toml"),
                                   "fig07"))[0]
    keep = ["a_deg", "W0_over_w0", "eta0", "w0_over_wg"]
    theta = common.select(sweep, "theta_norm", keep)
    theta = np.where(np.abs(theta) < common.ZERO, 0.0, theta)  # round-off of no rotation
    impacts = common.select(sweep, "impacts", keep)
    peak = np.nanmax(theta, axis=3)
    k = np.nanargmax(theta, axis=3)
    n_imp = np.take_along_axis(impacts, k[..., np.newaxis], axis=3)[..., 0]
    n_imp = np.where(peak > 0, n_imp, np.nan)
    xpeak = np.nanmax(common.select(sweep, "x_norm", keep), axis=3)
    eta, ratios = sweep.axes["eta0"], sweep.axes["W0_over_w0"]
    angles = [float(a) for a in sweep.axes["a_deg"]]
    pairs = [(a, 90.0 - a) for a in angles if a < 45 and (90.0 - a) in angles]
    fig, axes = plt.subplots(2, len(ratios), figsize=(15, 8.2), squeeze=False, sharex=True,
                             sharey="row", constrained_layout=True,
                             gridspec_kw={"height_ratios": [1.4, 1]})
    styles = common.curve_styles(len(angles))
    pair_colors = ["C3", "C0", "C2", "C4"]
    turns = eta > 1.0
    for ir, r in enumerate(ratios):
        ax = axes[0][ir]
        for ia, a in enumerate(angles):
            color, marker, ls = styles[ia]
            ax.plot(eta, peak[ia, ir], color=color, marker=marker, ls=ls, ms=3.5,
                    label=f"$\\alpha$ = {a:g}° (sin 2$\\alpha$ = {np.sin(np.radians(2 * a)):.2f})"
                    if ir == 0 else None)
        ax.set_title(f"{common.AXIS_LABEL['W0_over_w0']} = {r:g}")
        bottom = axes[1][ir]
        for ip, (a, b) in enumerate(pairs):
            ratio = peak[angles.index(a), ir] / np.where(peak[angles.index(b), ir] > 0,
                                                         peak[angles.index(b), ir], np.nan)
            bottom.plot(eta[turns], ratio[turns], color=pair_colors[ip % 4], marker="o", ms=3,
                        label=f"{a:g}° / {b:g}°" if ir == 0 else None)
        bottom.axhline(1.0, color="0.3", lw=1.0, ls=(0, (4, 3)))
        bottom.set_xlabel(common.AXIS_LABEL["eta0"])
        for row in (0, 1):
            axes[row][ir].axvline(1.0, color="0.5", lw=0.9, ls=(0, (1, 2)))
    axes[0][0].set_ylabel(r"$\max_{\omega_0/\omega_g}\ \theta_m\,\rho\,\omega_g^2/a_g$")
    axes[1][0].set_ylabel("rotation of α over\nrotation of 90° - α")
    h0, l0 = axes[0][0].get_legend_handles_labels()
    axes[0][-1].legend(h0, l0, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0,
                       fontsize=8.5)
    h1, l1 = axes[1][0].get_legend_handles_labels()
    ref = matplotlib.lines.Line2D([], [], color="0.3", lw=1.0, ls=(0, (4, 3)))
    onset = matplotlib.lines.Line2D([], [], color="0.5", lw=0.9, ls=(0, (1, 2)))
    axes[1][-1].legend(h1 + [ref, onset], l1 + ["ratio = 1: a function\nof sin 2α",
                                                "η_0 = 1: onset of rotation"],
                       loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0,
                       fontsize=8.5)
    fig.suptitle("Fig. 7: largest rotation against η_0 for different skew angles, cosine pulse, "
                 r"$\Pi_\delta$ = 1, $\xi$ = 5 %, $\varepsilon_N$ = 0.5, $\mu$ = 0", fontsize=10)
    common.caption(fig, ["rho", "ag", "w0", "Pi", "eta0", "alpha", "eps"],
                   "Top: the largest rotation over ω_0/ω_g = 0.1-10 per skew angle; bottom: the "
                   "rotation of α over that of its complement 90° - α at the same η_0 (the same "
                   "sin 2α and W/L), where the deck turns.")
    path = common.save(fig, out, "fig07_rotation_vs_eta0", False)
    return [path], {"eta": eta, "ratios": ratios, "angles": angles, "pairs": pairs,
                    "peak": peak, "xpeak": xpeak, "impacts": n_imp}


def impact_table(path, a_deg, eta0, mu):
    """One row per impact of a run file: time, corners with an impulse, the total normal
    impulse, the friction ratio sum Lambda_T / (mu sum Lambda_N) (-1 or +1: the deck slips
    through the impact, sigma = the sign; between: it sticks), the approach direction
    tan psi = gamma_T,A / |gamma_N,A| from the last sample before the impact, the criterion
    eta0 (1 + sigma mu / tan a) of docs/theory.md §4 (fact 2, derived) and theta' after."""
    a = np.radians(a_deg)
    with h5py.File(path, "r") as f:
        ev = f["events"]
        names = [as_text(n) for n in f.attrs["contact_names"]]
        t_ev, kind, contact = ev["t_s"][()], ev["kind"][()], ev["contact"][()]
        ln, lt = ev["impulse_N"][()], ev["impulse_T"][()]
        codes = dict(zip((as_text(n) for n in ev["kind"].attrs["kind_names"]),
                         ev["kind"].attrs["kind_codes"]))
        t, u = f["histories/t_s"][()], f["histories/u"][()]
    rows = []
    for ti in np.unique(t_ev[kind == codes["impact"]]):
        here = (kind == codes["impact"]) & (t_ev == ti)
        sum_n, sum_t = float(ln[here].sum()), float(lt[here].sum())
        struck = [names[c] for c, v in zip(contact[here], ln[here]) if v > 1e-9 * sum_n]
        i = max(int(np.searchsorted(t, ti)) - 1, 0)
        vx, vy = u[i, 0], u[i, 1]
        tan_psi = (vx * np.sin(a) + vy * np.cos(a)) / (vx * np.cos(a) - vy * np.sin(a))
        ratio = sum_t / (mu * sum_n) if mu > 0 else 0.0
        sigma = int(round(ratio)) if abs(abs(ratio) - 1) < 1e-6 else 0
        after = min(int(np.searchsorted(t, ti, side="right")), len(t) - 1)
        rows.append({"t": float(ti), "struck": struck, "Lambda_N": sum_n, "ratio": ratio,
                     "sigma": sigma, "tan_psi": float(tan_psi), "vy_vx": float(vy / vx),
                     "criterion": eta0 * (1 + sigma * mu / np.tan(a)) if sigma else None,
                     "omega_after": float(u[after, 2])})
    return rows


def _history_run(runner, out, name, mu, cell, interval, what):
    """A Fig. 8 history of the deck of Fig. 6 (left) with friction mu at `cell` (w0_over_wg,
    Pi_delta, eps_N, delta_over_L): the run file and its figure (path, or None when `out` is
    None)."""
    a_deg, eta0 = FIG06_CONFIG["a_deg"], FIG06_CONFIG["eta0"]
    path = pulse_run(runner, name, FIG06_CONFIG["a_g_g"], eta0, mu, a_deg=a_deg,
                     pi_delta=cell["Pi_delta"], w0=cell["w0_over_wg"] * W_G, eps=cell["eps_N"],
                     interval=interval, delta_over_L=cell["delta_over_L"])
    run = load_run(path)
    figure = None
    if out is not None:
        eta1 = eta0 * (1 + mu / np.tan(np.radians(a_deg)))
        title = (f"Fig. 8, {what}: α = {a_deg:g}°, η_0 = {eta0:g}, μ = {mu:g} (η_1 = {eta1:.3f}),"
                 f" ω_0/ω_g = {cell['w0_over_wg']:.3g}, Π_δ = {cell['Pi_delta']:.3g}, "
                 f"ε_N = {cell['eps_N']:g}, cosine pulse")
        figure, _ = figures.history(run, out, name, False, title=title)
    return figure, {"theta_max": float(run.max_abs_q[2]),
                    "impacts": impact_table(path, a_deg, eta0, mu)}


def friction(runner, out):
    """Fig. 8: the deck of Fig. 6 (left), a = 30 deg and eta0 = 0.87, with mu = 0.08 and 0.1
    under the cosine pulse: its histories in the configuration of Fig. 6 (FIG06_CONFIG), the map of
    where the deck turns over (w0/w_g, Pi_delta) per mu, and the histories at the map's cell
    of the largest rotation at mu = 0.1. Measures per mu of the map the share of its cells
    where the deck turns, of all ("share") and of those with an impact ("share_contact", with
    their number "n_contact"); the runs in Fig. 6's configuration ("fig06") and at that cell
    ("turning", its coordinates "cell"), each per mu the largest |theta| (rad) and the impacts
    one by one (impact_table)."""
    a_deg, eta0 = FIG06_CONFIG["a_deg"], FIG06_CONFIG["eta0"]
    sweep = load_cube(runner.sweep(os.path.join(SPECS, "paper", "fig08-friction-map.toml"),
                                   "fig08"))[0]
    mus, pis, ws = sweep.axes["mu"], sweep.axes["Pi_delta"], sweep.axes["w0_over_wg"]
    theta = common.select(sweep, "theta_norm", ["mu", "Pi_delta", "w0_over_wg"])
    contact = common.select(sweep, "impacts", ["mu", "Pi_delta", "w0_over_wg"]) > 0
    delta_over_l = float(sweep.param("delta_over_L"))
    if abs(delta_over_l / FIG06_CONFIG["delta_over_L"] - 1) > 1e-3:
        raise ReportError(f"fig08-friction-map.toml: delta_over_L = {delta_over_l:g}, not Fig. "
                          f"6's {FIG06_CONFIG['delta_over_L']:.4g}")
    i10 = list(mus).index(0.1)
    ip, iw = np.unravel_index(np.nanargmax(theta[i10]), theta[i10].shape)
    turning = {"w0_over_wg": float(ws[iw]), "Pi_delta": float(pis[ip]), "eps_N": FIG06_CONFIG["eps_N"],
               "delta_over_L": delta_over_l}
    ncol = 2
    nrow = int(np.ceil(len(mus) / ncol))
    fig, axes = plt.subplots(nrow, ncol, figsize=(12, 3.6 * nrow + 0.8), squeeze=False,
                             sharex=True, sharey=True, constrained_layout=True)
    top = max(float(np.nanmax(theta)), common.ZERO)
    share, share_contact, n_contact = {}, {}, {}
    mesh = None
    for k, mu in enumerate(mus):
        ax = axes[k // ncol][k % ncol]
        turns = theta[k] > common.ZERO
        data = np.where(turns, theta[k], np.nan)
        share[mu] = float(np.mean(turns))
        n_contact[mu] = int(np.sum(contact[k]))
        share_contact[mu] = float(np.sum(turns & contact[k]) / max(n_contact[mu], 1))
        mesh = ax.pcolormesh(ws, pis, data, shading="nearest", cmap="viridis", vmin=0, vmax=top)
        none = np.where(contact[k], np.nan, 1.0)  # cells without an impact, hatched grey
        ax.pcolormesh(ws, pis, none, shading="nearest", cmap="Greys", vmin=0, vmax=4,
                      alpha=0.6)
        common.log_axis(ax, "x")
        common.log_axis(ax, "y")
        eta1 = eta0 * (1 + mu / np.tan(np.radians(a_deg)))
        paper = " (paper)" if mu in (0.08, 0.1) else " (extension)"
        ax.set_title(f"μ = {mu:g}{paper}: η_1 = {eta1:.3f}\nturns in "
                     f"{100 * share_contact[mu]:.1f} % of the {n_contact[mu]} cells with an "
                     "impact", fontsize=9)
        if not np.any(turns):
            common.no_data(ax, "no rotation in any cell (θ = 0)", y=0.85)
        if k % ncol == 0:
            ax.set_ylabel(common.AXIS_LABEL["Pi_delta"])
        if k // ncol == nrow - 1:
            ax.set_xlabel(common.AXIS_LABEL["w0_over_wg"])
        ax.plot([FIG06_CONFIG["w0_over_wg"]], [FIG06_CONFIG["Pi_delta"]], "x", color="C3", ms=10, mew=2.4,
                label="Fig. 6's configuration")
        ax.plot([turning["w0_over_wg"]], [turning["Pi_delta"]], "+", color="C1", ms=12, mew=2.4,
                label="largest rotation at μ = 0.1")
    for k in range(len(mus), nrow * ncol):
        axes[k // ncol][k % ncol].set_visible(False)
    fig.colorbar(mesh, ax=axes, label=common.RESPONSE_LABEL["theta_norm"], shrink=0.8)
    axes[0][-1].legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0,
                       fontsize=8)
    fig.suptitle(f"Fig. 8 (map): where the deck turns, α = {a_deg:g}°, η_0 = {eta0:g}, cosine "
                 f"pulse, ε_N = 0.5, ξ = 5 %, Ω_0 = ω_0, δ/L = {delta_over_l:.4g}", fontsize=10)
    common.caption(fig, ["rho", "ag", "w0", "Pi", "eta0", "alpha", "eps"],
                   "η_1 = η_0 (1 + μ/tan α): the paper's frictional skew ratio. Coloured: the "
                   "deck turns; white: an impact, no rotation; grey: no impact (the gap never "
                   "closes).")
    paths = [common.save(fig, out, "fig08_map_where_the_deck_turns", False)]
    fig06_cell = {k: FIG06_CONFIG[k] for k in ("w0_over_wg", "Pi_delta", "eps_N", "delta_over_L")}
    fig06_runs, turning_runs = {}, {}
    for mu in (0.08, 0.1):
        path, fig06_runs[mu] = _history_run(runner, out, f"fig08_mu-{mu:g}", mu, fig06_cell,
                                            0.0005, "in Fig. 6's configuration")
        paths.append(path)
    for mu in (0.08, 0.1):
        path, turning_runs[mu] = _history_run(
            runner, out if mu == 0.1 else None, f"fig08_turning_mu-{mu:g}", mu, turning, 0.0005,
            "the map's largest rotation at μ = 0.1")
        if path:
            paths.append(path)
    return paths, {"share": share, "share_contact": share_contact, "n_contact": n_contact,
                   "fig06": fig06_runs, "turning": turning_runs, "cell": turning}


def sine_limit(runner):
    """The sine-pulse maxima in the limit w0/w_g -> 0 (jobs/specs/paper/sine-flexible-limit.toml,
    w0/w_g = 0.001): {(eta0, a_deg, Pi_delta): {response: value}} for x_norm, y_norm and
    theta_norm."""
    sweep = load_cube(runner.sweep(os.path.join(SPECS, "paper", "sine-flexible-limit.toml"),
                                   "sine-limit"))[0]
    keep = ["eta0", "a_deg", "Pi_delta"]
    values = {r: common.select(sweep, r, keep) for r in ("x_norm", "y_norm", "theta_norm")}
    out = {}
    for ie, e in enumerate(sweep.axes["eta0"]):
        for ia, a in enumerate(sweep.axes["a_deg"]):
            for ip, p in enumerate(sweep.axes["Pi_delta"]):
                out[_key(e, a, p)] = {r: float(v[ie, ia, ip])
                                                       for r, v in values.items()}
    return out


def _key(*values):
    """A dictionary key of grid coordinates, rounded so that a value read back matches."""
    return tuple(round(float(v), 9) for v in values)


def _limit_rows(rows, limit, key_of):
    """The sine-pulse rows of figures.spectra whose peak sits at the flexible end of the grid,
    with the limit w0/w_g -> 0: [(curve value, response, peak at the edge, limit)]."""
    out = []
    for pulse, value, resp, peak, at, edge, _ in rows:
        key = _key(*key_of(float(value)))
        if pulse == "sine" and edge and key in limit:
            out.append((value, resp, peak, limit[key][resp]))
    return out


def _spectra_for_angles(runner, out, eta0):
    sweep = load_cube(runner.sweep(os.path.join(SPECS, f"eta0-{eta0}.toml"),
                                   f"fig10-eta0-{eta0}"))[0]
    num = 9 if eta0 == 1 else 10
    title = (f"Fig. {num}: spectra of the subsystem for different skew angles at η_0 = {eta0}, "
             r"$\Pi_\delta$ = 1, $\Omega_0/\omega_0$ = 1, $\xi$ = 5 %, $\varepsilon_N$ = 0.5, "
             r"$\mu$ = 0")
    path, rows = figures.spectra(sweep, "a_deg", out, f"fig{num:02d}_spectra_eta0-{eta0}", False,
                                 title=title)
    limit = _limit_rows(rows, sine_limit(runner), lambda a: (float(eta0), a, 1.0))
    w = sweep.axes["w0_over_wg"]
    above = {}
    for resp in ("y_norm", "theta_norm"):
        v = common.select(sweep, resp, ["pulse", "a_deg", "w0_over_wg"])
        above[resp] = float(np.nanmax(np.abs(v[..., w > 2.0])))
    return [path], {"rows": rows, "limit": limit, "above_two": above,
                    "grid": (float(w.min()), float(w.max()))}


def spectra_eta0_1(runner, out):
    """Fig. 9: spectra for skew angles at eta0 = 1. Measures the spectra's table rows
    (figures.spectra: pulse, angle, response, peak, ...), the sine peaks at the grid's flexible
    end with their limit w0/w_g -> 0 ("limit", _limit_rows), the largest y_norm and theta_norm
    at w0/w_g > 2 ("above_two") and the grid's ends ("grid")."""
    return _spectra_for_angles(runner, out, 1)


def spectra_eta0_2(runner, out):
    """Fig. 10: spectra for skew angles at eta0 = 2, measured as spectra_eta0_1."""
    return _spectra_for_angles(runner, out, 2)


def complementary_angles(runner, out):
    """The extension after Fig. 10: spectra of the complementary skew angles a and 90 deg - a
    at two eta0. Measures the eta0 values, the angle pairs and, per (eta0, response, a), the
    largest difference of the two spectra in units of the larger peak ("diff")."""
    sweep = load_cube(runner.sweep(os.path.join(SPECS, "paper", "fig09-complementary.toml"),
                                   "fig09"))[0]
    etas, angles, w = sweep.axes["eta0"], list(sweep.axes["a_deg"]), sweep.axes["w0_over_wg"]
    pairs = [(a, 90.0 - a) for a in angles if a < 45 and (90.0 - a) in angles]
    resps = ["x_norm", "y_norm", "theta_norm"]
    fig, axes = plt.subplots(3, len(etas), figsize=(10, 9), squeeze=False, sharex=True,
                             constrained_layout=True)
    colors = ["C0", "C3", "C2", "C4"]
    diff = {}
    for ie, eta0 in enumerate(etas):
        for ir, resp in enumerate(resps):
            ax = axes[ir][ie]
            data = common.select(sweep, resp, ["eta0", "a_deg", "w0_over_wg"])[ie]
            # round-off of a deck that does not turn (1e-16) is drawn as the 0 it is
            data = np.where(np.abs(data) < common.ZERO, 0.0, data)
            for ip, (a, b) in enumerate(pairs):
                ra, rb = data[angles.index(a)], data[angles.index(b)]
                ax.plot(w, ra, color=colors[ip], ls="-", lw=2.2, alpha=0.6,
                        label=f"$\\alpha$ = {a:g}°" if ir == 0 and ie == 0 else None)
                ax.plot(w, rb, color=colors[ip], ls="--", marker="o", ms=3, markevery=3,
                        label=f"$\\alpha$ = {b:g}°" if ir == 0 and ie == 0 else None)
                scale = max(np.nanmax(ra), np.nanmax(rb))
                # two curves of no response (round-off, below ZERO) do not differ
                diff[(eta0, resp, a)] = (float(np.nanmax(np.abs(ra - rb)) / scale)
                                         if scale >= common.ZERO else 0.0)
            common.log_axis(ax, "x")
            ax.set_ylabel(common.RESPONSE_LABEL[resp])
            if not np.any(data):
                ax.text(0.5, 0.6, "no rotation at any α (0 below 1e-9)",
                        transform=ax.transAxes,
                        ha="center", color="0.4", fontsize=11)
            if ir == 0:
                ax.set_title(f"$\\eta_0$ = {eta0:g}")
            if ir == 2:
                ax.set_xlabel(common.AXIS_LABEL["w0_over_wg"])
    handles, labels = axes[0][0].get_legend_handles_labels()
    axes[0][-1].legend(handles, labels, loc="upper left", bbox_to_anchor=(1.02, 1.0),
                       borderaxespad=0.0)
    fig.suptitle("After Fig. 10 (extension, not a figure of the paper): complementary skew "
                 "angles (same sin 2α), cosine pulse, "
                 r"$\Pi_\delta$ = 1, $\Omega_0 = \omega_0$", fontsize=10)
    common.caption(fig, ["x", "rho", "ag", "w0", "eta0", "alpha"],
                   "Solid: α < 45°; dashed with markers: its complement 90° - α.")
    path = common.save(fig, out, "ext_complementary_angles", False)
    return [path], {"etas": etas, "pairs": pairs, "diff": diff}


def pi_delta_family(runner, out):
    """Fig. 11: the Pi_delta family at eta0 = 2. Measures the spectra's table rows
    (figures.spectra: pulse, Pi_delta, response, peak, ...), the sine peaks at the grid's edge
    with their limit ("limit") and the gap claim paired per frequency: per pulse and pair of
    neighbouring Pi_delta, the cells of w0/w_g where the deck strikes at both gaps ("both"),
    of them those whose theta_norm and y_norm are smaller at the smaller gap ("theta", "y")
    and their range of w0/w_g ("where_theta")."""
    sweep = load_cube(runner.sweep(os.path.join(SPECS, "paper", "fig11-pi-delta-eta0-2.toml"),
                                   "fig11"))[0]
    title = (r"Fig. 11: the $\Pi_\delta$ family at $\eta_0$ = 2, $\alpha$ = 20°, "
             r"$\Omega_0/\omega_0$ = 1, $\xi$ = 5 %, $\varepsilon_N$ = 0.5, $\mu$ = 0")
    path, rows = figures.spectra(sweep, "Pi_delta", out, "fig11_pi_delta_family_eta0-2", False,
                                 title=title)
    a_deg, eta0 = float(sweep.param("a_deg")), float(sweep.param("eta0"))
    limit = _limit_rows(rows, sine_limit(runner), lambda p: (eta0, a_deg, p))
    keep = ["pulse", "Pi_delta", "w0_over_wg"]
    theta = common.select(sweep, "theta_norm", keep)
    y = common.select(sweep, "y_norm", keep)
    hits = common.select(sweep, "impacts", keep) > 0
    pis, w = list(sweep.axes["Pi_delta"]), sweep.axes["w0_over_wg"]
    pairs = []
    for ip, pulse in enumerate(sweep.axes["pulse"]):
        for i in range(len(pis) - 1):
            both = hits[ip, i] & hits[ip, i + 1]
            smaller = both & (theta[ip, i] < theta[ip, i + 1])
            pairs.append({"pulse": pulse, "pis": (float(pis[i]), float(pis[i + 1])),
                          "both": int(both.sum()), "theta": int(smaller.sum()),
                          "y": int(np.sum(both & (y[ip, i] < y[ip, i + 1]))),
                          "where_theta": (float(w[smaller].min()), float(w[smaller].max()))
                          if smaller.any() else None})
    return [path], {"rows": rows, "limit": limit, "pairs": pairs}


def _pier_column(bearing):
    """The kind of a bearing of docs/examples/pilot-elements.toml: its two pier columns are
    built into the deck, so the file gives them as bearings on the ground with the columns'
    (unequal) stiffnesses; the laminated bearings on the seats are isotropic."""
    if bearing["pier"] is None and bearing["k_strong_Npm"] != bearing["k_weak_Npm"]:
        return "pier column (built into the deck)"
    return None


def pilot_plan(runner, out):
    """Fig. 12: the pilot bridge in plan, docs/examples/pilot-elements.toml. Measures the plan's
    table rows, the uncoupled frequencies the paper quotes (rad/s: along the principal axes,
    torsion about the centre of rigidity; "w") and the centre of rigidity from the mass centre
    (m; "e")."""
    model = os.path.join(ROOT, "docs", "examples", "pilot-elements.toml")
    plan = plan_view.load_plan(runner.exe, model)
    deck = plan["decks"][0]
    w = [np.sqrt(k / deck["mass_kg"]) for k in deck["principal_Npm"]]
    w.append(np.sqrt(deck["torsion_about_centre_Nmprad"] / deck["inertia_kgm2"]))
    e = np.array(deck["centre_of_rigidity_m"]) - np.array(deck["mass_centre_m"])
    off = max(abs(a / b - 1) for a, b in zip(w, PILOT_W_RADPS))
    path, rows = plan_view.draw_plan(
        plan, out, "fig12_pilot_bridge_plan", False, kind_of=_pier_column,
        title="Fig. 12: the pilot bridge in plan, built from its elements "
              "(docs/examples/pilot-elements.toml)",
        note="This element layout is drawn here; the records of Fig. 13 run the pilot bridge "
             "as the principal-axes model of docs/theory.md §6 (" +
             ", ".join(f"{v:g}" for v in PILOT_W_RADPS) + " rad/s and the centre of rigidity "
             "as published), whose frequencies this layout reproduces to "
             f"{100 * off:.1f} %.")
    return [path], {"rows": rows, "w": w, "e": e}


def _pilot_cubes(runner):
    """The pilot bridge's cubes: over the synthetic suite (jobs/specs/pilot-records.toml), over
    the real records (None without them) and the one-abutment control over the synthetic suite
    (jobs/specs/paper/pilot-one-abutment.toml)."""
    synthetic = load_cube(runner.sweep(os.path.join(SPECS, "pilot-records.toml"),
                                       "fig13-pilot-records"))[0]
    control = load_cube(runner.sweep(os.path.join(SPECS, "paper", "pilot-one-abutment.toml"),
                                     "pilot-one-abutment"))[0]
    if list(control.axes["record"]) != list(synthetic.axes["record"]):
        raise ReportError("pilot-one-abutment: its records differ from fig13-pilot-records'")
    return synthetic, real_pilot_sweep(runner), control


def group_edges(sweep):
    """The w0x/w_g groups of the pilot study as edges 0, e_1, ..., inf (the cube's bands)."""
    _, _, edges = figures.band_of(sweep, sweep.responses["w0x_over_wg"])
    return [0.0] + [float(e) for e in edges] + [float("inf")]


def gap_pairs(theta, y, hits, w0x, pis, edges):
    """The gap claim paired per record: per w0x/w_g group [lo, hi) of `edges` and per pair of
    neighbouring gaps (Pi_i, Pi_i+1), the records that strike at both gaps ("both"), of them
    those whose theta_m ("theta") and y_m ("y") is smaller at the smaller gap, and the median
    ratio theta_m(Pi_i) / theta_m(Pi_i+1) ("ratio"). theta, y, hits: [record, Pi]."""
    groups = []
    for lo, hi in zip(edges, edges[1:]):
        g = (w0x >= lo) & (w0x < hi)
        pairs = []
        for i in range(len(pis) - 1):
            both = g & hits[:, i] & hits[:, i + 1]
            pairs.append({"pis": (float(pis[i]), float(pis[i + 1])), "both": int(both.sum()),
                          "theta": int(np.sum(theta[both, i] < theta[both, i + 1])),
                          "y": int(np.sum(y[both, i] < y[both, i + 1])),
                          "ratio": float(np.median(theta[both, i] / theta[both, i + 1]))
                          if both.any() else float("nan")})
        groups.append({"lo": lo, "hi": hi, "n": int(g.sum()), "pairs": pairs})
    return groups


def pilot_records(runner, out):
    """Fig. 13: the pilot bridge under the synthetic record suite. Draws theta_m and y_m against
    L_e (13a) and their dimensionless maxima against w0x/w_g (13b) and measures the claims over
    the synthetic suite and, when the repository's record collection is there, over the real
    records with PGA >= 0.1 g (suite_stats; "real" None without them); "edges": the w0x/w_g
    groups."""
    sweep, real_sweep, _ = _pilot_cubes(runner)
    model = "the principal-axes model of docs/theory.md §6, not Fig. 12's element layout"
    p1, rows = figures.correlation_theta_vs_le(
        sweep, out, "fig13a_theta_vs_persistency", False, responses=("theta_m", "y_m"),
        title=f"Fig. 13a: the pilot bridge under {len(sweep.axes['record'])} synthetic "
              "records, rotation and transverse displacement against persistency\n(" + model +
              ")")
    p2, _ = figures.correlation_rotation_vs_w0x(
        sweep, out, "fig13b_rotation_vs_w0x", False, responses=("theta_norm", "y_norm"),
        title="Fig. 13b: the pilot bridge, dimensionless maxima by frequency-ratio group\n(" +
              model + ")")
    edges = group_edges(sweep)
    return [p1, p2], {
        "n_records": len(sweep.axes["record"]), "edges": edges,
        "synthetic": suite_stats(sweep, edges),
        "real": suite_stats(real_sweep, edges, min_pga_g=0.1) if real_sweep is not None
        else None}


def suite_stats(sweep, edges, min_pga_g=0.0):
    """The pilot-bridge claims measured over one record suite: the records with PGA >= min_pga_g,
    the coupling of L_e with T_m, and per Pi_delta Spearman's rho_s of theta_m and of y_m with
    L_e (all records and those that strike), the medians of theta_norm and y_norm below and
    above w0x/w_g = 2, and the gap claim paired per record (gap_pairs over `edges`)."""
    pis = list(sweep.axes["Pi_delta"])
    keep = ["record", "Pi_delta"]
    a_g = common.select(sweep, "a_g", keep)[:, 0]
    w_g = common.select(sweep, "w_g", keep)[:, 0]
    le = common.select(sweep, "L_e", keep)[:, 0]
    use = a_g >= min_pga_g * G
    tm = 2 * np.pi / w_g
    out = {"n": int(use.sum()), "coupling": stats.spearman(le[use], tm[use]),
           "pga_g": (float(a_g[use].min() / G), float(a_g[use].max() / G)),
           "per_pi": {}}
    w0x_all = common.select(sweep, "w0x_over_wg", keep)[use]
    pooled = {}
    for resp in ("theta_norm", "y_norm"):
        v = common.select(sweep, resp, keep)[use]
        pooled[resp] = tuple(float(np.median(v[m])) if np.any(m) else float("nan")
                             for m in (w0x_all < 2, w0x_all >= 2))
    out["pooled"] = pooled["theta_norm"]
    out["pooled_y"] = pooled["y_norm"]
    hits_all = common.select(sweep, "impacts", keep)[use] > 0
    theta_all = common.select(sweep, "theta_m", keep)[use]
    y_all = common.select(sweep, "y_m", keep)[use]
    out["gap"] = gap_pairs(theta_all, y_all, hits_all, w0x_all[:, 0], pis, edges)
    for ip, pi in enumerate(pis):
        hits = hits_all[:, ip]
        w0x = w0x_all[:, ip]
        row = {"n_hit": int(hits.sum()), "n_above": int(np.sum(w0x >= 2)),
               "median_theta": float(np.median(theta_all[:, ip]))}
        for name, resp, norm in (("", theta_all[:, ip], "theta_norm"),
                                 ("y_", y_all[:, ip], "y_norm")):
            v = common.select(sweep, norm, keep)[use, ip]
            row[name + "all"] = stats.spearman(le[use], resp)
            row[name + "hit"] = (stats.spearman(le[use][hits], resp[hits]) if hits.sum() >= 3
                                 else None)
            row[name + "below"] = float(np.median(v[w0x < 2])) if np.any(w0x < 2) else \
                float("nan")
            row[name + "above"] = float(np.median(v[w0x >= 2])) if np.any(w0x >= 2) else \
                float("nan")
        out["per_pi"][pi] = row
    return out


def gap_claim(runner, out):
    """After Fig. 13 (an extension): the gap claim paired per record. Per record that strikes at
    both of two neighbouring gaps, theta_m at the smaller over theta_m at the larger against
    w0x/w_g, for the pilot bridge (synthetic suite, real records) and for its one-abutment
    control. Measures gap_pairs of each ("synthetic", "real" or None, "control") over the
    groups of the synthetic cube ("edges")."""
    sweep, real_sweep, control = _pilot_cubes(runner)
    edges = group_edges(sweep)
    keep = ["record", "Pi_delta"]
    pis = list(sweep.axes["Pi_delta"])
    w0x = common.select(sweep, "w0x_over_wg", keep)[:, 0]
    cases = [("two abutments, synthetic suite", sweep, w0x, "theta_m", "y_m",
              dict(marker="o", color="C0", ls="none", ms=6)),
             ("one abutment (control), synthetic suite", control, w0x, "theta_m_d0", "y_m_d0",
              dict(marker="s", mfc="none", mec="C3", mew=1.4, ls="none", ms=7))]
    if real_sweep is not None:
        a_g = common.select(real_sweep, "a_g", keep)[:, 0]
        use = a_g >= 0.1 * G
        cases.append(("two abutments, real records (PGA ≥ 0.1 g)", real_sweep,
                      common.select(real_sweep, "w0x_over_wg", keep)[:, 0], "theta_m", "y_m",
                      dict(marker="^", color="C2", ls="none", ms=6), use))
    fig, axes = plt.subplots(2, len(pis) - 1, figsize=(12, 8.4), squeeze=False, sharex=True,
                             sharey="row", constrained_layout=True)
    measured = {}
    plotted = np.zeros(len(pis) - 1, dtype=bool)
    for case in cases:
        label, cube, w, t_name, y_name, style = case[:6]
        use = case[6] if len(case) > 6 else np.ones(len(w), dtype=bool)
        theta = common.select(cube, t_name, keep)[use]
        y = common.select(cube, y_name, keep)[use]
        hits = common.select(cube, "impacts", keep)[use] > 0
        measured[label] = gap_pairs(theta, y, hits, w[use], pis, edges)
        for i in range(len(pis) - 1):
            both = hits[:, i] & hits[:, i + 1]
            plotted[i] |= bool(both.any())
            for row, v in enumerate((theta, y)):
                axes[row][i].plot(w[use][both], v[both, i] / v[both, i + 1], label=label
                                  if row == 0 and i == 0 else None, **style)
    for i in range(len(pis) - 1):
        for row, sym in enumerate((r"\theta_m", "y_m")):
            ax = axes[row][i]
            ax.axhline(1.0, color="0.3", lw=1.0, ls=(0, (4, 3)))
            for e in edges[1:-1]:
                ax.axvline(e, color="0.6", lw=0.8, ls=":")
            ax.set_yscale("log")
            common.log_axis(ax, "x")
            ax.set_ylabel(f"${sym}(\\Pi_\\delta = {pis[i]:g})\\,/\\,{sym}(\\Pi_\\delta = "
                          f"{pis[i + 1]:g})$")
            if row == 1:
                ax.set_xlabel(r"$\omega_{0x}/\omega_g$")
            ax.set_title(f"{'rotation' if row == 0 else 'transverse displacement'}, "
                         f"Π_δ = {pis[i]:g} against {pis[i + 1]:g}", fontsize=10)
            if not plotted[i]:
                common.no_data(ax, "no record strikes at both gaps")
    ref = matplotlib.lines.Line2D([], [], color="0.3", lw=1.0, ls=(0, (4, 3)))
    grp = matplotlib.lines.Line2D([], [], color="0.6", lw=0.8, ls=":")
    h, lab = axes[0][0].get_legend_handles_labels()
    axes[0][-1].legend(h + [ref, grp], lab + ["ratio = 1: the same at both gaps",
                                              "edges of the ω0x/ωg groups"],
                       loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    fig.suptitle("After Fig. 13 (extension): the gap claim paired per record, the pilot bridge "
                 "and its one-abutment control", fontsize=10)
    common.caption(fig, ["x", "w0x", "Pi"], "Each point: one record that strikes an abutment "
                   "at both gaps; below 1 the response is smaller at the smaller gap, as the "
                   "paper states. The control is the same bridge with the +x abutment only "
                   "(jobs/specs/paper/pilot-one-abutment.toml).")
    path = common.save(fig, out, "fig13x_gap_claim_paired", False)
    return [path], {"edges": edges, "pairs": measured,
                    "labels": [c[0] for c in cases]}


# The figure function of each claim of paper_claims.FIGURES, by its key.
BY_CLAIM = {"5": self_similarity, "6": two_decks, "7": rotation_against_eta0, "8": friction,
            "9": spectra_eta0_1, "10": spectra_eta0_2, "10x": complementary_angles,
            "11": pi_delta_family, "12": pilot_plan, "13": pilot_records, "13x": gap_claim}
