#!/usr/bin/python3
"""The numbers of docs/validation.md, measured from the cubes run.sh made and from batches of
`skewbridge run`: one block per fact of docs/theory.md §4 and per trend of §6.

usage: facts.py SKEWBRIDGE WORK_DIR   (run by scripts/validation/run.sh)"""
import os
import subprocess
import sys
import tempfile

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
sys.dont_write_bytecode = True  # keep the source tree free of __pycache__
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from skewbridge_report import data, stats  # noqa: E402


def cube(work, file):
    """(axis order, axes, responses with the per-cell status) of the first sweep of a complete
    cube in the work folder, read by the report's reader (data.load_cube)."""
    sweep = data.load_cube(os.path.join(work, file))[0]
    resp = dict(sweep.responses)
    resp["status"] = sweep.status
    return sweep.axis_order, sweep.axes, resp


def fact1(work):
    print("## Fact 1: frictionless full-edge impact rotates iff eta0 > 1")
    order, ax, r = cube(work, "rotation-vs-eta0.h5")
    th = r["theta_norm"]
    eta = ax["eta0"]
    below = np.nanmax(np.abs(th[eta <= 1.0]))
    above = np.nanmax(th[eta > 1.0].reshape(np.count_nonzero(eta > 1.0), -1), axis=1)
    impacts = r["impacts"][eta <= 1.0]
    print(f"rotation-vs-eta0 (a = 30 deg, mu = 0): {int(np.sum(eta <= 1))} eta0 values <= 1, "
          f"{th[eta <= 1].size} cells, {int(np.sum(impacts > 0))} with impacts: "
          f"max theta_norm = {below:.3e}")
    print(f"  eta0 > 1: smallest per-eta0 maximum theta_norm = {np.min(above):.3e} "
          f"(at eta0 = {eta[eta > 1][np.argmin(above)]:.2f})")
    for file in ("eta0-1.h5", "eta0-2.h5"):
        order, ax, r = cube(work, file)
        th = r["theta_norm"]
        print(f"{file}: max theta_norm over all {th.size} cells = {np.nanmax(th):.3e}, "
              f"cells with impacts {int(np.sum(r['impacts'] > 0))}, failed {int(np.sum(r['status'] != 0))}")


def fact2(work):
    print("## Fact 2: friction and the onset of rotation (friction-eta0.h5, a = 30 deg)")
    order, ax, r = cube(work, "friction-eta0.h5")
    assert order == ["eta0", "mu", "w0_over_wg"], order
    eta, mus = ax["eta0"], ax["mu"]
    a = np.radians(30.0)
    for im, mu in enumerate(mus):
        peak = np.nanmax(r["theta_norm"][:, im, :], axis=1)
        rotating = eta[peak > 1e-9]
        onset = rotating.min() if len(rotating) else float("nan")
        threshold = 1.0 / (1.0 - mu / np.tan(a))
        line = ", ".join(f"{e:.2f}:{p:.3g}" for e, p in zip(eta, peak))
        print(f"mu = {mu:g}: predicted onset for a longitudinal approach eta0 > "
              f"{threshold:.3f}; smallest rotating eta0 on the grid = {onset:.2f}; "
              f"failed cells {int(np.sum(r['status'][:, im, :] != 0))}")
        print(f"  max theta_norm per eta0: {line}")


def fact2_run(exe, tmp):
    """The impact sequence of one frictional run below eta0 = 1 that rotates: which impact
    starts the rotation, with the sign of its slip."""
    a = np.radians(30.0)
    text = subsystem_model(30.0, 0.75, 0.63 * 2 * np.pi / 0.5, 0.3, "cosine")
    f = run_model(exe, text.replace("output_interval_s = 0.0", "output_interval_s = 0.001"),
                  tmp, "f2")
    ev, names = f["events"], [str(n) for n in f.attrs["contact_names"]]
    t, q, u = f["histories/t_s"][()], f["histories/q"][()], f["histories/u"][()]
    print("one run (a = 30 deg, eta0 = 0.75, mu = 0.3, cosine, w0/w_g = 0.63, docs/examples/"
          f"subsystem.toml otherwise): max theta {f['summary/max_abs_q'][2]:.3e} rad")
    for i in range(int(ev.attrs["count"])):
        j = int(np.searchsorted(t, ev["t_s"][i]))
        slip = u[j - 1, 0] * np.sin(a) + u[j - 1, 1] * np.cos(a)
        print(f"  t = {ev['t_s'][i]:.4f} s impact at {names[ev['contact'][i]]}: Lambda_N "
              f"{ev['impulse_N'][i]:.3g} N s, Lambda_T {ev['impulse_T'][i]:.3g} N s, slip before "
              f"~{slip:+.3f} m/s; theta before {q[j - 1, 2]:.2e}, 2 ms after "
              f"{q[min(j + 2, len(t) - 1), 2]:.2e} rad")
    f.close()


def fact3(work):
    print("## Fact 3: a = 0 is the pounding oscillator (zero-skew.h5, mu = 0.3)")
    order, ax, r = cube(work, "zero-skew.h5")
    print(f"cells {r['x_norm'].size}, with impacts {int(np.sum(r['impacts'] > 0))}, max x_norm "
          f"{np.nanmax(r['x_norm']):.4f}, max y_norm {np.nanmax(r['y_norm']):.3e}, "
          f"max theta_norm {np.nanmax(r['theta_norm']):.3e}")


def run_model(exe, text, tmp, tag):
    model = os.path.join(tmp, tag + ".toml")
    out = os.path.join(tmp, tag + ".h5")
    with open(model, "w") as f:
        f.write(text)
    subprocess.run([exe, "run", model, "--out", out], check=True, stdout=subprocess.DEVNULL)
    return h5py.File(out, "r")


def subsystem_model(a_deg=30.0, eta0=2.0, w0=12.0, mu=0.0, shape="cosine", scale=1.0):
    """docs/examples/subsystem.toml with parameters replaced; `scale` multiplies a_g, the gap
    and L together, so every dimensionless group stays fixed (fact 4)."""
    text = open(os.path.join(ROOT, "docs/examples/subsystem.toml")).read()
    out = []
    for line in text.splitlines():
        key = line.split("=")[0].strip()
        value = {"L": 30.0 * scale, "eta0": eta0, "skew_deg": a_deg, "w0": w0, "W0": w0,
                 "mu": mu, "a_g_g": 0.5 * scale, "gap_m": 0.03 * scale,
                 "shape": f'"{shape}"', "output_interval_s": 0.0}.get(key)
        out.append(line if value is None or "=" not in line else f"{key} = {value}")
    return "\n".join(out) + "\n"


def fact4(exe, tmp):
    print("## Fact 4: self-similarity in a_g (a_g, gap and L scaled together)")
    w_g = 2.0 * np.pi / 0.5
    for shape in ("cosine", "sine"):
        norms = []
        for scale in (0.1, 1.0, 10.0):
            f = run_model(exe, subsystem_model(shape=shape, scale=scale), tmp, f"f4-{shape}-{scale}")
            q = f["summary/max_abs_q"][()]
            a_g = 0.5 * scale * 9.80665
            L = 30.0 * scale
            W = L * np.sin(2 * np.radians(30)) / (2 * 2.0)
            rho = np.sqrt((L ** 2 + W ** 2 / np.cos(np.radians(30)) ** 2) / 12.0)
            norms.append(np.array([q[0], q[1], q[2] * rho]) * w_g ** 2 / a_g)
            impacts = int(f["summary"].attrs["impacts"])
        norms = np.array(norms)
        dev = np.max(np.abs(norms - norms[1]) / np.abs(norms[1]))
        print(f"{shape}: dimensionless maxima (x, y, theta rho) at a_g = 0.05, 0.5, 5 g: "
              f"{np.array2string(norms[1], precision=5)}, {impacts} impacts; "
              f"max relative deviation {dev:.2e}")


def fact5_and_trends(work):
    print("## Fact 5 / §6: rotation against eta0 (rotation-vs-eta0.h5, a = 30 deg, cosine)")
    order, ax, r = cube(work, "rotation-vs-eta0.h5")
    assert order == ["eta0", "W0_over_w0", "w0_over_wg"], order
    eta, W, w = ax["eta0"], ax["W0_over_w0"], ax["w0_over_wg"]
    th = r["theta_norm"]
    peak = np.nanmax(th, axis=2)
    arg = np.nanargmax(np.where(np.isfinite(th), th, -1), axis=2)
    above = eta > 1.0
    for iw, Wr in enumerate(W):
        p = peak[above, iw]
        d = np.diff(p)
        falls = [(eta[above][k], eta[above][k + 1], p[k], p[k + 1]) for k in range(len(d))
                 if d[k] < -1e-3 * max(p.max(), 1e-300)]
        first = falls[0] if falls else None
        s13 = np.polyfit(eta[(eta > 1) & (eta <= 3)], peak[(eta > 1) & (eta <= 3), iw], 1)[0]
        s34 = np.polyfit(eta[eta >= 3], peak[eta >= 3, iw], 1)[0]
        print(f"W0/w0 = {Wr:g}: max over w0/w_g at eta0 = 1.25, 2, 3, 4: "
              f"{np.interp([1.25, 2, 3, 4], eta, peak[:, iw]).round(4).tolist()}; decreases "
              f"between consecutive eta0 > 1: {len(falls)} of {len(d)}"
              + (f", first {first[0]:.2f} -> {first[1]:.2f} ({first[2]:.4f} -> {first[3]:.4f})"
                 if first else "")
              + f"; mean slope d/d eta0 on (1, 3] {s13:.4f}, on [3, 4] {s34:.4f}")
        jumps = sorted(set(np.round(w[arg[above, iw]], 3)))
        print(f"  w0/w_g at the maximum for eta0 > 1 takes {len(jumps)} values: {jumps}")
        # The trend at fixed w0/w_g: for how many frequency ratios is theta(eta0) monotonic?
        sub = th[above, iw, :]
        mono = np.all(np.diff(sub, axis=0) >= -1e-3 * np.nanmax(sub), axis=0)
        print(f"  at fixed w0/w_g, theta_norm(eta0) non-decreasing over eta0 > 1 for "
              f"{int(mono.sum())} of {len(w)} frequency ratios "
              f"(w0/w_g <= 1: {int(mono[w <= 1].sum())} of {int(np.sum(w <= 1))}; > 1: "
              f"{int(mono[w > 1].sum())} of {int(np.sum(w > 1))})"
              + (f"; not monotonic for w0/w_g in {w[~mono].min():.3f}..{w[~mono].max():.3f}"
                 if np.any(~mono) else ""))
    means = [float(np.mean(peak[above, iw])) for iw in range(len(W))]
    print("mean over eta0 > 1 of the maximum rotation, per W0/w0 = "
          + ", ".join(f"{Wr:g}: {m:.4f}" for Wr, m in zip(W, means)))
    # Impacts at the maximising cell, W0/w0 = 1
    iw1 = int(np.argmin(abs(W - 1.0)))
    imp = r["impacts"][above, iw1, :][np.arange(np.sum(above)), arg[above, iw1]]
    print("W0/w0 = 1: impacts at the maximising cell per eta0 > 1: "
          + ", ".join(f"{e:.2f}:{int(i)}" for e, i in zip(eta[above], imp)))
    fig, axs = plt.subplots(1, 2, figsize=(10, 4.2), constrained_layout=True)
    for iw, Wr in enumerate(W):
        axs[0].plot(eta, peak[:, iw], "o-", ms=3, label=rf"$\Omega_0/\omega_0$ = {Wr:g}")
    axs[0].set_xlabel(r"$\eta_0$")
    axs[0].set_ylabel(r"$\max_{\omega_0/\omega_g}\ \theta_m\,\rho\,\omega_g^2/a_g$")
    axs[0].legend(fontsize=9)
    axs[0].set_title("maximum over the spectrum", fontsize=10)
    colors = plt.cm.viridis(np.linspace(0, 0.9, 6))
    for c, target in zip(colors, (0.3, 0.5, 0.8, 1.0, 1.5, 2.5)):
        k = int(np.argmin(abs(w - target)))
        axs[1].plot(eta, th[:, iw1, k], "o-", ms=3, color=c, label=rf"$\omega_0/\omega_g$ = {w[k]:.2f}")
    axs[1].set_xlabel(r"$\eta_0$")
    axs[1].set_ylabel(r"$\theta_m\,\rho\,\omega_g^2/a_g$")
    axs[1].set_title(r"at fixed $\omega_0/\omega_g$, $\Omega_0/\omega_0$ = 1", fontsize=10)
    axs[1].legend(fontsize=9, ncol=2)
    for a_ in axs:
        a_.grid(alpha=0.3)
    fig.savefig(os.path.join(work, "facts-rotation-fixed-w0.png"), dpi=100)
    plt.close(fig)

    print("## §6: sin 2a scaling at fixed eta0 (eta0-1.h5, eta0-2.h5)")
    for file in ("eta0-1.h5", "eta0-2.h5"):
        order, ax, r = cube(work, file)
        a = ax["a_deg"]
        for ip, pulse in enumerate(ax["pulse"]):
            for resp in ("y_norm", "theta_norm"):
                pk = np.nanmax(r[resp][ip], axis=1)
                if np.max(pk) <= 1e-9:
                    print(f"{file} {pulse} {resp}: zero everywhere")
                    continue
                pairs = [(a[i], a[j]) for i in range(len(a)) for j in range(len(a))
                         if i < j and abs(a[i] + a[j] - 90) < 1e-9]
                ratios = [pk[list(a).index(p)] / pk[list(a).index(q)] for p, q in pairs]
                s2a = np.sin(2 * np.radians(a))
                r2_sin = _r2_through_origin(s2a, pk)
                r2_a = _r2_through_origin(np.radians(a), pk)
                print(f"{file} {pulse} {resp}: peaks per a = "
                      + ", ".join(f"{x:g}:{v:.4f}" for x, v in zip(a, pk))
                      + "; complementary-angle ratios "
                      + ", ".join(f"{p:g}/{q:g} {v:.3f}" for (p, q), v in zip(pairs, ratios))
                      + f"; R^2 of peak = c sin2a: {r2_sin:.3f}, of peak = c a: {r2_a:.3f}")

    print("## §6: coupling against w0/w_g (eta0-2.h5 against the a = 0 oscillator zero-skew.h5)")
    order, ax, r = cube(work, "eta0-2.h5")
    o0, ax0, r0 = cube(work, "zero-skew.h5")
    w, w_0 = ax["w0_over_wg"], ax0["w0_over_wg"]
    idx = [int(np.argmin(abs(w - x))) for x in w_0]
    assert np.allclose(w[idx], w_0, rtol=1e-9)
    for ip, pulse in enumerate(ax["pulse"]):
        x0 = r0["x_norm"][ip]
        lines = []
        for ia, a in enumerate(ax["a_deg"]):
            dx = np.abs(r["x_norm"][ip, ia, idx] - x0) / np.maximum(x0, 1e-12)
            yr = r["y_norm"][ip, ia, idx] / np.nanmax(r["y_norm"][ip, ia])
            tr = r["theta_norm"][ip, ia, idx] / max(np.nanmax(r["theta_norm"][ip, ia]), 1e-300)
            hi = w_0 > 2.0
            lines.append(f"a={a:g}: |dx|/x0 max {np.nanmax(dx[~hi]):.3f} (w<=2) vs "
                         f"{np.nanmax(dx[hi]):.3f} (w>2); y/ypeak max(w>2) {np.nanmax(yr[hi]):.3f}; "
                         f"theta/thetapeak max(w>2) {np.nanmax(tr[hi]):.3f}")
        print(f"{pulse}:\n  " + "\n  ".join(lines))

    print("## §6: the Pi_delta family (pi-delta.h5, a = 20 deg, eta0 = 1.48)")
    order, ax, r = cube(work, "pi-delta.h5")
    for ip, pulse in enumerate(ax["pulse"]):
        for resp in ("x_norm", "y_norm", "theta_norm"):
            pk = np.nanmax(r[resp][ip], axis=1)
            wpk = ax["w0_over_wg"][np.nanargmax(r[resp][ip], axis=1)]
            print(f"{pulse} {resp} peak per Pi_delta: "
                  + ", ".join(f"{p:g}:{v:.4f}@{x:.2f}" for p, v, x in zip(ax["Pi_delta"], pk, wpk)))

    print("## §6: spectra shape (eta0-2.h5): peak value and w0/w_g per a")
    order, ax, r = cube(work, "eta0-2.h5")
    for ip, pulse in enumerate(ax["pulse"]):
        for resp in ("x_norm", "y_norm", "theta_norm"):
            pk = np.nanmax(r[resp][ip], axis=1)
            wpk = ax["w0_over_wg"][np.nanargmax(r[resp][ip], axis=1)]
            lo = r[resp][ip][:, 0]
            hi = r[resp][ip][:, -1]
            print(f"{pulse} {resp}: " + ", ".join(f"a={a:g}: {v:.3f}@{x:.2f}" for a, v, x in
                                                  zip(ax["a_deg"], pk, wpk))
                  + f"; at w0/w_g = 0.1: {lo.min():.3f}..{lo.max():.3f}; at 10: "
                  f"{hi.min():.4f}..{hi.max():.4f}")


def _r2_through_origin(x, y):
    c = np.dot(x, y) / np.dot(x, x)
    return 1.0 - np.sum((y - c * x) ** 2) / np.sum((y - y.mean()) ** 2)


def _impact_energy(f):
    """(impacts, gains, largest gain [J], net impact loss [J]) of one run file."""
    ev = f["events"]
    kind = ev["kind"][()]
    t = ev["t_s"][()][kind == 0]
    loss = ev["kinetic_loss"][()][kind == 0]
    _, first = np.unique(t, return_index=True)
    loss = loss[first]  # a multi-contact impact repeats its loss on each row
    return len(loss), int(np.sum(loss < 0)), float(max(0.0, -loss.min())) if len(loss) else 0.0, \
        float(loss.sum())


def pilot_model(scale, mu):
    """docs/examples/pilot-bridge.toml with its signal scaled and mu replaced."""
    folder = os.path.join(ROOT, "docs/examples")
    out = []
    for line in open(os.path.join(folder, "pilot-bridge.toml")).read().splitlines():
        key = line.split("=")[0].strip()
        if key == "file":
            line = f'file = "{os.path.join(folder, "pilot-signal.txt")}"\nscale = {scale}'
        elif key == "mu":
            line = f"mu = {mu}"
        elif key == "output_interval_s":
            line = "output_interval_s = 0.0"
        out.append(line)
    return "\n".join(out) + "\n"


def fact6(exe, tmp):
    print("## Fact 6: energy at impacts (batches of skewbridge run; eps_N = 0.5)")
    rows = []
    for mu in (0.0, 0.3, 0.6, 1.0):
        for shape in ("cosine", "sine"):
            for a in (20.0, 30.0, 45.0, 60.0):
                for eta0 in (0.5, 1.0, 2.0, 3.0):
                    for ratio in np.geomspace(0.3, 3.0, 8):
                        w0 = ratio * 2 * np.pi / 0.5
                        f = run_model(exe, subsystem_model(a, eta0, w0, mu, shape), tmp, "f6")
                        e = dict(f["energy"].attrs)
                        rows.append(("subsystem", mu, f"{shape} a={a:g} eta0={eta0:g} "
                                     f"w0/w_g={ratio:.2f}") + _impact_energy(f)
                                    + (float(e["input_J"]), float(e["balance_error_J"]),
                                       f.attrs["status"]))
                        f.close()
    for mu in (0.3, 0.6, 1.0):
        for scale in (2.0, 3.0, 4.0, 5.0, 6.0, 8.0):
            f = run_model(exe, pilot_model(scale, mu), tmp, "f6p")
            e = dict(f["energy"].attrs)
            rows.append(("pilot", mu, f"signal x {scale:g}") + _impact_energy(f)
                        + (float(e["input_J"]), float(e["balance_error_J"]), f.attrs["status"]))
            f.close()
    for family in ("subsystem", "pilot"):
        for mu in sorted(set(r[1] for r in rows if r[0] == family)):
            sel = [r for r in rows if r[0] == family and r[1] == mu]
            impacts = sum(r[3] for r in sel)
            gains = sum(r[4] for r in sel)
            with_gain = [r for r in sel if r[4] > 0]
            bal = max(abs(r[8]) / r[7] for r in sel if r[7] > 0)
            worst = max(sel, key=lambda r: r[5] / r[7] if r[7] > 0 else 0)
            statuses = {}
            for r in sel:
                statuses[r[9]] = statuses.get(r[9], 0) + 1
            print(f"{family} mu = {mu:g}: {len(sel)} runs {statuses}, {impacts} impacts, {gains} "
                  f"gain kinetic energy (in {len(with_gain)} runs); largest gain "
                  f"{worst[5]:.4g} J = {100 * worst[5] / worst[7]:.3f} % of that run's input "
                  f"({worst[2]}); largest |balance error| / input {bal:.1e}")
            for r in with_gain[:4]:
                print(f"    {r[2]}: {r[4]} of {r[3]} impacts gain, largest {r[5]:.4g} J "
                      f"({100 * r[5] / r[7]:.3f} % of input), net impact loss {r[6]:.4g} J")


def pilot(work):
    print("## §6: pilot bridge over the 62-record suite (pilot-records.h5)")
    order, ax, r = cube(work, "pilot-records.h5")
    assert order == ["record", "Pi_delta"], order
    print(f"cells {r['theta_m'].size}, failed {int(np.sum(r['status'] != 0))}, with impacts "
          f"{int(np.sum(r['impacts'] > 0))}; w0x/w_g range {np.nanmin(r['w0x_over_wg']):.2f}.."
          f"{np.nanmax(r['w0x_over_wg']):.2f}")
    for ipi, pi in enumerate(ax["Pi_delta"]):
        le, th = r["L_e"][:, ipi], r["theta_m"][:, ipi]
        row = stats.correlation_row(le, th)
        tn, w = r["theta_norm"][:, ipi], r["w0x_over_wg"][:, ipi]
        lo, hi = tn[w < 2], tn[w >= 2]
        print(f"Pi_delta = {pi:g}: theta_m vs L_e Pearson {row['pearson']:.3f}, Spearman "
              f"{row['spearman']:.3f}, log-log slope {row['slope']:.3f} (R^2 {row['r2']:.3f}, "
              f"{row['n_log']} records with theta_m > 0); theta_norm median/max for w0x/w_g < 2: "
              f"{np.median(lo):.4f}/{np.max(lo):.4f} ({len(lo)}), >= 2: "
              + (f"{np.median(hi):.4f}/{np.max(hi):.4f} ({len(hi)})" if len(hi) else "none"))
        hit = r["impacts"][:, ipi] > 0
        sub = stats.correlation_row(le[hit], th[hit])
        mid = hit & (w >= 1) & (w < 2)
        sub_mid = stats.correlation_row(le[mid], th[mid])
        print(f"  records with impacts: {int(hit.sum())}, Spearman(theta_m, L_e) over them "
              f"{sub['spearman']:.3f}, log-log slope {sub['slope']:.3f}; within 1 <= w0x/w_g < 2 "
              f"and impacts ({int(mid.sum())}): Spearman {sub_mid['spearman']:.3f}; "
              f"w0x/w_g of records with impacts {np.min(w[hit]):.2f}..{np.max(w[hit]):.2f}")
    le, w, pga = r["L_e"][:, 0], r["w0x_over_wg"][:, 0], r["a_g"][:, 0]
    print(f"suite: Spearman(L_e, w0x/w_g) = {stats.spearman(le, w):.3f}; PGA "
          f"{pga.min() / 9.80665:.3f}..{pga.max() / 9.80665:.3f} g (spread x{pga.max() / pga.min():.1f}), "
          f"w_g {r['w_g'][:, 0].min():.2f}..{r['w_g'][:, 0].max():.2f} rad/s "
          f"(L_e spread x{le.max() / le.min():.1f})")


def main(exe, work):
    fact1(work)
    fact2(work)
    fact3(work)
    with tempfile.TemporaryDirectory() as tmp:
        fact2_run(exe, tmp)
        fact4(exe, tmp)
        fact6(exe, tmp)
    fact5_and_trends(work)
    pilot(work)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
