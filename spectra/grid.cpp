#include "spectra/grid.h"

#include <algorithm>
#include <limits>
#include <optional>

#include "solver/common/error.h"

namespace skewbridge::spectra {

std::vector<std::size_t> CellGrid::Shape() const {
  std::vector<std::size_t> shape;
  for (const Axis& axis : axes) {
    shape.push_back(axis.Size());
  }
  return shape;
}

std::uint64_t CellGrid::CellCount() const {
  // Saturates instead of wrapping, so that a product beyond 2^64 is still refused as too large.
  std::uint64_t n = 1;
  for (const Axis& axis : axes) {
    const std::uint64_t size = axis.Size();
    if (size != 0 && n > std::numeric_limits<std::uint64_t>::max() / size) {
      return std::numeric_limits<std::uint64_t>::max();
    }
    n *= size;
  }
  return n;
}

std::vector<std::size_t> CellGrid::AxisIndex(std::uint64_t cell) const {
  SB_DEMAND(cell < CellCount(), "cell index out of range");
  std::vector<std::size_t> index(axes.size());
  for (std::size_t k = axes.size(); k-- > 0;) {
    index[k] = static_cast<std::size_t>(cell % axes[k].Size());
    cell /= axes[k].Size();
  }
  return index;
}

const Axis* CellGrid::FindAxis(std::string_view key) const {
  for (const Axis& axis : axes) {
    if (axis.key == key) {
      return &axis;
    }
  }
  return nullptr;
}

const FixedValue* CellGrid::FindFixed(std::string_view key) const {
  for (const FixedValue& f : fixed) {
    if (f.key == key) {
      return &f;
    }
  }
  return nullptr;
}

double NumberOf(const CellGrid& grid, std::span<const std::size_t> index, std::string_view key,
                double fallback, bool* given) {
  for (std::size_t k = 0; k < grid.axes.size(); ++k) {
    if (grid.axes[k].key == key) {
      if (given != nullptr) *given = true;
      return grid.axes[k].values[index[k]];
    }
  }
  if (const FixedValue* fixed = grid.FindFixed(key)) {
    if (given != nullptr) *given = true;
    return fixed->value;
  }
  if (given != nullptr) *given = false;
  return fallback;
}

std::string LabelOf(const CellGrid& grid, std::span<const std::size_t> index, std::string_view key,
                    std::string fallback) {
  for (std::size_t k = 0; k < grid.axes.size(); ++k) {
    if (grid.axes[k].key == key) return grid.axes[k].labels[index[k]];
  }
  if (const FixedValue* fixed = grid.FindFixed(key)) return fixed->label;
  return fallback;
}

namespace {

model::Method ParseMethodLabel(const CellGrid& grid, const std::string& label) {
  if (const std::optional<model::Method> method = model::ParseMethod(label)) return *method;
  throw InputError::AtField(grid.source, "method",
                            "must be event-driven or time-stepping (got \"" + label + "\")");
}

}  // namespace

model::Method MethodOf(const CellGrid& grid, std::span<const std::size_t> index,
                       model::Method fallback) {
  const std::string label = LabelOf(grid, index, "method");
  return label.empty() ? fallback : ParseMethodLabel(grid, label);
}

std::vector<model::Method> MethodsOf(const CellGrid& grid, model::Method fallback) {
  std::vector<std::string> labels;
  if (const Axis* axis = grid.FindAxis("method")) {
    labels = axis->labels;
  } else if (const FixedValue* fixed = grid.FindFixed("method")) {
    labels = {fixed->label};
  }
  std::vector<model::Method> methods;
  for (const std::string& label : labels) {
    const model::Method method = ParseMethodLabel(grid, label);
    if (std::find(methods.begin(), methods.end(), method) == methods.end()) {
      methods.push_back(method);
    }
  }
  if (methods.empty()) methods.push_back(fallback);
  return methods;
}

bool Mentions(const CellGrid& grid, std::string_view key) {
  return grid.FindAxis(key) != nullptr || grid.FindFixed(key) != nullptr;
}

std::string KeyWhere(const CellGrid& grid, std::string_view key) {
  const std::string field = (grid.FindAxis(key) != nullptr ? "axes." : "fixed.") + std::string(key);
  const auto at = grid.key_at.find(field);
  return (at != grid.key_at.end() ? at->second : grid.source) + ": " + field;
}

bool MentionsSeat(const CellGrid& grid) {
  return Mentions(grid, "seat_over_L") || Mentions(grid, "seat_m");
}

double SeatWidthOf(const CellGrid& grid, std::span<const std::size_t> index, double length_m,
                   bool* given) {
  bool relative = false, absolute = false;
  const double seat_over_L = NumberOf(grid, index, "seat_over_L", 0.0, &relative);
  if (relative) {
    if (given != nullptr) *given = true;
    return seat_over_L * length_m;
  }
  const double seat_m = NumberOf(grid, index, "seat_m", 0.0, &absolute);
  if (given != nullptr) *given = absolute;
  return seat_m;
}

}  // namespace skewbridge::spectra
