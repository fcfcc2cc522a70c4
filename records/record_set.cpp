#include "records/record_set.h"

#include <toml++/toml.h>
#include <cmath>
#include <set>

#include "solver/common/error.h"

namespace skewbridge::records {
namespace {

long LineOf(const toml::node& node) { return static_cast<long>(node.source().begin.line); }

std::string Where(const std::filesystem::path& manifest, long line) {
  return manifest.string() + ":" + std::to_string(line);
}

std::string RequireString(const toml::table& table, std::string_view key,
                          const std::filesystem::path& manifest, bool required) {
  const toml::node* node = table.get(key);
  if (node == nullptr) {
    if (required) {
      throw InputError::AtField(Where(manifest, LineOf(table)), key, "is required (a string)");
    }
    return {};
  }
  const std::optional<std::string> value = node->value<std::string>();
  if (!value) {
    throw InputError::AtField(Where(manifest, LineOf(*node)), key, "must be a string");
  }
  return *value;
}

std::optional<double> PositiveNumber(const toml::table& table, std::string_view key,
                                     const std::filesystem::path& manifest) {
  const toml::node* node = table.get(key);
  if (node == nullptr) return std::nullopt;
  const std::optional<double> value = node->value<double>();
  if (!value || !std::isfinite(*value) || *value <= 0.0) {
    throw InputError::AtField(Where(manifest, LineOf(*node)), key, "must be a number > 0");
  }
  return value;
}

}  // namespace

RecordSet LoadRecordSet(const std::filesystem::path& manifest) {
  toml::table root;
  try {
    root = toml::parse_file(manifest.string());
  } catch (const toml::parse_error& e) {
    throw InputError::AtLine(manifest.string(), static_cast<long>(e.source().begin.line),
                             std::string(e.description()));
  }
  RecordSet set;
  set.manifest = manifest;
  set.name = manifest.stem().string();
  for (const auto& [key, node] : root) {
    if (key != "name" && key != "record") {
      throw InputError::AtField(Where(manifest, LineOf(node)), key.str(),
                                "unknown key (allowed: name, [[record]])");
    }
  }
  if (const toml::node* name = root.get("name")) {
    if (!name->is_string()) {
      throw InputError::AtField(Where(manifest, LineOf(*name)), "name", "must be a string");
    }
    set.name = *name->value<std::string>();
  }
  const toml::array* records = root.get_as<toml::array>("record");
  if (records == nullptr || records->empty()) {
    throw InputError::AtLine(manifest.string(), 0, "no [[record]] entries");
  }
  const std::filesystem::path base = manifest.parent_path();
  static const std::set<std::string_view> kKeys = {"file",  "label", "component", "scale",
                                                   "units", "dt",    "format",    "channel"};
  for (const toml::node& item : *records) {
    const toml::table* table = item.as_table();
    if (table == nullptr) {
      throw InputError::AtLine(manifest.string(), LineOf(item),
                               "record must be a [[record]] table");
    }
    for (const auto& [key, value] : *table) {
      if (!kKeys.contains(key.str())) {
        throw InputError::AtField(Where(manifest, LineOf(value)), key.str(),
                                  "unknown key (allowed: file, label, component, scale, units, "
                                  "dt, format, channel)");
      }
    }
    RecordEntry entry;
    entry.line = LineOf(*table);
    entry.file = base / RequireString(*table, "file", manifest, true);
    entry.label = RequireString(*table, "label", manifest, false);
    entry.component = RequireString(*table, "component", manifest, false);
    entry.scale = PositiveNumber(*table, "scale", manifest).value_or(1.0);
    if (!(entry.scale <= 1e6)) {  // beyond, accelerations overflow into unit errors
      throw InputError::AtField(Where(manifest, LineOf(*table->get("scale"))), "scale",
                                "must be a number > 0 and at most 1e6");
    }
    entry.options.dt_s = PositiveNumber(*table, "dt", manifest);
    if (const std::string units = RequireString(*table, "units", manifest, false); !units.empty()) {
      entry.options.units = ParseUnits(units);
      if (!entry.options.units) {
        throw InputError::AtField(Where(manifest, LineOf(*table->get("units"))), "units",
                                  "unknown units '" + units + "' (allowed: g, m/s^2, cm/s^2)");
      }
    }
    if (const std::string format = RequireString(*table, "format", manifest, false);
        !format.empty()) {
      const std::optional<Format> parsed = ParseFormat(format);
      if (!parsed) {
        throw InputError::AtField(Where(manifest, LineOf(*table->get("format"))), "format",
                                  "unknown format '" + format +
                                      "' (allowed: auto, at2, esm, itsak, cosmos, csmip, smc, "
                                      "smtk, plain, time-acc)");
      }
      entry.options.format = *parsed;
    }
    if (const toml::node* channel = table->get("channel")) {
      const std::optional<int64_t> value = channel->value<int64_t>();
      if (!value || *value < 1 || *value > 1000) {
        throw InputError::AtField(Where(manifest, LineOf(*channel)), "channel",
                                  "must be an integer >= 1");
      }
      entry.options.channel = static_cast<int>(*value);
    }
    // A record axis names records by label: two records of one label would make the label
    // bind to whichever the lookup meets first.
    const std::string label = RecordLabel(entry);
    for (const RecordEntry& earlier : set.records) {
      if (RecordLabel(earlier) == label) {
        throw InputError::AtField(Where(manifest, entry.line), "label",
                                  "duplicate record label '" + label +
                                      "' (also the record of line " + std::to_string(earlier.line) +
                                      "); give each record its own label");
      }
    }
    set.records.push_back(std::move(entry));
  }
  return set;
}

std::string RecordLabel(const RecordEntry& entry) {
  return entry.label.empty() ? entry.file.filename().string() : entry.label;
}

GroundMotion LoadRecord(const RecordEntry& entry) {
  GroundMotion motion = ReadRecord(entry.file, entry.options);
  for (double& a : motion.acc_mps2) a *= entry.scale;
  if (!entry.component.empty()) motion.component = entry.component;
  return motion;
}

}  // namespace skewbridge::records
