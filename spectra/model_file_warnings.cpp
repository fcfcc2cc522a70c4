// The model-file evaluator's warnings about the bridge and its note about the scale factors.
#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "solver/model/plausibility.h"
#include "spectra/model_file_evaluator.h"

namespace skewbridge::spectra {

std::vector<std::string> ModelFileEvaluator::BridgeWarnings() const {
  std::vector<std::string> out;
  const std::string& src = spec_.source;
  auto add = [&out](const std::string& where, std::optional<std::string> warning) {
    if (warning) out.push_back(where + ": " + *warning);
  };
  double shortest_m = std::numeric_limits<double>::infinity();
  for (const model::Body& b : file_.model.bodies()) {
    shortest_m = std::min(shortest_m, b.geometry.length_m);
  }
  // The file's masses, gaps and period; a sweep axis that replaces a gap or the stiffness is
  // judged by its own values (the period of every cell, below).
  for (const std::string& w : model::PlausibilityWarnings(file_)) {
    const bool gap = w.find(".gap_m") != std::string::npos;
    const bool period = w.find("fundamental period") != std::string::npos;
    if (period || (gap && (Mentions(spec_, "gap_m") || Mentions(spec_, "Pi_delta")))) continue;
    out.push_back(w);
  }
  if (const Axis* axis = spec_.FindAxis("gap_m"); axis != nullptr && !axis->values.empty()) {
    add(src, model::WidthWarning("axes.gap_m", "gap",
                                 *std::max_element(axis->values.begin(), axis->values.end()),
                                 shortest_m));
  } else if (const FixedValue* fixed = spec_.FindFixed("gap_m")) {
    add(src, model::WidthWarning("fixed.gap_m", "gap", fixed->value, shortest_m));
  }
  if (const Axis* axis = spec_.FindAxis("seat_m"); axis != nullptr && !axis->values.empty()) {
    add(src, model::WidthWarning("axes.seat_m", "seat",
                                 *std::max_element(axis->values.begin(), axis->values.end()),
                                 shortest_m));
  } else if (const FixedValue* fixed = spec_.FindFixed("seat_m")) {
    add(src, model::WidthWarning("fixed.seat_m", "seat", fixed->value, shortest_m));
  }
  for (const LimitState& ls : spec_.limit_states) {
    if (ls.seat_m.empty()) continue;
    add(ls.at,
        model::WidthWarning("limit_states." + ls.name + ".seat_m", "seat",
                            *std::max_element(ls.seat_m.begin(), ls.seat_m.end()), shortest_m));
  }
  return out;
}

std::vector<std::string> ModelFileEvaluator::Notes() const {
  if (!spec_.im.scale || !(spec_.im.max_scale > 0.0)) return {};
  double largest = 0.0;
  for (const double f : scale_of_cell_) largest = std::max(largest, f);
  return {
      fmt::format("{} of {} cells scaled beyond max_scale = {} (largest factor {:.4g}); "
                  "flagged in the response scaled_too_far",
                  scaled_too_far_, scale_of_cell_.size(), spec_.im.max_scale, largest)};
}

}  // namespace skewbridge::spectra
