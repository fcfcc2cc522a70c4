"""The figures of scripts/paper, one function per figure of the paper (Dimitrakopoulos 2011,
Figs. 5 to 13) and one extension, each keyed in BY_CLAIM by the claim it serves
(paper_claims.py). Each runs what it needs (paper_running.Runner), draws its figures into the
output folder and returns (paths, measurements): the numbers the claim is judged on, as a
dict, and nothing of the verdict."""
import os
import tomllib

import h5py
import matplotlib.pyplot as plt
import numpy as np

from . import common, figures, stats
from . import plan as plan_view
from .data import as_text, load_cube, load_run
from .paper_running import FIG08_CELL, G, ROOT, SPECS, W_G, pulse_run, real_pilot_sweep


def _rho(model):
    deck = model["deck"]
    a = np.radians(deck["skew_deg"])
    width = deck["L"] * np.sin(2 * a) / (2 * deck["eta0"])
    return np.sqrt((deck["L"] ** 2 + width ** 2 / np.cos(a) ** 2) / 12.0)


def self_similarity(runner, out):
    """Fig. 5: dimensionless histories at three intensities, same Pi_delta. Measures the largest
    difference of each dimensionless history (x, y, theta rho) from the one at the lowest
    intensity, in units of its peak ("worst"), and the impacts of each run."""
    levels = [0.25, 0.5, 1.0]
    runs = [load_run(pulse_run(runner, f"fig05-ag{a}", a, 2.0, 0.0)) for a in levels]
    fig, grid = plt.subplots(3, 2, figsize=(12, 8), sharex="col", constrained_layout=True)
    labels = [r"$x\,\omega_g^2/a_g$", r"$y\,\omega_g^2/a_g$", r"$\theta\,\rho\,\omega_g^2/a_g$"]
    dim_labels = [r"$x$ [mm]", r"$y$ [mm]", r"$\theta$ [mrad]"]
    curves = []
    for (run, a_g_g), (color, marker, ls) in zip(zip(runs, levels), common.curve_styles(3)):
        model = tomllib.loads(run.model_text)
        scale = W_G ** 2 / (a_g_g * G)
        norm = np.column_stack([run.q[:, 0] * scale, run.q[:, 1] * scale,
                                run.q[:, 2] * _rho(model) * scale])
        curves.append(norm)
        for k in range(3):
            grid[k][0].plot(run.t_s, run.q[:, k] * 1e3, color=color, ls=ls, lw=1.6)
            grid[k][1].plot(W_G * run.t_s, norm[:, k], color=color, ls=ls, lw=1.6,
                            label=f"$a_g$ = {a_g_g:g} g" if k == 0 else None)
    for k in range(3):
        grid[k][0].set_ylabel(dim_labels[k])
        grid[k][1].set_ylabel(labels[k])
    grid[0][0].set_title("dimensional: grows with a_g", fontsize=10)
    grid[0][1].set_title("dimensionless: one curve", fontsize=10)
    grid[-1][0].set_xlabel(r"$t$ [s]")
    grid[-1][1].set_xlabel(r"$\omega_g t$")
    axes = [row[1] for row in grid]
    axes[0].legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    fig.suptitle(r"Fig. 5: self-similarity, $\Pi_\delta$ = 1, $\eta_0$ = 2, $\alpha$ = 30°, "
                 r"$\omega_0/\omega_g$ = 0.955, cosine pulse", fontsize=10)
    common.caption(fig, ["rho", "ag", "Pi", "eta0", "alpha"],
                   "x, y, θ: displacements and rotation of the deck; the deck size is the same "
                   "at every a_g.")
    path = common.save(fig, out, "fig05_self_similarity", False)
    n = min(len(c) for c in curves)
    dev = [np.max(np.abs(c[:n] - curves[0][:n]), axis=0) / np.max(np.abs(curves[0][:n]), axis=0)
           for c in curves[1:]]
    return [path], {"worst": np.max(dev, axis=0),
                    "impacts": [int(r.summary_attrs.get("impacts", 0)) for r in runs]}


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
    """Fig. 7: the largest rotation over the spectrum against eta0, one curve per Omega0/w0,
    with eta0 to 8 for the claim about eta0 > 6. Measures the eta0 grid, the Omega0/w0 values
    and the largest theta_norm over w0/w_g per (Omega0/w0, eta0) ("peak")."""
    sweep = load_cube(runner.sweep(os.path.join(SPECS, "paper", "fig07-rotation-eta0.toml"),
                                   "fig07"))[0]
    path, _ = figures.rotation_vs_eta0(sweep, "W0_over_w0", out, "fig07_rotation_vs_eta0", False)
    theta = common.select(sweep, "theta_norm", ["W0_over_w0", "eta0", "w0_over_wg"])
    return [path], {"eta": sweep.axes["eta0"], "ratios": sweep.axes["W0_over_w0"],
                    "peak": np.nanmax(theta, axis=2)}


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


def friction(runner, out):
    """Fig. 8: a = 30 deg, eta0 = 0.87 with mu = 0.08 and 0.1 under the cosine pulse: the map of
    where the deck turns over (w0/w_g, Pi_delta) per mu, and the histories at FIG08_CELL.
    Measures the share of the map's cells where the deck turns per mu ("share") and, per mu of
    the histories, the largest |theta| (rad) and the impacts one by one (impact_table)."""
    a_deg, eta0 = 30.0, 0.87
    sweep = load_cube(runner.sweep(os.path.join(SPECS, "paper", "fig08-friction-map.toml"),
                                   "fig08"))[0]
    mus, pis, ws = sweep.axes["mu"], sweep.axes["Pi_delta"], sweep.axes["w0_over_wg"]
    theta = common.select(sweep, "theta_norm", ["mu", "Pi_delta", "w0_over_wg"])
    ncol = 2
    nrow = int(np.ceil(len(mus) / ncol))
    fig, axes = plt.subplots(nrow, ncol, figsize=(12, 3.6 * nrow + 0.8), squeeze=False,
                             sharex=True, sharey=True, constrained_layout=True)
    top = max(float(np.nanmax(theta)), common.ZERO)
    share = {}
    mesh = None
    for k, mu in enumerate(mus):
        ax = axes[k // ncol][k % ncol]
        data = np.where(theta[k] > common.ZERO, theta[k], np.nan)
        share[mu] = float(np.mean(theta[k] > common.ZERO))
        mesh = ax.pcolormesh(ws, pis, data, shading="nearest", cmap="viridis", vmin=0, vmax=top)
        common.log_axis(ax, "x")
        common.log_axis(ax, "y")
        eta1 = eta0 * (1 + mu / np.tan(np.radians(a_deg)))
        paper = " (paper)" if mu in (0.08, 0.1) else " (extension)"
        ax.set_title(f"μ = {mu:g}{paper}: η_1 = {eta1:.3f}, turns in {100 * share[mu]:.0f} %",
                     fontsize=9)
        if not np.any(theta[k] > common.ZERO):
            common.no_data(ax, "no rotation in any cell (θ = 0)")
        if k % ncol == 0:
            ax.set_ylabel(common.AXIS_LABEL["Pi_delta"])
        if k // ncol == nrow - 1:
            ax.set_xlabel(common.AXIS_LABEL["w0_over_wg"])
        ax.plot([FIG08_CELL["w0_over_wg"]], [FIG08_CELL["Pi_delta"]], "x", color="C3", ms=9,
                mew=2, label="cell of the histories")
    for k in range(len(mus), nrow * ncol):
        axes[k // ncol][k % ncol].set_visible(False)
    fig.colorbar(mesh, ax=axes, label=common.RESPONSE_LABEL["theta_norm"], shrink=0.8)
    axes[0][0].legend(loc="lower left", fontsize=8)
    fig.suptitle(f"Fig. 8 map: where the deck turns, α = {a_deg:g}°, η_0 = {eta0:g}, cosine "
                 f"pulse, ε_N = 0.5, ξ = 5 %, Ω_0 = ω_0 (white: θ = 0)", fontsize=10)
    common.caption(fig, ["rho", "ag", "w0", "Pi", "eta0", "alpha", "eps"],
                   "η_1 = η_0 (1 + μ/tan α): the paper's frictional skew ratio.")
    paths = [common.save(fig, out, "fig08_map_where_the_deck_turns", False)]
    runs = {}
    for mu in (0.08, 0.1):
        name = f"fig08_mu-{mu:g}"
        path = pulse_run(runner, name, 0.5, eta0, mu, a_deg=a_deg,
                         pi_delta=FIG08_CELL["Pi_delta"], w0=FIG08_CELL["w0_over_wg"] * W_G,
                         eps=FIG08_CELL["eps_N"], interval=0.0005,
                         delta_over_L=0.002)
        run = load_run(path)
        title = (f"Fig. 8: α = {a_deg:g}°, η_0 = {eta0:g}, μ = {mu:g} "
                 f"(η_1 = {eta0 * (1 + mu / np.tan(np.radians(a_deg))):.3f}), "
                 f"ω_0/ω_g = {FIG08_CELL['w0_over_wg']:g}, Π_δ = {FIG08_CELL['Pi_delta']:g}, "
                 f"ε_N = {FIG08_CELL['eps_N']:g}, cosine pulse")
        hist, _ = figures.history(run, out, name, False, title=title)
        paths.append(hist)
        runs[mu] = {"theta_max": float(run.max_abs_q[2]),
                    "impacts": impact_table(path, a_deg, eta0, mu)}
    return paths, {"share": share, "runs": runs}


def _spectra_for_angles(runner, out, eta0):
    sweep = load_cube(runner.sweep(os.path.join(SPECS, f"eta0-{eta0}.toml"),
                                   f"fig10-eta0-{eta0}"))[0]
    num = 9 if eta0 == 1 else 10
    path, rows = figures.spectra(sweep, "a_deg", out, f"fig{num:02d}_spectra_eta0-{eta0}", False)
    return [path], {"rows": rows}


def spectra_eta0_1(runner, out):
    """Fig. 9: spectra for skew angles at eta0 = 1. Measures the spectra's table rows
    (figures.spectra: pulse, angle, response, peak, ...)."""
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
    fig.suptitle("Extension (not a figure of the paper): complementary skew angles (same "
                 "sin 2α), cosine pulse, "
                 r"$\Pi_\delta$ = 1, $\Omega_0 = \omega_0$", fontsize=10)
    common.caption(fig, ["x", "rho", "ag", "w0", "eta0", "alpha"],
                   "Solid: α < 45°; dashed with markers: its complement 90° - α.")
    path = common.save(fig, out, "ext_complementary_angles", False)
    return [path], {"etas": etas, "pairs": pairs, "diff": diff}


def pi_delta_family(runner, out):
    """Fig. 11: the Pi_delta family at eta0 = 2. Measures the spectra's table rows
    (figures.spectra: pulse, Pi_delta, response, peak, ...)."""
    sweep = load_cube(runner.sweep(os.path.join(SPECS, "paper", "fig11-pi-delta-eta0-2.toml"),
                                   "fig11"))[0]
    path, rows = figures.spectra(sweep, "Pi_delta", out, "fig11_pi_delta_family_eta0-2", False)
    return [path], {"rows": rows}


def pilot_plan(runner, out):
    """Fig. 12: the pilot bridge in plan, docs/examples/pilot-elements.toml. Measures the plan's
    table rows, the uncoupled frequencies the paper quotes (rad/s: along the principal axes,
    torsion about the centre of rigidity; "w") and the centre of rigidity from the mass centre
    (m; "e")."""
    model = os.path.join(ROOT, "docs", "examples", "pilot-elements.toml")
    plan = plan_view.load_plan(runner.exe, model)
    path, rows = plan_view.draw_plan(plan, out, "fig12_pilot_bridge_plan", False,
                                     title="Fig. 12: the pilot bridge in plan "
                                     "(docs/examples/pilot-elements.toml)")
    deck = plan["decks"][0]
    w = [np.sqrt(k / deck["mass_kg"]) for k in deck["principal_Npm"]]
    w.append(np.sqrt(deck["torsion_about_centre_Nmprad"] / deck["inertia_kgm2"]))
    e = np.array(deck["centre_of_rigidity_m"]) - np.array(deck["mass_centre_m"])
    return [path], {"rows": rows, "w": w, "e": e}


def pilot_records(runner, out):
    """Fig. 13: the pilot bridge under the synthetic record suite. Measures the correlation rows
    of theta_m against L_e per Pi_delta (figures.correlation_theta_vs_le), the median of
    theta_norm over all Pi_delta below w0x/w_g = 2 ("low") and at or above it ("high") with the
    largest there ("top"), the number of records, and the claims' statistics over the synthetic
    suite and, when the repository's record collection is there, over the real records with
    PGA >= 0.1 g (suite_stats; "real" None without them)."""
    spec = os.path.join(SPECS, "pilot-records.toml")
    sweep = load_cube(runner.sweep(spec, "fig13-pilot-records"))[0]
    p1, rows = figures.correlation_theta_vs_le(sweep, out, "fig13a_theta_vs_persistency", False)
    p2, _ = figures.correlation_rotation_vs_w0x(sweep, out, "fig13b_rotation_vs_w0x", False)
    w0x = common.select(sweep, "w0x_over_wg", ["record", "Pi_delta"])
    theta = common.select(sweep, "theta_norm", ["record", "Pi_delta"])
    real_sweep = real_pilot_sweep(runner)
    return [p1, p2], {
        "rows": rows, "n_records": len(sweep.axes["record"]),
        "low": np.nanmedian(theta[w0x < 2]) if np.any(w0x < 2) else float("nan"),
        "high": np.nanmedian(theta[w0x >= 2]) if np.any(w0x >= 2) else float("nan"),
        "top": np.nanmax(theta[w0x >= 2]) if np.any(w0x >= 2) else float("nan"),
        "synthetic": suite_stats(sweep),
        "real": suite_stats(real_sweep, min_pga_g=0.1) if real_sweep is not None else None}


def suite_stats(sweep, min_pga_g=0.0):
    """The pilot-bridge claims measured over one record suite: the records with PGA >= min_pga_g,
    the coupling of L_e with T_m, and per Pi_delta the rank correlation of theta_m with L_e (all
    records and those that strike), the medians of theta_norm below and above w0x/w_g = 2, the
    median theta_m (the gap claim)."""
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
    norm_all = common.select(sweep, "theta_norm", keep)[use]
    out["pooled"] = (float(np.median(norm_all[w0x_all < 2])) if np.any(w0x_all < 2) else
                     float("nan"),
                     float(np.median(norm_all[w0x_all >= 2])) if np.any(w0x_all >= 2) else
                     float("nan"))
    for ip, pi in enumerate(pis):
        theta = common.select(sweep, "theta_m", keep)[use, ip]
        norm = common.select(sweep, "theta_norm", keep)[use, ip]
        hits = common.select(sweep, "impacts", keep)[use, ip] > 0
        w0x = common.select(sweep, "w0x_over_wg", keep)[use, ip]
        out["per_pi"][pi] = {
            "all": stats.spearman(le[use], theta),
            "hit": stats.spearman(le[use][hits], theta[hits]) if hits.sum() >= 3 else None,
            "n_hit": int(hits.sum()),
            "below": float(np.median(norm[w0x < 2])) if np.any(w0x < 2) else float("nan"),
            "above": float(np.median(norm[w0x >= 2])) if np.any(w0x >= 2) else float("nan"),
            "n_above": int(np.sum(w0x >= 2)),
            "median_theta": float(np.median(theta))}
    return out


# The figure function of each claim of paper_claims.FIGURES, by its key.
BY_CLAIM = {"5": self_similarity, "6": two_decks, "7": rotation_against_eta0, "8": friction,
            "9": spectra_eta0_1, "10": spectra_eta0_2, "10x": complementary_angles,
            "11": pi_delta_family, "12": pilot_plan, "13": pilot_records}
