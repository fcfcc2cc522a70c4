"""Running what scripts/paper needs: the sweeps of jobs/specs/paper/ and jobs/specs/ (thinned
by --quick) and the runs of jobs/specs/paper/subsystem-run.toml, with mpiexec, into a work
folder; a complete cube or run file is reused, a partial cube resumed, a changed specification
or record suite computed afresh. Nothing here draws or judges."""
import filecmp
import json
import os
import shutil
import subprocess
import tomllib

import numpy as np

from .data import ReportError, load_cube

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
SPECS = os.path.join(ROOT, "jobs", "specs")
G = 9.80665  # standard gravity, m/s^2
# The period of the subsystem's pulse (T_g, jobs/specs/paper/subsystem-run.toml) and its
# circular frequency w_g (rad/s).
T_G_S = 0.5
W_G = 2 * np.pi / T_G_S


def _toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k} = {_toml_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(v)


def to_toml(doc, comment):
    """A TOML text of a document of tables (the subset the specs and models use)."""
    lines = [f"# {comment}"]
    for table, body in doc.items():
        lines += ["", f"[{table}]"] + [f"{k} = {_toml_value(v)}" for k, v in body.items()]
    return "\n".join(lines) + "\n"


def _thin(values, keep):
    """At most `keep` values of a list, the ends included, evenly spread."""
    if len(values) <= keep:
        return values
    idx = np.unique(np.round(np.linspace(0, len(values) - 1, keep)).astype(int))
    return [values[i] for i in idx]


def quick_spec(doc):
    """A thinned copy of a sweep specification for --quick: at most 4 values of a list axis
    (8 records), at most 11 points of a linspace/logspace."""
    doc = json.loads(json.dumps(doc))
    for key, axis in doc.get("axes", {}).items():
        if isinstance(axis, list):
            doc["axes"][key] = _thin(axis, 8 if key == "record" else 4)
        elif isinstance(axis, dict):
            for kind in ("linspace", "logspace"):
                if kind in axis:
                    a, b, n = axis[kind]
                    axis[kind] = [a, b, min(int(n), 11)]
    return doc


def openmpi_env(path=os.path.join(ROOT, "scripts", "openmpi.env")):
    """Open MPI's environment of every script that starts MPI programs: the NAME=VALUE lines of
    scripts/openmpi.env (root containers, more ranks than free cores), as a dict."""
    env = {}
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            name, sep, value = line.partition("=")
            if not sep or not name.strip():
                raise ReportError(f"{path}:{number}: expected NAME=VALUE, got '{line}'")
            env[name.strip()] = value.strip()
    return env


class Runner:
    """Runs `skewbridge sweep` and `skewbridge run` into the work folder, reusing what is done."""

    def __init__(self, args):
        self.exe, self.work, self.quick, self.ranks = args.exe, args.work, args.quick, args.ranks
        self.mpiexec = args.mpiexec
        self.suite_changed = False
        self._suite = None  # the suite's folder name once made in this run

    def _call(self, cmd, what):
        env = dict(os.environ, **openmpi_env())
        done = subprocess.run(cmd, cwd=self.work, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True, env=env)
        if done.returncode not in (0, 3):  # 3: a run stopped with an expected numerical status
            said = [line for line in done.stderr.splitlines() if line.strip("- \t")]
            last = " ".join(said[:3]) if said else "no message"
            raise ReportError(f"{what} failed (status {done.returncode}): {last}")

    def sweep(self, spec_path, name, own_records=False):
        """The cube of one specification: reused when complete, resumed when partial. A record
        sweep runs the synthetic suite unless own_records keeps the specification's set."""
        with open(spec_path, "rb") as f:
            doc = tomllib.load(f)
        if self.quick:
            doc = quick_spec(doc)
        if "model" in doc["sweep"]:  # a model-file sweep: its model beside the specification
            doc["sweep"]["model"] = os.path.normpath(os.path.join(os.path.dirname(spec_path),
                                                                  doc["sweep"]["model"]))
        if "records" in doc and not own_records:
            doc["records"]["set"] = self.suite() + "/set.toml"
            labels = [f"synth-2011-{i:03d}" for i in range(8 if self.quick else 62)]
            doc["axes"]["record"] = labels
        spec = os.path.join(self.work, name + ".toml")
        text = to_toml(doc, f"{os.path.relpath(spec_path, ROOT)}" +
                       (", thinned by scripts/paper --quick" if self.quick else ""))
        out = os.path.join(self.work, name + ".h5")
        same = (os.path.exists(spec) and open(spec).read() == text and
                not ("records" in doc and self.suite_changed and not own_records))
        if same and os.path.exists(out):
            return out
        if not same:  # a new or changed specification: compute from scratch
            for stale in (out, out + ".partial"):
                if os.path.exists(stale):
                    os.remove(stale)
        with open(spec, "w") as f:
            f.write(text)
        cmd = [self.mpiexec, "-n", str(self.ranks), self.exe, "sweep", spec, "--out", out,
               "--quiet"]
        if os.path.exists(out + ".partial"):
            cmd.append("--resume")
        self._call(cmd, f"skewbridge sweep {name}")
        return out

    def suite(self):
        """The synthetic record suite standing in for the study's 62 Greek records. Generated
        afresh once per run (about 1 s) and compared with the one in the work folder: when the
        program's records changed, the suite is replaced and the record cubes are recomputed."""
        if self._suite is not None:
            return self._suite
        name = "synth8" if self.quick else "synth62"
        fresh = name + ".new"
        shutil.rmtree(os.path.join(self.work, fresh), ignore_errors=True)
        cmd = [self.exe, "records", "synth", "--count", "8" if self.quick else "62",
               "--seed", "2011", "--out", fresh]
        if self.quick:
            cmd += ["--duration-s", "10"]
        self._call(cmd, "skewbridge records synth")
        old, new = os.path.join(self.work, name), os.path.join(self.work, fresh)
        same = os.path.isdir(old) and not filecmp.dircmp(old, new).diff_files and \
            sorted(os.listdir(old)) == sorted(os.listdir(new))
        if same:
            shutil.rmtree(new)
        else:
            shutil.rmtree(old, ignore_errors=True)
            os.rename(new, old)
            self.suite_changed = True
        self._suite = name
        return name

    def run(self, name, changes):
        """A run of jobs/specs/paper/subsystem-run.toml with `changes` ({table: {key: value}})."""
        with open(os.path.join(SPECS, "paper", "subsystem-run.toml"), "rb") as f:
            doc = tomllib.load(f)
        for table, body in changes.items():
            doc[table].update(body)
        text = to_toml(doc, f"jobs/specs/paper/subsystem-run.toml with {json.dumps(changes)}")
        model = os.path.join(self.work, name + ".toml")
        out = os.path.join(self.work, name + ".h5")
        if os.path.exists(out) and os.path.exists(model) and open(model).read() == text:
            return out
        with open(model, "w") as f:
            f.write(text)
        self._call([self.exe, "run", model, "--out", out], f"skewbridge run {name}")
        return out


def pulse_run(runner, name, a_g_g, eta0, mu, pi_delta=1.0, a_deg=30.0, w0=None, eps=None,
              interval=None, delta_over_L=None):
    """A cosine-pulse run of the subsystem with the gap set from Pi_delta = delta w_g^2/a_g;
    w0 (rad/s, W0 = w0), eps_N, the output interval (s) and the deck length (from delta/L, as
    a sweep cell sets it) change the model file's when given."""
    gap = pi_delta * a_g_g * G / W_G ** 2
    changes = {"deck": {"eta0": eta0, "skew_deg": a_deg},
               "abutments": {"gap_m": gap, "mu": mu}, "excitation": {"a_g_g": a_g_g}}
    if w0 is not None:
        changes["substructure"] = {"w0": w0, "W0": w0}
    if eps is not None:
        changes["abutments"]["eps_N"] = eps
    if delta_over_L is not None:
        changes["deck"]["L"] = gap / delta_over_L
    if interval is not None:
        changes["run"] = {"output_interval_s": interval, "tail_s": 3.0}
    return runner.run(name, changes)


def _subsystem_run():
    with open(os.path.join(SPECS, "paper", "subsystem-run.toml"), "rb") as f:
        return tomllib.load(f)


# The configuration of the paper's Fig. 6 (left) as this reproduction runs it, which the paper
# runs its Fig. 8 in ("the mechanical configuration of Fig. 6 (left)"): a = 30 deg, eta0 = 0.87
# (the paper's); w0/w_g (w0 of jobs/specs/paper/subsystem-run.toml against its pulse),
# Pi_delta = 1, eps_N = 0.5, a_g = 0.5 g and the deck length of that file, hence delta/L
# (this reproduction's choice, as the paper does not state them).
FIG06_CONFIG = {"a_deg": 30.0, "eta0": 0.87, "a_g_g": 0.5, "Pi_delta": 1.0,
         "w0_over_wg": _subsystem_run()["substructure"]["w0"] / W_G,
         "eps_N": _subsystem_run()["abutments"]["eps_N"],
         "delta_over_L": 1.0 * 0.5 * G / W_G ** 2 / _subsystem_run()["deck"]["L"]}

# The friction coefficient of Fig. 5's frictional column: the paper's mu of Fig. 8 at which
# the deck of Fig. 6 (left) turns.
FIG05_MU = 0.1


# The pilot bridge's uncoupled frequencies (rad/s) along its principal axes 1 and 2 and in
# torsion about the centre of rigidity, and that centre from the mass centre (m), as published
# [Dimitrakopoulos 2011, §4; docs/theory.md §6].
PILOT_W_RADPS = (18.0, 19.0, 26.0)
PILOT_E_M = (-0.24, 0.01)


def real_pilot_sweep(runner):
    """The pilot bridge over the real records of jobs/specs/real/pilot-study-shared.toml (the
    set's path made absolute for the work folder); None when the records are not there."""
    spec = os.path.join(SPECS, "real", "pilot-study-shared.toml")
    with open(spec, "rb") as f:
        doc = tomllib.load(f)
    doc["records"]["set"] = os.path.normpath(os.path.join(os.path.dirname(spec),
                                                          doc["records"]["set"]))
    records = os.path.join(ROOT, "..", "shared", "records")
    if not os.path.exists(doc["records"]["set"]) or not os.path.isdir(records):
        return None
    path = os.path.join(runner.work, "pilot-study-shared.src.toml")
    text = to_toml(doc, "jobs/specs/real/pilot-study-shared.toml, the set's path absolute")
    if not os.path.exists(path) or open(path).read() != text:
        with open(path, "w") as f:
            f.write(text)
    saved, runner.quick = runner.quick, False  # 117 cells: never thinned
    try:
        return load_cube(runner.sweep(path, "pilot-real", own_records=True))[0]
    finally:
        runner.quick = saved
