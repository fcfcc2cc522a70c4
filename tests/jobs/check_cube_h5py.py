#!/usr/bin/python3
"""Checks, with h5py alone, that a skewbridge cube is self-describing: dimension scales on every
per-cell dataset, units and descriptions, the specification and provenance attributes, chunks
contiguous along the last axis with shuffle + deflate, and the cell_echo response of the test
evaluator equal to the row-major cell index (an oracle independent of the C++ reader).

usage: check_cube_h5py.py CUBE.h5 SWEEP_NAME"""
import sys

import h5py
import numpy as np


def main(path, name):
    with h5py.File(path, "r") as f:
        assert f.attrs["format"] == "skewbridge-cube", f.attrs["format"]
        g = f["sweeps"][name]
        for key in ("spec_text", "spec_canonical", "spec_hash", "program_version",
                    "source_revision", "created_utc", "completed_utc", "family"):
            assert key in g.attrs, key
        assert "[sweep]" in g.attrs["spec_text"]
        assert g.attrs["complete"] == 1
        # The event policy that made the cells, with its documentation lists.
        pol = g["event_policy"].attrs
        assert pol["velocity_tolerance"] == 1e-10 and pol["decision_passes"] == 4, dict(pol)
        # The contact layer's thresholds with them (solver/contact/contact_policy.h).
        assert pol["contact.tie_tolerance"] == 1e-9, dict(pol)
        assert pol["contact.contact_compliance"] == 1e-9, dict(pol)
        assert pol["contact.impact_compliance"] == 1e-9, dict(pol)
        assert pol["contact.enumeration_unknowns"] == 14, dict(pol)
        assert len(pol["keys"]) == len(pol["units"]) == len(pol["relative_to"]) == len(pol) - 3
        axis_order = list(g.attrs["axis_order"])
        shape = tuple(g["axes"][k].shape[0] for k in axis_order)
        per_cell = [g["responses"][r] for r in g.attrs["response_order"]]
        per_cell += [g["status"], g["done"], g["stats/run"], g["stats/events"],
                     g["stats/steps"], g["stats/wall_s"]]
        for ds in per_cell:
            assert ds.shape == shape, (ds.name, ds.shape, shape)
            assert "units" in ds.attrs and "description" in ds.attrs, ds.name
            for k, key in enumerate(axis_order):
                assert len(ds.dims[k]) == 1, (ds.name, k)
                scale = ds.dims[k][0]
                # the same object as axes/<key> (also linked as <key> beside the responses)
                assert scale == g["axes"][key] == g[key], (scale.name, key)
                assert ds.dims[k].label == key
                assert h5py.h5ds.is_scale(scale.id)
            assert ds.chunks[-1] == shape[-1], ds.chunks
            assert ds.compression == "gzip" and ds.shuffle, ds.name
        for key in axis_order:
            axis = g["axes"][key]
            assert "units" in axis.attrs and "description" in axis.attrs
        labels = [s.decode() if isinstance(s, bytes) else s for s in g["axes"]["pulse"][()]]
        assert labels == ["cosine", "sine"], labels
        codes = list(g["status"].attrs["status_codes"])
        names = list(g["status"].attrs["status_names"])
        table = dict(zip(codes, names))
        assert table[0] == "ok" and table[-2] == "exception" and table[1] == "ray", table
        assert np.all(g["done"][()] == 1)
        status = g["status"][()]
        echo = g["responses"]["cell_echo"][()]
        expected = np.arange(np.prod(shape), dtype=float).reshape(shape)
        ok = status != -2
        assert np.array_equal(echo[ok], expected[ok])
        assert np.all(np.isnan(echo[~ok]))
        assert np.any(status == 1) and np.any(status == -2), "test grid has failures"
    print(f"h5py: {path} ok, shape {shape}, axes {axis_order}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
