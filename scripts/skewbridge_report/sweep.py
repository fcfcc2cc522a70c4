"""A sweep of a cube held in memory (data.load_cube reads it from /sweeps/<name>): what the
planning, the figures and the tables of the report take. Nothing here reads a file, so a sweep
can be built in memory (tests/report/planning_test.py)."""
from dataclasses import dataclass, field

import numpy as np


@dataclass
class Sweep:
    """One /sweeps/<name> group read into memory: axes, responses and per-cell status."""

    path: str
    name: str
    family: str
    complete: bool
    axis_order: list
    axes: dict  # key -> np.ndarray of float, or list of str for label axes
    responses: dict  # name -> ndarray of shape = axis sizes in axis_order
    status: np.ndarray
    status_names: dict  # code -> name
    fixed: dict
    spec_text: str
    response_attrs: dict  # name -> {attribute: value} of responses/<name>
    axis_attrs: dict = field(default_factory=dict)  # key -> {units, symbol, description}
    fixed_units: dict = field(default_factory=dict)  # fixed key -> unit ("1", "", "deg", ...)
    extra: dict = field(default_factory=dict)  # optional groups (records/, correlation/)
    # The intensity measure of a record sweep (attributes im_measure, im_description, im_units of
    # the sweep group; empty without [records] scale_to or im).
    im_attrs: dict = field(default_factory=dict)
    # Rotations (rad) below it are round-off, drawn and tabulated as 0 with their normalised
    # twins (attribute round_off_floor_rad of the sweep group; 0: none given); floored_cells
    # counts the cells of the responses set to 0 (data.floor_rotations).
    round_off_floor_rad: float = 0.0
    floored_cells: int = 0

    def shape(self):
        """The axis lengths in axis_order: the shape of every response."""
        return tuple(len(self.axes[k]) for k in self.axis_order)

    def has_axis(self, key, min_size=1):
        """Whether the sweep has axis `key` with at least min_size values."""
        return key in self.axes and len(self.axes[key]) >= min_size

    def cells(self):
        """The number of cells (the product of the axis lengths)."""
        return int(np.prod(self.shape()))

    def param(self, key):
        """The value of a parameter fixed over the sweep, or None."""
        return self.fixed.get(key)
