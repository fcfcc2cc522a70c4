#include <cmath>
#include <optional>

#include "jobs/sweep_parser.h"

namespace skewbridge::jobs {

void SpecParser::ParseStudyTable(const toml::table& study, SweepSpec& spec) const {
  for (auto&& [key, node] : study) {
    if (key.str() != "bands") {
      throw Error(key.source(), "study." + std::string(key.str()), "unknown key; allowed: bands");
    }
  }
  const toml::node* node = study.get("bands");
  if (node == nullptr) return;
  const toml::array* list = node->as_array();
  const std::string problem =
      "must be a list of increasing, finite, positive w0x/w_g edges, e.g. [0.5, 1.0, 2.0]";
  if (list == nullptr || list->empty()) throw Error(node->source(), "study.bands", problem);
  for (const toml::node& item : *list) {
    const std::optional<double> edge = item.value<double>();
    if (!edge || !std::isfinite(*edge) || *edge <= 0.0 ||
        (!spec.study_bands.empty() && *edge <= spec.study_bands.back())) {
      throw Error(item.source(), "study.bands", problem);
    }
    spec.study_bands.push_back(*edge);
  }
}

}  // namespace skewbridge::jobs
