"""Run files of re-run cells against their cube, with h5py and numpy (tests/app/rerun_cell_test.sh).

usage: check_rerun.py CUBE RECORDS_DIR CELL_RUN... -- RECORD_RUN...
       check_rerun.py --spectra CUBE CELL_RUN...  (a subsystem or pilot-bridge cube)

Each CELL_RUN (`skewbridge run --from-cube`) names its cell in origin/cell_index: its maxima,
residuals, exact corner travel, impacts and smallest impact separation must equal the cube's
stored responses bit for bit, and its stored ground acceleration must equal the AT2 file parsed
here (values in g times 9.80665 times the cube's scale factor, in that order of operations).
Each RECORD_RUN (`run --record` / `run --record-set`) must equal the cube's cell of record
NIS090.AT2, im_g = 1.1, k_factor = 1 the same way.
"""
import os
import sys

import h5py
import numpy as np

G = 9.80665


def fail(message):
    print("check_rerun: " + message, file=sys.stderr)
    sys.exit(1)


def at2_samples(path):
    """The accelerations of a PEER AT2 file in g, parsed independently of the program's reader:
    four header lines, the fourth starting with NPTS and DT, then the values."""
    with open(path, encoding="ascii") as f:
        lines = f.read().splitlines()
    npts = int(lines[3].replace(",", " ").replace("NPTS=", " ").split()[0])
    values = np.array([float(v) for line in lines[4:] for v in line.split()])
    if len(values) != npts:
        fail(f"{path}: {len(values)} values, header says {npts}")
    return values


def compare(run_path, cube, cell, records_dir, label):
    g = cube["sweeps/cells"]
    shape = g["status"].shape
    at = np.unravel_index(cell, shape)
    stored = {name: g["responses"][name][at] for name in g["responses"]}
    if g["status"][at] != 0:
        fail(f"cell {cell}: cube status {g['status'][at]}")
    with h5py.File(run_path, "r") as f:
        s = f["summary"]
        mine = {
            "x_m_d0": s["max_abs_q"][0], "y_m_d0": s["max_abs_q"][1],
            "theta_m_d0": s["max_abs_q"][2], "x_end_d0": s["q_end"][0],
            "y_end_d0": s["q_end"][1], "theta_end_d0": s["q_end"][2],
            "travel_m_d0": s["max_travel_m"][0], "impacts": float(s.attrs["impacts"]),
            "min_impact_separation": s.attrs["min_impact_separation_s"],
        }
        for name, value in mine.items():
            if np.float64(value).tobytes() != np.float64(stored[name]).tobytes():
                fail(f"{run_path}: {name} = {value!r}, cube cell {cell} stores {stored[name]!r}")
        if "histories" not in f or f["histories/t_s"].shape[0] < 100:
            fail(f"{run_path}: no histories")
        ground = f["origin/ground_acceleration"][()]
        dt = f["origin/ground_acceleration"].attrs["dt_s"]
        r = at[[as_text(k) for k in g.attrs["axis_order"]].index("record")]
        rec = as_text(g["records/label"][r])
        if rec != label and label is not None:
            fail(f"{run_path}: record {rec}, expected {label}")
        expected = at2_samples(os.path.join(records_dir, rec)) * G
        factor = stored["scale_factor"]
        if factor != 1.0:
            expected = expected * factor
        if ground.shape != (len(expected), 2) or not np.array_equal(ground[:, 0], expected):
            fail(f"{run_path}: ground acceleration differs from {rec} parsed by numpy x "
                 f"{factor!r} (largest difference "
                 f"{np.max(np.abs(ground[:, 0] - expected)) if ground.shape[0] == len(expected) else 'n/a'})")
        if np.any(ground[:, 1] != 0.0):
            fail(f"{run_path}: a y component along an x excitation")
        if dt != g["records/dt_s"][r]:
            fail(f"{run_path}: dt {dt} differs from the record table's")
    return mine["impacts"]


def as_text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def compare_spectra(cube_path, run_paths):
    """Cells of a subsystem or pilot-bridge cube: every stored maximum, residual, travel and
    impact count the run file also holds, bit for bit. Returns the impact counts."""
    cube = h5py.File(cube_path, "r")
    (name,) = list(cube["sweeps"])
    g = cube["sweeps"][name]
    impacts = []
    for path in run_paths:
        with h5py.File(path, "r") as f:
            cell = int(f["origin"].attrs["cell_index"])
            at = np.unravel_index(cell, g["status"].shape)
            s = f["summary"]
            mine = {"x_m": s["max_abs_q"][0], "y_m": s["max_abs_q"][1],
                    "theta_m": s["max_abs_q"][2], "x_end": s["q_end"][0],
                    "theta_end": s["q_end"][2], "travel_m": s["max_travel_m"][0],
                    "impacts": float(s.attrs["impacts"]),
                    "min_impact_separation": s.attrs["min_impact_separation_s"]}
            compared = [k for k in mine if k in g["responses"]]
            if len(compared) < 6:
                fail(f"{path}: only {compared} to compare")
            for k in compared:
                stored = g["responses"][k][at]
                if np.float64(mine[k]).tobytes() != np.float64(stored).tobytes():
                    fail(f"{path}: {k} = {mine[k]!r}, cube cell {cell} stores {stored!r}")
            if f["histories/t_s"].shape[0] < 50:
                fail(f"{path}: no histories")
            # The run used the policy the cube's cells ran with: the run file's group of its
            # method equals the cube's, attribute by attribute.
            groups = [p for p in ("event_policy", "time_stepping_policy") if p in f]
            if len(groups) != 1:
                fail(f"{path}: policy groups {groups}")
            mine_policy, cube_policy = f[groups[0]].attrs, g[groups[0]].attrs
            if sorted(mine_policy) != sorted(cube_policy):
                fail(f"{path}: {groups[0]} members differ from the cube's")
            for k in mine_policy:
                if not np.array_equal(mine_policy[k], cube_policy[k]):
                    fail(f"{path}: {groups[0]}.{k} = {mine_policy[k]!r}, the cube's "
                         f"{cube_policy[k]!r}")
            impacts.append(mine["impacts"])
    if not any(n > 0 for n in impacts):
        fail(f"no re-run cell of {cube_path} with impacts: {impacts}")
    print(f"check_rerun: {len(run_paths)} cells of {cube_path} equal the cube bit for bit "
          f"(impacts {impacts})")


def main():
    args = sys.argv[1:]
    if args[0] == "--spectra":
        compare_spectra(args[1], args[2:])
        return
    split = args.index("--")
    cube_path, records_dir = args[0], args[1]
    cell_runs, record_runs = args[2:split], args[split + 1:]
    cube = h5py.File(cube_path, "r")
    impacts, cells = [], set()
    for path in cell_runs:
        with h5py.File(path, "r") as f:
            o = f["origin"].attrs
            if as_text(o["kind"]) != "cube-cell":
                fail(f"{path}: origin kind {o['kind']}")
            cell = int(o["cell_index"])
        cells.add(cell)
        impacts.append(compare(path, cube, cell, records_dir, None))
    if len(cells) != len(cell_runs):
        fail(f"the re-runs cover {len(cells)} distinct cells, expected {len(cell_runs)}")
    if not any(n > 0 for n in impacts) or not any(n == 0 for n in impacts):
        fail(f"impacts of the re-run cells {impacts}: want cells with and without impacts")
    # record NIS090.AT2 (axis 0 index 0), im_g = 1.1 (index 1), k_factor = 1 (index 0)
    order = [as_text(k) for k in cube["sweeps/cells"].attrs["axis_order"]]
    if order != ["record", "im_g", "k_factor"]:
        fail(f"axis order {order}")
    target = np.ravel_multi_index((0, 1, 0), cube["sweeps/cells/status"].shape)
    for path in record_runs:
        compare(path, cube, int(target), records_dir, "NIS090.AT2")
    print(f"check_rerun: {len(cell_runs)} cells and {len(record_runs)} record runs equal the cube "
          f"bit for bit (impacts {impacts})")


if __name__ == "__main__":
    main()
