#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "jobs/sweep_parser.h"
#include "solver/common/nearest.h"
#include "spectra/limit_states.h"

namespace skewbridge::jobs {

double SpecParser::Threshold(const toml::node& node, const std::string& field,
                             std::string_view unit) const {
  const std::optional<double> v = node.value<double>();
  if (!node.is_number() || !v || !std::isfinite(*v) || *v < 0.0) {
    throw Error(node.source(), field, "must be a number >= 0 (" + std::string(unit) + ")");
  }
  return *v;
}

double SpecParser::Above(const toml::node& node, const std::string& field,
                         std::string_view key) const {
  const toml::table* table = node.as_table();
  if (table == nullptr || table->size() != 1 || !table->contains(key)) {
    throw Error(node.source(), field,
                "must be a table {" + std::string(key) + " = VALUE} (the value it must exceed)");
  }
  return Threshold(*table->get(key), field + "." + std::string(key), key.substr(6));
}

void SpecParser::ParseLimitStates(const toml::table& limits, SweepSpec& spec) const {
  using spectra::LimitState;
  using spectra::LimitStateKind;
  constexpr std::array<std::string_view, 6> kKeys{"unseating", "rotation",      "seat_displacement",
                                                  "residual",  "joint_closing", "response"};
  const std::string allowed =
      "unknown key; allowed: unseating, rotation, seat_displacement, residual, "
      "joint_closing, response";
  for (std::string_view k : kKeys) {
    const toml::node* node = limits.get(k);
    if (node == nullptr) continue;
    const std::string field = "limit_states." + std::string(k);
    LimitState ls;
    ls.name = std::string(k);
    ls.at = Where(source_, node->source());
    if (k == "unseating" || k == "joint_closing") {
      ls.kind = k == "unseating" ? LimitStateKind::kUnseating : LimitStateKind::kJointClosing;
      const std::optional<bool> flag = node->value<bool>();
      if (node->is_boolean() && flag && *flag) {
        spec.limit_states.push_back(std::move(ls));
        continue;
      }
      const toml::table* table = node->as_table();
      if (k == "joint_closing" || table == nullptr || table->size() != 1 ||
          !table->contains("seat_m")) {
        throw Error(node->source(), field,
                    k == "joint_closing"
                        ? "must be true (any impact exceeds it)"
                        : "must be true (the sweep's seat widths) or {seat_m = WIDTH} or "
                          "{seat_m = [WIDTH, ...]} (m, one per support line)");
      }
      const toml::node* seat = table->get("seat_m");
      if (const toml::array* list = seat->as_array()) {
        if (list->empty()) {
          throw Error(seat->source(), field + ".seat_m", "must not be empty");
        }
        for (const toml::node& item : *list) {
          ls.seat_m.push_back(Threshold(item, field + ".seat_m", "m"));
        }
      } else {
        ls.seat_m.push_back(Threshold(*seat, field + ".seat_m", "m"));
      }
    } else if (k == "rotation") {
      ls.kind = LimitStateKind::kRotation;
      ls.threshold = Above(*node, field, "above_rad");
    } else if (k == "seat_displacement" || k == "residual") {
      ls.kind = k == "residual" ? LimitStateKind::kResidual : LimitStateKind::kSeatDisplacement;
      ls.threshold = Above(*node, field, "above_m");
    } else {
      const toml::table* table = node->as_table();
      if (table == nullptr || table->empty()) {
        throw Error(node->source(), field,
                    "must be a table {RESPONSE = THRESHOLD, ...} (exceeded above it)");
      }
      std::vector<std::string> names;
      for (auto&& [key, value] : *table) names.emplace_back(key.str());
      std::sort(names.begin(), names.end());
      for (const std::string& name : names) {
        const toml::node* value = table->get(name);
        LimitState r;
        r.kind = LimitStateKind::kResponse;
        r.name = r.response = name;
        r.at = Where(source_, value->source());
        r.threshold = value->value<double>().value_or(0.0);
        if (!value->is_number() || !std::isfinite(r.threshold)) {
          throw Error(value->source(), field + "." + name,
                      "must be a finite number (the value the response must exceed)");
        }
        spec.limit_states.push_back(std::move(r));
      }
      continue;
    }
    spec.limit_states.push_back(std::move(ls));
  }
  for (auto&& [key, node] : limits) {
    if (std::find(kKeys.begin(), kKeys.end(), key.str()) == kKeys.end()) {
      throw Error(key.source(), "limit_states." + std::string(key.str()),
                  allowed + DidYouMean(key.str(), {kKeys.begin(), kKeys.end()}));
    }
  }
}

}  // namespace skewbridge::jobs
