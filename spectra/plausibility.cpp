#include "spectra/plausibility.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <string_view>
#include <utility>

#include "solver/model/plausibility.h"
#include "spectra/point.h"

namespace skewbridge::spectra {
namespace {

// The largest value of numeric parameter `key` in the grid and where it is given ("axes.KEY"
// or "fixed.KEY"); nothing when the grid does not give it.
std::optional<std::pair<double, std::string>> Largest(const CellGrid& grid, std::string_view key) {
  if (const Axis* axis = grid.FindAxis(key); axis != nullptr && !axis->values.empty()) {
    return std::pair{*std::max_element(axis->values.begin(), axis->values.end()),
                     "axes." + std::string(key)};
  }
  if (const FixedValue* fixed = grid.FindFixed(key); fixed != nullptr) {
    return std::pair{fixed->value, "fixed." + std::string(key)};
  }
  return std::nullopt;
}

}  // namespace

std::vector<std::string> GridWarnings(const CellGrid& grid) {
  std::vector<std::string> out;
  if (const auto seat = Largest(grid, "seat_over_L");
      seat && seat->first > model::kMaxGapOverSpan) {
    out.push_back(fmt::format(
        "{}: {}: up to {:g}, a seat wider than a tenth of the span: a width in metres typed as a "
        "fraction of L?",
        grid.source, seat->second, seat->first));
  }
  // The pilot bridge's span is fixed; a model file's is judged with the file
  // (ModelFileEvaluator::Warnings).
  if (const auto seat = Largest(grid, "seat_m"); seat && grid.family == "pilot-bridge") {
    if (std::optional<std::string> w = model::WidthWarning(seat->second, "seat", seat->first,
                                                           PilotBridgeDeck().geometry.length_m)) {
      out.push_back(grid.source + ": " + *w);
    }
  }
  if (const auto im = Largest(grid, "im_g")) {
    if (std::optional<std::string> w = model::IntensityWarning(im->second, im->first)) {
      out.push_back(grid.source + ": " + *w);
    }
  }
  return out;
}

}  // namespace skewbridge::spectra
