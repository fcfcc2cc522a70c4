"""Checks a `skewbridge run --out` file against docs/run-output.md and the independent CSV text.

usage: run_h5_check.py RUN.h5 RUN.csv MODEL.toml SUMMARY.txt [METHOD [TIME_STEP_S]]

METHOD (default event-driven) and TIME_STEP_S (time-stepping only) are the run.method and
run.time_step_s the model file asks for; the root attributes must name them.
"""
import math
import re
import sys

import h5py
import numpy as np


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def main():
    h5_path, csv_path, model_path, summary_path = sys.argv[1:5]
    method = sys.argv[5] if len(sys.argv) > 5 else "event-driven"
    f = h5py.File(h5_path, "r")

    # Root provenance.
    for name in ("format", "format_version", "program_version", "git_revision", "created_utc",
                 "model_text", "status", "status_message", "contact_names", "method",
                 "time_step_s"):
        if name not in f.attrs:
            fail("root attribute %s missing" % name)
    if f.attrs["format"] != "skewbridge-run" or f.attrs["format_version"] != 1:
        fail("format attributes: %r %r" % (f.attrs["format"], f.attrs["format_version"]))
    with open(model_path, encoding="utf-8") as model:
        if f.attrs["model_text"] != model.read():
            fail("model_text is not the model file verbatim")
    if f.attrs["status"] != "ok" or f.attrs["status_message"] != "":
        fail("status %r %r" % (f.attrs["status"], f.attrs["status_message"]))
    # The integrator: its name, and the step h only where the scheme has one.
    if f.attrs["method"] != method:
        fail("method %r, the model file asks for %r" % (f.attrs["method"], method))
    step = float(f.attrs["time_step_s"])
    if method == "time-stepping":
        if step != float(sys.argv[6]):
            fail("time_step_s %r, the model file asks for %s" % (step, sys.argv[6]))
    elif not math.isnan(step):
        fail("time_step_s %r for an event-driven run, expected NaN" % step)
    with open(summary_path, encoding="utf-8") as text:
        printed_step = re.search(r"method time-stepping \(h = (\S+) s\)", text.read())
    if (printed_step is not None) != (method == "time-stepping") or (
            printed_step and abs(float(printed_step.group(1)) - step) > 1e-6 * step):
        fail("printed summary's method line disagrees with time_step_s %r" % step)
    if not re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", f.attrs["created_utc"]):
        fail("created_utc %r is not ISO 8601 UTC" % f.attrs["created_utc"])
    for group in ("summary", "energy", "events", "histories"):
        if group not in f:
            fail("group %s missing" % group)

    # Every dataset documents its units and meaning.
    def visit(name, obj):
        if isinstance(obj, h5py.Dataset):
            for attr in ("units", "description"):
                if attr not in obj.attrs:
                    fail("dataset %s has no %s attribute" % (name, attr))
    f.visititems(visit)

    # Summary against the printed summary (an independent formatting path, 7 digits).
    s = f["summary"]
    n_dof = int(f.attrs["n_dof"])
    with open(summary_path, encoding="utf-8") as text:
        printed = text.read()
    maxima = re.findall(r"max\|(\w+)\| = (\S+) at (\S+) s, residual (\S+)", printed)
    if len(maxima) != n_dof:
        fail("summary printed %d maxima, file has n_dof %d" % (len(maxima), n_dof))
    names = list(s["max_abs_q"].attrs["column_names"])
    for i, (name, peak, when, residual) in enumerate(maxima):
        if names[i] != name:
            fail("column %d named %s, printed %s" % (i, names[i], name))
        for dataset, value in (("max_abs_q", peak), ("time_of_max_s", when), ("q_end", residual)):
            stored = s[dataset][i]
            if abs(stored - float(value)) > 1e-6 * abs(float(value)) + 1e-12:
                fail("%s[%d] = %r, printed %s" % (dataset, i, stored, value))
    counts = re.search(r"impacts (\d+), plastic closures (\d+), detachments (\d+), "
                       r"stick (\d+), slip (\d+)", printed).groups()
    for name, value in zip(("impacts", "plastic_closures", "detachments", "stick_transitions",
                            "slip_transitions"), counts):
        if s.attrs[name] != int(value):
            fail("summary %s = %d, printed %s" % (name, s.attrs[name], value))
    steps = re.search(r"exact (\d+), Runge-Kutta (\d+) \(\+(\d+) rejected\)", printed).groups()
    for name, value in zip(("free_steps", "rk_steps", "rk_rejected"), steps):
        if s.attrs[name] != int(value):
            fail("summary %s = %d, printed %s" % (name, s.attrs[name], value))
    if s.attrs["impacts"] < 1:
        fail("the example should pound at least once")

    # Energy ledger: the stored error equals the balance of the other entries.
    e = f["energy"].attrs
    balance = (e["kinetic_J"] + e["strain_J"]) - (e["initial_J"] + e["input_J"] - e["damping_J"]
                                                  - e["impact_J"] - e["friction_J"])
    scale = max(abs(e["input_J"]), abs(e["initial_J"]), 1.0)
    if abs(balance - e["balance_error_J"]) > 1e-12 * scale:
        fail("ledger sums to %r, balance_error_J is %r" % (balance, e["balance_error_J"]))
    if abs(e["balance_error_J"]) > 1e-3 * scale:
        fail("balance error %r J is large against %r J" % (e["balance_error_J"], scale))

    # Event log: parallel columns, impact rows consistent with the counts and with restitution.
    ev = f["events"]
    rows = int(ev.attrs["count"])
    for name in ("t_s", "kind", "contact", "impulse_N", "impulse_T", "gamma_N_before",
                 "gamma_N_after", "kinetic_loss"):
        if ev[name].shape != (rows,):
            fail("events/%s has shape %r, count %d" % (name, ev[name].shape, rows))
    kind_names = list(ev["kind"].attrs["kind_names"])
    kind = ev["kind"][...]
    impact_rows = kind == kind_names.index("impact")
    if len(np.unique(ev["t_s"][impact_rows])) != s.attrs["impacts"]:
        fail("%d distinct impact times, summary counts %d impacts"
             % (len(np.unique(ev["t_s"][impact_rows])), s.attrs["impacts"]))
    if np.count_nonzero(kind == kind_names.index("detachment")) != s.attrs["detachments"]:
        fail("detachment rows differ from the summary count")
    contacts = list(ev.attrs["contact_names"])
    if not np.all((ev["contact"][...] >= 0) & (ev["contact"][...] < len(contacts))):
        fail("event contact index out of range")
    if np.any(ev["impulse_N"][impact_rows] < 0) or np.any(ev["kinetic_loss"][impact_rows] < 0):
        fail("negative normal impulse or kinetic loss at an impact")
    # Event-driven only: the Moreau-Jean ledger's impact_J also holds the normal work of every
    # later step a contact stays closed, which the onset rows of the event log do not.
    if method == "event-driven" and abs(np.sum(np.unique(ev["kinetic_loss"][impact_rows]))
                                        - e["impact_J"]) > 1e-9 * scale:
        fail("impact kinetic losses sum to %r, ledger impact_J %r"
             % (np.sum(np.unique(ev["kinetic_loss"][impact_rows])), e["impact_J"]))

    # Histories against the CSV text (12 significant digits, so the rounding of the text adds
    # 5e-12 relative to the 1e-12 asked of the binary copy).
    h = f["histories"]
    csv = np.loadtxt(csv_path, delimiter=",", skiprows=1, ndmin=2)
    with open(csv_path, encoding="utf-8") as text:
        header = text.readline().strip().split(",")
    t = h["t_s"][...]
    q = h["q"][...]
    u = h["u"][...]
    if csv.shape[0] != t.shape[0] or q.shape != (t.shape[0], n_dof):
        fail("histories: %d CSV rows, t_s %r, q %r" % (csv.shape[0], t.shape, q.shape))

    def same(stored, text_values, what):
        tolerance = (1e-12 + 5e-12) * np.abs(stored) + 1e-300
        worst = np.max(np.abs(stored - text_values) - tolerance)
        if worst > 0:
            fail("%s differs from the CSV beyond 1e-12 relative + text rounding" % what)

    same(t, csv[:, 0], "t_s")
    same(q, csv[:, 1:1 + n_dof], "q")
    same(u, csv[:, 1 + n_dof:1 + 2 * n_dof], "u")
    nc = len(contacts)
    block = csv[:, 1 + 2 * n_dof:].reshape(csv.shape[0], nc, 4)
    same(h["gap"][...], block[:, :, 0], "gap")
    same(h["lambda_N"][...], block[:, :, 1], "lambda_N")
    same(h["lambda_T"][...], block[:, :, 2], "lambda_T")
    if not np.array_equal(h["state"][...], block[:, :, 3].astype(int)):
        fail("state differs from the CSV")
    if header[1:4] != ["x0_m", "y0_m", "theta0_rad"] or list(h["q"].attrs["column_names"][:3]) != [
            "x0", "y0", "theta0"]:
        fail("column names: CSV %r, HDF5 %r" % (header[1:4], h["q"].attrs["column_names"]))
    # The sampled peaks never exceed the integrator's tracked maxima.
    if np.any(np.max(np.abs(q), axis=0) > s["max_abs_q"][...] * (1 + 1e-12)):
        fail("a sampled |q| exceeds summary/max_abs_q")
    for name in ("q", "u", "gap", "lambda_N", "lambda_T", "state"):
        scales = h[name].dims[0]
        if len(scales) != 1 or scales[0].name != "/histories/t_s":
            fail("histories/%s dimension 0 has no t_s scale" % name)
    print("ok")


if __name__ == "__main__":
    main()
