#include "spectra/over_axis.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/common/error.h"

namespace skewbridge::spectra {

AxisSplit SplitAlong(const CellGrid& grid, std::size_t k) {
  SB_DEMAND(k < grid.axes.size(), "no such axis");
  AxisSplit s;
  for (std::size_t a = 0; a < grid.axes.size(); ++a) {
    if (a < k) s.outer *= grid.axes[a].Size();
    if (a > k) s.inner *= grid.axes[a].Size();
  }
  s.size = grid.axes[k].Size();
  return s;
}

CellGrid GridWithout(const CellGrid& grid, std::size_t k) {
  SB_DEMAND(k < grid.axes.size(), "no such axis");
  CellGrid out = grid;
  out.axes.erase(out.axes.begin() + static_cast<std::ptrdiff_t>(k));
  return out;
}

AxisStatistics ReduceOverAxis(const CellGrid& grid, std::size_t k, std::span<const double> values,
                              std::span<const std::uint8_t> usable) {
  const AxisSplit split = SplitAlong(grid, k);
  const Axis& axis = grid.axes[k];
  SB_DEMAND(axis.kind == ParameterKind::kNumber, "a label axis has no coordinate of a maximum");
  SB_DEMAND(values.size() == grid.CellCount() && usable.size() == values.size(),
            "values do not match the grid");
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = split.Reduced();
  AxisStatistics out;
  out.max.assign(n, kNaN);
  out.median.assign(n, kNaN);
  out.coordinate_of_max.assign(n, kNaN);
  out.complete.assign(n, 0);
  std::vector<double> along(split.size);
  for (std::size_t r = 0; r < n; ++r) {
    bool complete = true;
    std::size_t at = 0;
    for (std::size_t i = 0; i < split.size && complete; ++i) {
      const std::size_t c = split.Cell(r, i);
      along[i] = values[c];
      complete = usable[c] != 0 && !std::isnan(values[c]);
      if (complete && along[i] > along[at]) at = i;
    }
    if (!complete) continue;
    out.complete[r] = 1;
    out.max[r] = along[at];
    out.coordinate_of_max[r] = axis.values[at];
    std::sort(along.begin(), along.end());
    const std::size_t m = split.size / 2;
    out.median[r] = split.size % 2 == 1 ? along[m] : (along[m - 1] + along[m]) / 2.0;
  }
  return out;
}

}  // namespace skewbridge::spectra
