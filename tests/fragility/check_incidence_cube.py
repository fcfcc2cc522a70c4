"""Checks what a sweep with an incidence_deg axis stores over the angle, from the cube's own
cells with numpy: over_incidence/max, median and angle_of_max_deg of every response of the bridge
against np.max, np.median and the axis coordinate of np.argmax over the axis (cells not done
with status ok read as NaN); the attributes that say what each dataset reduces; the same
datasets through xarray (h5netcdf) on the remaining axes; and, per stripe, the worst angle's
fraction of exceedance at least that of every single angle.

usage: check_incidence_cube.py FILE.h5 SWEEP
"""
import sys

import h5py
import numpy as np
import xarray as xr

# The per-cell values that describe the excitation, the model or the scaling: not reduced.
INPUTS = {"a_g", "w_g", "L_e", "delta", "pga", "pgv", "pgd", "T_m", "arias", "D5_95", "T1", "im",
          "im_unscaled", "scale_factor", "scaled_too_far", "w0x_over_wg", "band"}


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def main():
    path, sweep = sys.argv[1], sys.argv[2]
    g = h5py.File(path, "r")["sweeps/" + sweep]
    axes = [text(a) for a in g.attrs["axis_order"]]
    k = axes.index("incidence_deg")
    angles = g["axes/incidence_deg"][()]
    rest = axes[:k] + axes[k + 1:]
    o = g["over_incidence"]
    assert text(o.attrs["reduces"]) == "incidence_deg"
    assert np.array_equal(o.attrs["incidence_deg"], angles)
    assert [text(a) for a in o.attrs["axis_order"]] == rest
    responses = [text(r) for r in g.attrs["response_order"]]
    expected = [r for r in responses if r not in INPUTS]
    assert [text(r) for r in o.attrs["responses"]] == expected, (list(o.attrs["responses"]), expected)
    assert any(r.startswith("ls_") for r in expected), "no limit state reduced"
    ok = (g["done"][()] == 1) & (g["status"][()] == 0)
    compared = 0
    for r in expected:
        v = np.where(ok, g["responses/" + r][()], np.nan)
        # np.max and np.median propagate NaN: a reduced cell with a missing angle is NaN
        want_max = np.max(v, axis=k)
        want_median = np.median(v, axis=k)
        filled = np.where(np.isnan(v), -np.inf, v)
        want_angle = np.where(np.isnan(want_max), np.nan, angles[np.argmax(filled, axis=k)])
        for stat, want in (("max", want_max), ("median", want_median),
                           ("angle_of_max_deg", want_angle)):
            ds = o[stat][r]
            got = ds[()]
            assert got.shape == want.shape, (r, stat, got.shape, want.shape)
            if stat == "median":
                ok_num = np.isnan(got) == np.isnan(want)
                assert ok_num.all(), (r, stat)
                m = ~np.isnan(want)
                same = (got[m] == want[m]) | (np.abs(got[m] - want[m]) <= 1e-15 * np.abs(want[m]))
                assert np.all(same), (r, stat, got[m], want[m])
            else:
                assert np.array_equal(got, want, equal_nan=True), (r, stat, got, want)
            assert text(ds.attrs["reduces"]) == "incidence_deg" and text(ds.attrs["statistic"]) == stat
            assert text(ds.attrs["response"]) == r
            units = "deg" if stat == "angle_of_max_deg" else text(g["responses/" + r].attrs["units"])
            assert text(ds.attrs["units"]) == units, (r, stat, ds.attrs["units"])
            assert [text(ds.dims[i][0].name).split("/")[-1] for i in range(len(rest))] == rest
            compared += int(np.isfinite(want).sum())
    assert compared > 0, "nothing finite to compare"
    # xarray opens each statistic as one Dataset over the remaining axes
    for stat in ("max", "median", "angle_of_max_deg"):
        ds = xr.open_dataset(path, engine="h5netcdf", group=f"sweeps/{sweep}/over_incidence/{stat}")
        for r in expected:
            assert list(ds[r].dims) == rest, (stat, r, ds[r].dims)
            assert np.array_equal(ds[r].values, o[stat][r][()], equal_nan=True), (stat, r)
        for key in rest:
            a = g["axes/" + key]
            want = list(a.asstr()[()]) if h5py.check_string_dtype(a.dtype) else a[()]
            assert np.array_equal(np.asarray(ds.coords[key].values), np.asarray(want)), key
    # the worst angle's fraction per stripe against each angle's
    w, f = g["fragility_worst_incidence"], g["fragility"]
    combo = [text(a) for a in f.attrs["axis_order"]]
    wcombo = [text(a) for a in w.attrs["axis_order"]]
    assert wcombo == [a for a in combo if a != "incidence_deg"], (wcombo, combo)
    ki = combo.index("incidence_deg")
    stripes = 0
    for name in f.attrs["limit_states"]:
        n, e = f[name]["stripe_n"][()], f[name]["stripe_exceeded"][()]
        wn, we = w[name]["stripe_n"][()], w[name]["stripe_exceeded"][()]
        for i in range(len(angles)):
            an, ae = np.take(n, i, axis=ki), np.take(e, i, axis=ki)
            assert np.all(wn == an), (name, "every cell of this sweep is used at every angle")
            assert np.all(we >= ae), (name, angles[i], we, ae)
            assert np.all(we / np.maximum(wn, 1) >= ae / np.maximum(an, 1))
        # the worst angle is no more than the union: at most the sum over the angles
        assert np.all(we <= e.sum(axis=ki)), name
        stripes += int(wn.size)
    print("over_incidence of %s: %d responses x 3 statistics agree with numpy (%d finite values), "
          "xarray reads them; worst-angle fractions >= every angle's at %d stripes"
          % (sweep, len(expected), compared, stripes))


if __name__ == "__main__":
    main()
