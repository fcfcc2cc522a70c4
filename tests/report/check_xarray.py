#!/usr/bin/python3
"""xarray opens every sweep of a cube (docs/hdf5-layout.md, "Reading with xarray"): each response
is a DataArray with the sweep's axes as named, valued coordinates (label axes as str) and units,
equal to what h5py reads; the record table opens as a Dataset on the record dimension, so that
a response can be selected by record label and by T_m; fixed/ carries a unit per parameter.

usage: check_xarray.py CUBE.h5 [CUBE.h5 ...]"""
import sys

import h5py
import numpy as np
import xarray as xr


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def check_sweep(path, name, g):
    order = [text(k) for k in g.attrs["axis_order"]]
    ds = xr.open_dataset(path, engine="h5netcdf", group=f"sweeps/{name}")
    for key in order:
        axis = g["axes"][key]
        coord = ds.coords[key]
        if h5py.check_string_dtype(axis.dtype):
            expected = list(axis.asstr()[()])
            assert all(isinstance(v, str) for v in coord.values), (key, coord.values)
            assert list(coord.values) == expected, (key, list(coord.values), expected)
        else:
            assert np.array_equal(coord.values, axis[()]), key
        assert coord.attrs["units"] == text(axis.attrs["units"]), (key, coord.attrs)
    responses = [text(r) for r in g.attrs["response_order"]]
    # a response named like an axis is linked beside the axes as response_<name>
    links = [text(r) for r in g.attrs["response_links"]]
    for r, link in zip(responses, links):
        assert link == r or (link == "response_" + r and r in order), (r, link)
        da = ds[link]
        assert list(da.dims) == order, (r, da.dims, order)
        assert da.attrs["units"] == text(g["responses"][r].attrs["units"]), (r, da.attrs)
        assert np.array_equal(da.values, g["responses"][r][()], equal_nan=True), r
    fixed = g["fixed"].attrs
    keys = [text(k) for k in fixed["keys"]] if "keys" in fixed else []
    units = dict(zip(keys, (text(u) for u in fixed["units"]))) if keys else {}
    assert set(keys) == set(fixed) - {"keys", "units"}, (keys, list(fixed))
    # numbers have a unit ("1" when dimensionless), labels (pulse) none
    assert all(bool(units[k]) != isinstance(fixed[k], (str, bytes)) for k in keys), units
    if "a_deg" in units:
        assert units["a_deg"] == "deg", units
    print(f"{path} {name}: {len(g.attrs['response_order'])} responses over {order}, "
          f"fixed units {units}")
    if "records" in g and "record" in order:
        check_records(path, name, g, ds, order)


def check_records(path, name, g, ds, order):
    rec = xr.open_dataset(path, engine="h5netcdf", group=f"sweeps/{name}/records")
    assert list(rec["T_m_s"].dims) == ["record"], rec["T_m_s"].dims
    ds = ds.assign_coords(T_m=rec["T_m_s"], PGA=rec["pga_mps2"])
    labels = list(g["axes/record"].asstr()[()])
    theta = g["responses/theta_m"][()]
    ir = order.index("record")
    for k in (0, len(labels) - 1):
        picked = ds["theta_m"].sel(record=labels[k]).values
        assert np.array_equal(picked, np.take(theta, k, axis=ir), equal_nan=True), k
    t_m = g["records/T_m_s"][()]
    cut = float(np.median(t_m))
    short = ds["theta_m"].where(ds.T_m < cut, drop=True)
    assert short.sizes["record"] == int(np.count_nonzero(t_m < cut)), short.sizes
    assert list(short.coords["record"].values) == [labels[i] for i in np.flatnonzero(t_m < cut)]
    print(f"{path} {name}: selected by record label and by T_m < {cut:.3f} s "
          f"({short.sizes['record']} records)")


def main(paths):
    for path in paths:
        with h5py.File(path, "r") as f:
            for name, g in f["sweeps"].items():
                check_sweep(path, name, g)
    print("check_xarray: ok")


if __name__ == "__main__":
    main(sys.argv[1:])
