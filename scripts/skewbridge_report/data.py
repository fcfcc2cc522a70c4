"""Reading skewbridge cubes (docs/hdf5-layout.md) and run files (docs/run-output.md) with h5py.

Every problem with an input file is raised as ReportError with one line naming the file."""
import os
from dataclasses import dataclass

import h5py
import numpy as np

from .sweep import Sweep


class ReportError(Exception):
    """Bad input: a missing, foreign or incomplete file; the message is one line."""


def as_text(value):
    """An attribute or label as str (h5py gives bytes for some variable-length strings)."""
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.ndarray) and value.shape == ():
        return as_text(value[()])
    return str(value)


def _open_h5(path):
    if not os.path.exists(path):
        raise ReportError(f"{path}: no such file")
    if os.path.isdir(path):
        raise ReportError(f"{path}: is a directory, expected an HDF5 file")
    try:
        return h5py.File(path, "r", locking=False)
    except OSError:
        raise ReportError(f"{path}: not an HDF5 file") from None


def _read_group_tree(group):
    """Every dataset and attribute below a group, as a nested dict of numpy values."""
    out = {"attrs": {k: group.attrs[k] for k in group.attrs}}
    for key, item in group.items():
        if isinstance(item, h5py.Dataset):
            out[key] = item[()]
            out[key + "@attrs"] = {k: item.attrs[k] for k in item.attrs}
        else:
            out[key] = _read_group_tree(item)
    return out


def tree_attrs(tree):
    """The attributes of a group read by _read_group_tree (an entry of Sweep.extra, or a group
    below it), strings decoded."""
    return {k: as_text(v) if isinstance(v, (str, bytes)) else v for k, v in tree["attrs"].items()}


# The sweep group's, when stored; max_scale is "inf" without a limit.
IM_ATTRS = ("im_measure", "im_description", "im_units", "max_scale", "beyond_max_scale")


def load_cube(path, allow_partial=False):
    """All sweeps of a cube file. @throws ReportError on a missing, foreign or incomplete file."""
    with _open_h5(path) as f:
        fmt = as_text(f.attrs.get("format", ""))
        if fmt == "skewbridge-run":
            raise ReportError(f"{path}: is a skewbridge run file; pass it with --run")
        if fmt != "skewbridge-cube":
            raise ReportError(f"{path}: not a skewbridge cube (root attribute format is "
                              f"'{fmt}', expected 'skewbridge-cube')")
        if "sweeps" not in f or len(f["sweeps"]) == 0:
            raise ReportError(f"{path}: a skewbridge cube without sweeps")
        sweeps = []
        for name, g in f["sweeps"].items():
            complete = int(g.attrs.get("complete", 0)) == 1
            if not complete and not allow_partial:
                raise ReportError(f"{path}: sweep '{name}' is incomplete (complete = 0); "
                                  "finish it with --resume or pass --allow-partial")
            axis_order = [as_text(k) for k in g.attrs["axis_order"]]
            axes, axis_attrs = {}, {}
            for key in axis_order:
                axis_attrs[key] = {k: as_text(v) for k, v in g["axes"][key].attrs.items()
                                   if k in ("units", "symbol", "description", "spacing")}
                values = g["axes"][key][()]
                if values.dtype.kind in "OSU":
                    axes[key] = [as_text(v) for v in values]
                else:
                    axes[key] = np.asarray(values, dtype=float)
            responses = {as_text(r): np.asarray(g["responses"][as_text(r)][()], dtype=float)
                         for r in g.attrs["response_order"]}
            status = np.asarray(g["status"][()])
            names = dict(zip((int(c) for c in g["status"].attrs["status_codes"]),
                             (as_text(n) for n in g["status"].attrs["status_names"])))
            if "done" in g:
                not_done = np.asarray(g["done"][()]) == 0
                for values in responses.values():
                    values[not_done] = np.nan
            fixed, fixed_units = {}, {}
            if "fixed" in g and "keys" in g["fixed"].attrs:
                fixed_units = dict(zip((as_text(k) for k in g["fixed"].attrs["keys"]),
                                       (as_text(u) for u in g["fixed"].attrs["units"])))
            if "fixed" in g:
                for k in g["fixed"].attrs:
                    if k in ("keys", "units"):  # the units of the fixed parameters
                        continue
                    v = g["fixed"].attrs[k]
                    fixed[k] = as_text(v) if isinstance(v, (str, bytes)) else float(v)
            extra = {key: _read_group_tree(g[key])
                     for key in ("records", "correlation", "fragility", "risk", "over_incidence",
                                 "fragility_worst_incidence") if key in g}
            for key in g["responses"]:
                if key not in responses:
                    responses[key] = np.asarray(g["responses"][key][()], dtype=float)
            response_attrs = {key: {k: as_text(v) if isinstance(v, (str, bytes)) else v
                                    for k, v in g["responses"][key].attrs.items()}
                              for key in g["responses"]}
            floor = float(g.attrs.get("round_off_floor_rad", 0.0))
            floored = floor_rotations(responses, response_attrs, floor)
            sweeps.append(Sweep(path=path, name=name, family=as_text(g.attrs.get("family", "")),
                                complete=complete, axis_order=axis_order, axes=axes,
                                responses=responses, status=status, status_names=names,
                                fixed=fixed, spec_text=as_text(g.attrs.get("spec_text", "")),
                                response_attrs=response_attrs, axis_attrs=axis_attrs,
                                fixed_units=fixed_units, extra=extra,
                                im_attrs={k: as_text(g.attrs[k]) for k in IM_ATTRS
                                          if k in g.attrs},
                                round_off_floor_rad=floor, floored_cells=floored))
        return sweeps


def floor_rotations(responses, response_attrs, floor):
    """Sets to 0, in place, every rotation (a response in rad) below `floor` in magnitude and,
    in the same cells, its normalised twin (theta_norm[_d<i>] of theta_m[_d<i>],
    theta_end_norm[_d<i>] of theta_end[_d<i>]), as the fits read them. Returns the number of
    response values set to 0."""
    if not floor > 0:
        return 0
    count = 0
    for name, values in responses.items():
        if response_attrs.get(name, {}).get("units") != "rad":
            continue
        below = np.abs(values) < floor
        below &= values != 0
        if not below.any():
            continue
        count += int(below.sum())
        values[below] = 0.0
        for twin in (name.replace("_m", "_norm", 1), name.replace("_end", "_end_norm", 1)):
            if twin != name and twin in responses and twin.startswith("theta"):
                responses[twin][below] = 0.0
                break
    return count


@dataclass
class Run:
    """One run file: histories, events and summary (docs/run-output.md)."""

    path: str
    status: str
    n_bodies: int
    contact_names: list
    t_s: np.ndarray
    q: np.ndarray  # [n, n_dof]
    state: np.ndarray  # [n, n_contacts], 0 open
    event_t_s: np.ndarray
    event_kind: np.ndarray
    event_contact: np.ndarray
    kind_names: dict  # code -> name
    max_abs_q: np.ndarray
    summary_attrs: dict
    energy: dict
    u: np.ndarray = None  # [n, n_dof] velocities
    gap: np.ndarray = None  # [n, n_contacts] normal gaps g_N in m
    model_text: str = ""
    origin: dict = None  # the group origin's attributes (a record, a scale, a cube's cell)
    ground: np.ndarray = None  # [n, 2] ground acceleration applied (m/s^2), origin group
    ground_dt_s: float = 0.0  # its sample interval (s)

    def kind_code(self, name):
        for code, n in self.kind_names.items():
            if n == name:
                return code
        return None


def load_run(path):
    """A run file written by `skewbridge run --out`. @throws ReportError without histories."""
    with _open_h5(path) as f:
        fmt = as_text(f.attrs.get("format", ""))
        if fmt == "skewbridge-cube":
            raise ReportError(f"{path}: is a skewbridge cube; pass it without --run")
        if fmt != "skewbridge-run":
            raise ReportError(f"{path}: not a skewbridge run file (root attribute format is "
                              f"'{fmt}', expected 'skewbridge-run')")
        if "histories" not in f:
            raise ReportError(f"{path}: the run file has no histories; rerun with "
                              "--output-interval S")
        ev = f["events"]
        kinds = dict(zip((int(c) for c in ev["kind"].attrs["kind_codes"]),
                         (as_text(n) for n in ev["kind"].attrs["kind_names"])))
        return Run(path=path, status=as_text(f.attrs["status"]), n_bodies=int(f.attrs["n_bodies"]),
                   contact_names=[as_text(n) for n in f.attrs["contact_names"]],
                   t_s=f["histories/t_s"][()], q=f["histories/q"][()],
                   state=f["histories/state"][()], event_t_s=ev["t_s"][()],
                   event_kind=ev["kind"][()], event_contact=ev["contact"][()],
                   kind_names=kinds, max_abs_q=f["summary/max_abs_q"][()],
                   summary_attrs={k: f["summary"].attrs[k] for k in f["summary"].attrs},
                   energy={k: f["energy"].attrs[k] for k in f["energy"].attrs
                           if k.endswith("_J")},
                   u=f["histories/u"][()] if "u" in f["histories"] else None,
                   gap=f["histories/gap"][()] if "gap" in f["histories"] else None,
                   model_text=as_text(f.attrs.get("model_text", "")),
                   origin=({k: (as_text(v) if isinstance(v, (bytes, str)) else v)
                            for k, v in f["origin"].attrs.items()} if "origin" in f else {}),
                   ground=(f["origin/ground_acceleration"][()]
                           if "origin/ground_acceleration" in f else None),
                   ground_dt_s=(float(f["origin/ground_acceleration"].attrs["dt_s"])
                                if "origin/ground_acceleration" in f else 0.0))
