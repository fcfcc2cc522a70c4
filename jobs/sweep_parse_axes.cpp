#include <algorithm>
#include <cmath>

#include "jobs/sweep_parser.h"
#include "solver/common/nearest.h"

namespace skewbridge::jobs {
namespace {

// "a number >= MIN and <= MAX": the range of a numeric parameter, for messages.
std::string AllowedRange(const ParameterInfo& p) {
  std::string lo = p.min_inclusive ? ">= " + Fmt(p.min) : "> " + Fmt(p.min);
  if (std::isinf(p.max)) {
    return "a number " + lo;
  }
  std::string hi = p.max_inclusive ? "<= " + Fmt(p.max) : "< " + Fmt(p.max);
  return "a number " + lo + " and " + hi;
}

}  // namespace

std::string SpecParser::NearestParameter(const std::string& word) {
  std::vector<std::string> names;
  std::vector<const ParameterInfo*> owners;
  for (const ParameterInfo& p : KnownParameters()) {
    names.emplace_back(p.key);
    owners.push_back(&p);
    if (p.symbol != p.key) {
      names.emplace_back(p.symbol);
      owners.push_back(&p);
    }
  }
  names.emplace_back("skew_deg");  // [deck] skew_deg of a model file
  owners.push_back(FindParameter("a_deg"));
  const std::vector<std::string> nearest = NearestNames(word, names, 1, true);
  if (nearest.empty()) {
    return "";
  }
  const auto at = std::find(names.begin(), names.end(), nearest.front()) - names.begin();
  const ParameterInfo& p = *owners[static_cast<std::size_t>(at)];
  return fmt::format("; did you mean `{}` ({})?", p.key, p.description);
}

const ParameterInfo& SpecParser::Known(const std::string& field, const std::string& key,
                                       const toml::source_region& where) const {
  const ParameterInfo* info = FindParameter(key);
  if (info == nullptr) {
    std::string allowed;
    for (const ParameterInfo& p : KnownParameters()) {
      allowed += (allowed.empty() ? "" : ", ") + std::string(p.key);
    }
    throw Error(where, field, "unknown parameter; allowed: " + allowed + NearestParameter(key));
  }
  return *info;
}

void SpecParser::CheckNumber(const ParameterInfo& p, double v, const std::string& field,
                             const toml::source_region& where) const {
  const bool low_ok = p.min_inclusive ? v >= p.min : v > p.min;
  const bool high_ok = p.max_inclusive ? v <= p.max : v < p.max;
  if (!std::isfinite(v) || !low_ok || !high_ok) {
    throw Error(where, field, "must be " + AllowedRange(p) + " (got " + Fmt(v) + ")");
  }
  if (p.integer && v != std::floor(v)) {
    throw Error(where, field, "must be a whole number (got " + Fmt(v) + ")");
  }
}

void SpecParser::CheckLabel(const ParameterInfo& p, const std::string& v, const std::string& field,
                            const toml::source_region& where) const {
  if (v.empty()) {
    throw Error(where, field, "labels must be non-empty strings");
  }
  if (p.choices.empty()) {
    return;
  }
  std::string_view rest = p.choices;
  while (!rest.empty()) {
    const std::size_t bar = rest.find('|');
    if (rest.substr(0, bar) == v) {
      return;
    }
    rest = bar == std::string_view::npos ? std::string_view() : rest.substr(bar + 1);
  }
  throw Error(where, field, "must be one of " + std::string(p.choices) + " (got '" + v + "')");
}

double SpecParser::Number(const toml::node& node, const std::string& field) const {
  const auto v = node.value<double>();
  if (!node.is_number() || !v) {
    throw Error(node.source(), field, "must be a number");
  }
  return *v;
}

Axis SpecParser::ParseAxis(const std::string& key, const toml::source_region& key_where,
                           const toml::node& node, const SweepSpec& spec) const {
  const std::string field = "axes." + key;
  const ParameterInfo& p = Known(field, key, key_where);
  Axis axis;
  axis.key = std::string(p.key);
  axis.kind = p.kind;
  if (axis.key == "record" && node.is_string()) {
    if (node.value<std::string>() != "*") {
      throw Error(node.source(), field,
                  "must be a list of record labels or \"*\" (every record of the set)");
    }
    axis.spacing = "all";
    axis.labels = AllRecordLabels(spec, field, node.source());
    return axis;
  }
  if (const toml::array* list = node.as_array()) {
    if (list->empty()) {
      throw Error(node.source(), field, "empty axis: give at least one value");
    }
    axis.spacing = "list";
    for (const toml::node& item : *list) {
      if (p.kind == ParameterKind::kLabel) {
        const auto label = item.value<std::string>();
        if (!item.is_string() || !label) {
          throw Error(item.source(), field, "entries must be strings");
        }
        CheckLabel(p, *label, field, item.source());
        if (axis.key == "record" && *label == "*") {
          throw Error(item.source(), field,
                      "\"*\" stands alone: record = \"*\" takes every record of the set");
        }
        axis.labels.push_back(*label);
      } else {
        const double v = Number(item, field);
        CheckNumber(p, v, field, item.source());
        axis.values.push_back(v);
      }
    }
  } else if (const toml::table* gen = node.as_table()) {
    if (p.kind == ParameterKind::kLabel) {
      throw Error(node.source(), field, "a label axis must be a list of strings");
    }
    if (gen->size() != 1 || !(gen->contains("linspace") || gen->contains("logspace"))) {
      throw Error(node.source(), field,
                  "must be a list, {linspace = [a, b, n]} or {logspace = [a, b, n]}");
    }
    axis.spacing = gen->contains("linspace") ? "linspace" : "logspace";
    const toml::node& args_node = *gen->get(axis.spacing);
    const toml::array* args = args_node.as_array();
    if (args == nullptr || args->size() != 3) {
      throw Error(args_node.source(), field + "." + axis.spacing, "must be [a, b, n]");
    }
    const double a = Number(*args->get(0), field + "." + axis.spacing);
    const double b = Number(*args->get(1), field + "." + axis.spacing);
    const toml::node& n_node = *args->get(2);
    const auto n = n_node.value<std::int64_t>();
    if (!n_node.is_integer() || !n || *n < 1) {
      throw Error(n_node.source(), field + "." + axis.spacing, "n must be a whole number >= 1");
    }
    if (*n > 100'000'000) {
      throw Error(n_node.source(), field + "." + axis.spacing, "n must be <= 100000000");
    }
    if (axis.spacing == "logspace" && !(a > 0 && b > 0)) {
      throw Error(args_node.source(), field + ".logspace",
                  "a and b are values (not decades) and must be > 0");
    }
    axis.values = axis.spacing == "linspace" ? Linspace(a, b, static_cast<std::size_t>(*n))
                                             : Logspace(a, b, static_cast<std::size_t>(*n));
    for (double v : axis.values) {
      CheckNumber(p, v, field, node.source());
    }
  } else {
    throw Error(node.source(), field,
                "must be a list, {linspace = [a, b, n]} or {logspace = [a, b, n]}");
  }
  std::vector<double> sorted = axis.values;
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::string> sorted_labels = axis.labels;
  std::sort(sorted_labels.begin(), sorted_labels.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end() ||
      std::adjacent_find(sorted_labels.begin(), sorted_labels.end()) != sorted_labels.end()) {
    throw Error(node.source(), field, "duplicate coordinate (each value must appear once)");
  }
  return axis;
}

FixedValue SpecParser::ParseFixed(const std::string& key, const toml::source_region& key_where,
                                  const toml::node& node, const SweepSpec& spec) const {
  const std::string field = "fixed." + key;
  const ParameterInfo& p = Known(field, key, key_where);
  if (spec.FindAxis(p.key) != nullptr) {
    throw Error(key_where, field, "is also an axis; give it in [axes] or [fixed], not both");
  }
  FixedValue fixed;
  fixed.key = std::string(p.key);
  fixed.kind = p.kind;
  if (p.kind == ParameterKind::kLabel) {
    const auto label = node.value<std::string>();
    if (!node.is_string() || !label) {
      throw Error(node.source(), field, "must be a string");
    }
    CheckLabel(p, *label, field, node.source());
    if (fixed.key == "record" && *label == "*") {
      throw Error(node.source(), field,
                  "a fixed record is one label; [axes] record = \"*\" takes every record");
    }
    fixed.label = *label;
  } else {
    fixed.value = Number(node, field);
    CheckNumber(p, fixed.value, field, node.source());
  }
  return fixed;
}

std::vector<double> Linspace(double a, double b, std::size_t n) {
  SB_DEMAND(n >= 1, "linspace needs n >= 1");
  std::vector<double> v(n, a);
  for (std::size_t i = 1; i < n; ++i) {
    v[i] = i + 1 == n ? b : a + (b - a) * static_cast<double>(i) / static_cast<double>(n - 1);
  }
  return v;
}

std::vector<double> Logspace(double a, double b, std::size_t n) {
  SB_DEMAND(n >= 1 && a > 0 && b > 0, "logspace needs n >= 1 and a, b > 0");
  std::vector<double> v(n, a);
  const double la = std::log(a);
  const double lb = std::log(b);
  for (std::size_t i = 1; i < n; ++i) {
    v[i] = i + 1 == n
               ? b
               : std::exp(la + (lb - la) * static_cast<double>(i) / static_cast<double>(n - 1));
  }
  return v;
}

}  // namespace skewbridge::jobs
