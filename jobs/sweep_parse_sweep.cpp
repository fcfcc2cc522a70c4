#include <algorithm>
#include <cctype>

#include "jobs/sweep_parser.h"
#include "solver/common/nearest.h"

namespace skewbridge::jobs {

void SpecParser::ParseSweepTable(const toml::table& sweep, SweepSpec& spec) const {
  for (auto&& [key, node] : sweep) {
    const std::string_view k = key.str();
    if (k != "name" && k != "family" && k != "model" && k != "responses" && k != "description") {
      throw Error(key.source(), "sweep." + std::string(k),
                  "unknown key; allowed: name, family, model, responses, description" +
                      DidYouMean(k, {"name", "family", "model", "responses", "description"}));
    }
  }
  spec.name = RequireString(sweep, "sweep", "name");
  const bool name_ok = std::all_of(spec.name.begin(), spec.name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
  if (!name_ok || spec.name == "." || spec.name == "..") {
    throw Error(sweep.get("name")->source(), "sweep.name",
                "use letters, digits, '_', '-' and '.' only (it names an HDF5 group)");
  }
  spec.family = RequireString(sweep, "sweep", "family");
  const std::span<const std::string_view> families = KnownFamilies();
  if (std::find(families.begin(), families.end(), spec.family) == families.end()) {
    throw Error(sweep.get("family")->source(), "sweep.family",
                "unknown family '" + spec.family +
                    "'; allowed: subsystem, pilot-bridge, model-file, multi-span");
  }
  if (spec.family == "model-file") {
    spec.model_file = RequireString(sweep, "sweep", "model");
    spec.model_path = ExistingFile(sweep, "sweep", "model", spec.model_file);
  } else if (sweep.contains("model")) {
    throw Error(sweep.get("model")->source(), "sweep.model",
                "only allowed with family = \"model-file\"");
  }
  if (const toml::node* node = sweep.get("description"); node && !node->is_string()) {
    throw Error(node->source(), "sweep.description", "must be a string");
  }
  if (const toml::node* node = sweep.get("responses")) {
    const toml::array* list = node->as_array();
    if (list == nullptr || list->empty()) {
      throw Error(node->source(), "sweep.responses", "must be a non-empty list of response names");
    }
    for (const toml::node& item : *list) {
      const auto name = item.value<std::string>();
      if (!item.is_string() || !name || name->empty()) {
        throw Error(item.source(), "sweep.responses", "entries must be non-empty strings");
      }
      if (std::find(spec.responses.begin(), spec.responses.end(), *name) != spec.responses.end()) {
        throw Error(item.source(), "sweep.responses", "duplicate response '" + *name + "'");
      }
      spec.responses.push_back(*name);
    }
  }
}

}  // namespace skewbridge::jobs
