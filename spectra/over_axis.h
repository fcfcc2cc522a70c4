#pragma once
/// @file
/// Statistics of per-cell values over one axis of a grid (the incidence angle: the largest
/// response over the angles, its median and the angle of the largest; docs/hdf5-layout.md,
/// over_incidence/), and the grid without that axis, over which they are indexed.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "spectra/grid.h"

namespace skewbridge::spectra {

/// How the row-major cells of a grid fall along one of its axes: cell (o, i, j) with o over the
/// axes before it, i along it and j over the axes after it is o * size * inner + i * inner + j;
/// its reduced cell (the grid without the axis) is o * inner + j.
struct AxisSplit {
  std::size_t outer = 1;  ///< product of the sizes of the axes before it
  std::size_t size = 1;   ///< its size
  std::size_t inner = 1;  ///< product of the sizes of the axes after it
  /// Cells of the grid without the axis.
  std::size_t Reduced() const { return outer * inner; }
  /// The grid's cell at reduced cell `r` and coordinate index `i` of the axis.
  std::size_t Cell(std::size_t r, std::size_t i) const {
    return ((r / inner) * size + i) * inner + r % inner;
  }
};

/// The split of `grid`'s cells along its axis number `k`.
/// @pre k < grid.axes.size()
AxisSplit SplitAlong(const CellGrid& grid, std::size_t k);

/// `grid` without its axis number `k` (the cells of AxisSplit::Reduced, same order).
/// @pre k < grid.axes.size()
CellGrid GridWithout(const CellGrid& grid, std::size_t k);

/// Per reduced cell: the largest value over the axis, the median (numpy's: the mean of the two
/// middle values for an even count) and the axis coordinate of the largest (the first on ties).
struct AxisStatistics {
  std::vector<double> max, median, coordinate_of_max;
  std::vector<std::uint8_t> complete;  ///< 1 when every cell along the axis is usable
};

/// The statistics of `values` over axis `k` of `grid`; NaN (and complete = 0) in a reduced cell
/// where some cell along the axis is not usable or its value is NaN.
/// @pre k < grid.axes.size(), the axis numeric, values and usable of grid.CellCount() entries
AxisStatistics ReduceOverAxis(const CellGrid& grid, std::size_t k, std::span<const double> values,
                              std::span<const std::uint8_t> usable);

}  // namespace skewbridge::spectra
