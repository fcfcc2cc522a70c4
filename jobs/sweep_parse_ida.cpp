#include <cmath>
#include <optional>

#include "jobs/sweep_parser.h"
#include "solver/common/nearest.h"

namespace skewbridge::jobs {

void SpecParser::ParseIda(const toml::table& table, SweepSpec& spec) const {
  spectra::IdaSpec& ida = spec.ida;
  ida.enabled = true;
  const std::string allowed = "start, step, step_increase, tolerance, max_im, max_runs";
  for (auto&& [key, node] : table) {
    const std::string k(key.str());
    const std::string field = "ida." + k;
    double* target = k == "start"           ? &ida.start
                     : k == "step"          ? &ida.step
                     : k == "step_increase" ? &ida.step_increase
                     : k == "tolerance"     ? &ida.tolerance
                     : k == "max_im"        ? &ida.max_im
                                            : nullptr;
    if (k == "max_runs") {
      const std::optional<std::int64_t> n = node.value<std::int64_t>();
      if (!node.is_integer() || !n || *n < 2 || *n > 200) {
        throw Error(node.source(), field, "must be a whole number of runs from 2 to 200");
      }
      ida.max_runs = static_cast<int>(*n);
      continue;
    }
    if (target == nullptr) {
      throw Error(
          key.source(), field,
          "unknown key; allowed: " + allowed +
              DidYouMean(k, {"start", "step", "step_increase", "tolerance", "max_im", "max_runs"}));
    }
    const std::optional<double> v = node.value<double>();
    const bool zero_ok = k == "step_increase";
    if (!(node.is_number()) || !v || !std::isfinite(*v) || *v < 0.0 || (!zero_ok && *v == 0.0)) {
      throw Error(node.source(), field,
                  zero_ok ? "must be a number >= 0 (g, or m/s for PGV)"
                          : "must be a number > 0 (g, or m/s for PGV)");
    }
    *target = *v;
  }
  if (!(ida.max_im > ida.start)) {
    throw Error(table.source(), "ida.max_im",
                fmt::format("must exceed ida.start ({} <= {})", ida.max_im, ida.start));
  }
}

}  // namespace skewbridge::jobs
