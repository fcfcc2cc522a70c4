"""A model file drawn in plan (the analogue of the paper's Fig. 12): each deck's outline with its
skew, the abutment faces and joints with their gaps, the contact points named as in
solver/NOTATION.md, the bearings and piers with their stiffness and axes, the mass centre and
the centre of rigidity with the principal axes. The geometry comes from the program's own
parser (`skewbridge modes MODEL.toml --plan`), so the drawing is the model the solver runs."""
import json
import os
import subprocess

import matplotlib.pyplot as plt
import numpy as np

from . import common
from .data import ReportError


def load_plan(exe, model_path):
    """The plan of a model file as `skewbridge modes --plan` prints it (a dict)."""
    if not os.access(exe, os.X_OK):
        raise ReportError(f"{exe}: not built (cmake --build build/release --target skewbridge)")
    done = subprocess.run([exe, "modes", model_path, "--plan"], stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        said = done.stderr.strip().splitlines()
        raise ReportError(said[0] if said else f"{model_path}: skewbridge modes failed")
    return json.loads(done.stdout)


def _mn(k):
    return f"{k / 1e6:.4g} MN/m"


def _spring_text(s):
    if abs(s["k_strong_Npm"] - s["k_weak_Npm"]) <= 1e-9 * max(s["k_strong_Npm"], 1.0):
        return f"k = {_mn(s['k_strong_Npm'])} in every direction"
    return (f"k = {_mn(s['k_strong_Npm'])} along {s['strong_axis_deg']:g}°, "
            f"{_mn(s['k_weak_Npm'])} across")


def _draw_axes_cross(ax, p, s, size, color):
    """A cross at p: a long bar along the strong axis, a short one across (lengths in
    proportion to the stiffnesses)."""
    phi = np.radians(s["strong_axis_deg"])
    e1, e2 = np.array([np.cos(phi), np.sin(phi)]), np.array([-np.sin(phi), np.cos(phi)])
    ratio = s["k_weak_Npm"] / max(s["k_strong_Npm"], 1e-300)
    for e, f in ((e1, 1.0), (e2, ratio)):
        a, b = p - 0.5 * size * f * e, p + 0.5 * size * f * e
        ax.plot([a[0], b[0]], [a[1], b[1]], color=color, lw=2.2, solid_capstyle="butt",
                zorder=5)


def draw_plan(plan, out_dir, name, pdf, title=None, kind_of=None, note=""):
    """Draws `plan` (load_plan) and returns (path, rows): rows of (item, value) for a table.
    kind_of(bearing) names what a bearing of the plan stands for (None: "bearing"); `note` ends
    the caption. A centre of rigidity closer to the mass centre than the markers' size is shown
    in a zoomed inset as well."""
    decks = plan["decks"]
    pts = np.array([c for d in decks for c in d["corners_m"]])
    span = np.ptp(pts, axis=0)
    size = max(span) * 0.035
    width_in = 12.0
    fig, ax = plt.subplots(figsize=(width_in, 6.0), constrained_layout=True)
    handles = {}
    rows = []
    for i, d in enumerate(decks):
        c = np.array(d["corners_m"])  # P1, P2, P3, P4
        ring = c[[0, 3, 2, 1, 0]]
        ax.fill(ring[:, 0], ring[:, 1], color="0.9", zorder=1)
        handles["deck outline"], = ax.plot(ring[:, 0], ring[:, 1], color="0.25", lw=1.4, zorder=2)
        m = np.array(d["mass_centre_m"])
        handles["mass centre"], = ax.plot(*m, marker="o", ms=9, mfc="white", mec="k", mew=1.6,
                                          ls="none", zorder=7)
        ax.plot(*m, marker="+", ms=9, color="k", mew=1.4, zorder=8)
        label = (f"L = {d['L_m']:.4g} m, W = {d['W_m']:.4g} m, α = {d['skew_deg']:.4g}°, "
                 f"m = {d['mass_kg'] / 1e3:.5g} t")
        ax.text(m[0], c[:, 1].min() - 0.4 * size, f"{d['name']}: " + label.replace(", α", "\nα"),
                ha="center", va="top", fontsize=8, color="0.2", zorder=9)
        rows.append((f"deck {i} ({d['name']})", label))
        cr = d.get("centre_of_rigidity_m")
        if cr is not None:
            cr = np.array(cr)
            handles["centre of rigidity, principal axes"], = ax.plot(
                *cr, marker="D", ms=5, color="C3", ls="none", zorder=9)
            k1, k2 = d["principal_Npm"]
            phi = np.radians(d["axis1_deg"])
            for k, ang, tag in ((k1, phi, "1"), (k2, phi + np.pi / 2, "2")):
                e = np.array([np.cos(ang), np.sin(ang)])
                tip = cr + 3.0 * size * e
                ax.annotate("", xy=tip, xytext=cr, zorder=8,
                            arrowprops={"arrowstyle": "->", "color": "C3", "lw": 1.5})
                ax.text(*(tip + 0.4 * size * e), f"k{tag} = {_mn(k)}", color="C3", fontsize=8,
                        ha="center", va="center", zorder=9)
            e = cr - m
            rows.append((f"deck {i}: centre of rigidity from the mass centre",
                         f"({e[0]:.4g}, {e[1]:.4g}) m; principal axis 1 at "
                         f"{d['axis1_deg']:.4g}°; k1 = {_mn(k1)}, k2 = {_mn(k2)}, "
                         f"k_θ = {d['torsion_about_centre_Nmprad']:.4g} N m/rad"))
    # Faces: one line per distinct face, long enough to cover the corners that meet it.
    faces = {}
    for ct in plan["contacts"]:
        key = (tuple(np.round(ct["face_point_m"], 9)), tuple(np.round(ct["normal"], 9)),
               ct["face_deck"])
        faces.setdefault(key, []).append(ct)
    for (a_pt, n, face_deck), cts in faces.items():
        a_pt, n = np.array(a_pt), np.array(n)
        t = np.array(cts[0]["tangent"])
        proj = [t @ (np.array(ct["point_m"]) - a_pt) for ct in cts]
        lo, hi = min(proj) - 2 * size, max(proj) + 2 * size
        p0, p1 = a_pt + lo * t, a_pt + hi * t
        # the face itself: the free side is along +n, the abutment (or other deck) behind it
        if face_deck is None:
            handles["abutment face"], = ax.plot([p0[0], p1[0]], [p0[1], p1[1]], color="C0",
                                                lw=2.4, zorder=3)
            for s in np.linspace(0, 1, 12):
                q = p0 + s * (p1 - p0)
                ax.plot([q[0], q[0] - 0.8 * size * n[0] + 0.5 * size * t[0]],
                        [q[1], q[1] - 0.8 * size * n[1] + 0.5 * size * t[1]], color="C0",
                        lw=0.8, zorder=3)
        else:
            handles["joint face (moves with its deck)"], = ax.plot(
                [p0[0], p1[0]], [p0[1], p1[1]], color="C4", lw=2.4, ls="--", zorder=3)
        gap = cts[0]["gap_m"]
        cos_a = abs(n[0])
        where = "abutment" if face_deck is None else f"deck {face_deck}"
        text = (f"gap {1e3 * gap:.3g} mm\n(δ = {1e3 * gap / cos_a:.3g} mm along x)"
                if cos_a > 1e-9 else f"gap {1e3 * gap:.3g} mm")
        if face_deck is None:  # beside the face, on the abutment side, along it
            angle = np.degrees(np.arctan2(t[1], t[0]))
            angle = angle - 180 if angle > 90 else angle + 180 if angle <= -90 else angle
            ax.text(*(a_pt - 1.8 * size * n), text.replace("\n", " "), fontsize=8, color="C0",
                    ha="center", va="center", rotation=angle, rotation_mode="anchor", zorder=9)
        else:  # a joint: under its lower end, clear of the decks
            end = p0 if p0[1] < p1[1] else p1
            ax.text(end[0], end[1] - 0.3 * size, text, fontsize=8, color="C4", ha="center",
                    va="top", zorder=9)
        rows.append((f"face of {where} ({', '.join(ct['name'] for ct in cts)})",
                     f"normal ({n[0]:.4g}, {n[1]:.4g}); gap at rest {1e3 * gap:.4g} mm, "
                     f"ε_N = {cts[0]['eps_N']:g}, μ = {cts[0]['mu']:g}"))
    for ct in plan["contacts"]:
        p = np.array(ct["point_m"])
        handles["contact point"], = ax.plot(*p, marker="o", ms=6, color="C2", ls="none",
                                            zorder=9)
        inward = np.array(ct["normal"])
        ax.text(*(p + 1.1 * size * inward), ct["name"], color="C2", fontsize=10,
                fontweight="bold", ha="center", va="center", zorder=10)
    groups = {}
    for b in plan["bearings"]:
        p = np.array(b["position_m"])
        kind = (kind_of(b) if kind_of else None) or ("bearing" if b["pier"] is None else
                                                      "bearing on a pier")
        groups.setdefault((kind, _spring_text(b)), []).append(p)
        color = "C1" if kind == "bearing" else "C5" if kind == "bearing on a pier" else "C6"
        _draw_axes_cross(ax, p, b, 1.2 * size, color)
    for pr in plan["piers"]:
        p = np.array(pr["position_m"])
        groups.setdefault(("pier", _spring_text(pr)), []).append(p)
        _draw_axes_cross(ax, p, pr, 1.6 * size, "C6")
    markers = {"bearing": ("s", "C1"), "bearing on a pier": ("s", "C5"), "pier": ("o", "C6")}
    for (kind, text), ps in groups.items():
        ps = np.array(ps)
        mk, color = markers.get(kind, ("o", "C6"))
        h, = ax.plot(ps[:, 0], ps[:, 1], marker=mk, ms=6 if kind.startswith("bearing") else 8,
                     mfc="none", mec=color, mew=1.3, ls="none", zorder=6)
        handles[f"{len(ps)} × {kind}: {text}"] = h
        rows.append((f"{len(ps)} × {kind}", text))
    for s in plan["supports"]:  # lumped springs: in the table, and as the principal axes drawn
        rows.append((f"support of deck {s['deck']}", f"k_x = {_mn(s['k_x_Npm'])}, "
                     f"k_y = {_mn(s['k_y_Npm'])}, k_θ = {s['k_theta_Nmprad']:.4g} N m/rad"))
    ax.set_aspect("equal")
    ax.margins(0.04, 0.12)
    ax.autoscale_view()
    for d in decks:
        _zoom_on_centres(ax, d, size)
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    fig.set_size_inches(width_in, min(max(0.88 * width_in * (y1 - y0) / (x1 - x0), 2.5), 9.0)
                        + 2.6)
    ax.set_xlabel("x [m] (along the bridge)")
    ax.set_ylabel("y [m]")
    ax.legend(list(handles.values()), list(handles.keys()), loc="upper center",
              bbox_to_anchor=(0.5, -0.16), ncol=2, fontsize=8, frameon=False)
    ax.set_title(title or f"{os.path.basename(plan['model'])} in plan", fontsize=10)
    common.caption(fig, ["alpha"], "Contact points as in solver/NOTATION.md (P1, P3 acute; "
                   "P2, P4 obtuse); gap: normal to the face at rest; crosses at bearings and "
                   "piers: long bar along the strong axis, short bar across, in proportion; red "
                   "arrows: principal stiffness axes at the centre of rigidity." +
                   (" " + note if note else ""))
    return common.save(fig, out_dir, name, pdf), rows


def _zoom_on_centres(ax, deck, size):
    """An inset in the lower right of the plan, magnified about the mass centre, when the
    centre of rigidity lies within the markers' size of it (hidden under the mass centre's
    marker at the plan's scale): both centres and their offset."""
    cr = deck.get("centre_of_rigidity_m")
    if cr is None:
        return
    m, cr = np.array(deck["mass_centre_m"]), np.array(cr)
    e = cr - m
    if np.hypot(*e) >= size or np.hypot(*e) == 0.0:
        return
    half = 2.0 * max(abs(e[0]), abs(e[1]))
    # in the axes' own coordinates, below the deck's centre line to the right of the mass
    # centre, where the plan draws nothing: the plan's limits stay as they are
    inset = ax.inset_axes([0.62, 0.05, 0.18, 0.15], zorder=12)
    inset.plot(*m, marker="o", ms=11, mfc="white", mec="k", mew=1.6, ls="none")
    inset.plot(*m, marker="+", ms=11, color="k", mew=1.4)
    inset.plot(*cr, marker="D", ms=6, color="C3", ls="none")
    inset.annotate("", xy=cr, xytext=m, arrowprops={"arrowstyle": "->", "color": "0.3",
                                                    "lw": 1.0})
    inset.text(0.5, 0.04, f"e = ({e[0]:.3g}, {e[1]:.3g}) m", transform=inset.transAxes,
               fontsize=8, ha="center", va="bottom", color="0.2")
    inset.set_xlim(m[0] - half * 1.5, m[0] + half * 1.5)
    inset.set_ylim(m[1] - half * 0.75, m[1] + half * 0.75)
    inset.tick_params(labelsize=7)
    inset.locator_params(nbins=3)
    inset.set_title("the two centres, magnified [m]", fontsize=8)
