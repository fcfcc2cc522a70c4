#include <cmath>
#include <optional>

#include "jobs/sweep_parser.h"
#include "solver/common/nearest.h"
#include "spectra/study.h"

namespace skewbridge::jobs {

void SpecParser::ParseRecordsTable(const toml::table& records, SweepSpec& spec) const {
  const bool folder_form = records.contains("folder") || records.contains("pattern");
  for (auto&& [key, node] : records) {
    const std::string_view k = key.str();
    const bool folder_key =
        k == "folder" || k == "pattern" || k == "units" || k == "dt" || k == "pairs";
    const bool im_key = k == "scale_to" || k == "im" || k == "max_scale" || k == "beyond_max_scale";
    if (k != "set" && k != "synthetic" && !im_key && !(folder_form && folder_key)) {
      throw Error(key.source(), "records." + std::string(k),
                  "unknown key; allowed: set, synthetic, or folder and pattern (with units, "
                  "dt, pairs); scale_to or im, max_scale, beyond_max_scale" +
                      DidYouMean(k, {"set", "synthetic", "folder", "pattern", "units", "dt",
                                     "pairs", "scale_to", "im", "max_scale", "beyond_max_scale"}));
    }
  }
  ParseIntensityMeasure(records, spec);
  if (static_cast<int>(records.contains("set")) + static_cast<int>(records.contains("synthetic")) +
          static_cast<int>(folder_form) !=
      1) {
    throw InputError::AtField(source_, "records",
                              "give set = \"FILE\" or synthetic = {count = N, seed = S} or "
                              "folder = \"DIR\" with pattern = \"GLOB\", one of them");
  }
  if (folder_form) {
    ParseRecordFolder(records, spec);
    return;
  }
  if (records.contains("set")) {
    spec.record_set = RequireString(records, "records", "set");
    spec.record_set_path = ExistingFile(records, "records", "set", spec.record_set);
    return;
  }
  const toml::node* node = records.get("synthetic");
  const toml::table* synth = node->as_table();
  if (synth == nullptr) {
    throw Error(node->source(), "records.synthetic", "must be a table {count = N, seed = S}");
  }
  for (auto&& [key, value] : *synth) {
    if (key.str() != "count" && key.str() != "seed") {
      throw Error(key.source(), "records.synthetic." + std::string(key.str()),
                  "unknown key; allowed: count, seed");
    }
  }
  const auto count = (*synth)["count"].value<std::int64_t>();
  if (!count || *count < 1 || *count > 100000) {
    throw Error(node->source(), "records.synthetic.count",
                "must be a whole number of records, 1 to 100000");
  }
  const auto seed = (*synth)["seed"].value<std::int64_t>();
  if (!seed || *seed < 0) {
    throw Error(node->source(), "records.synthetic.seed", "must be a whole number >= 0");
  }
  spec.synthetic_count = static_cast<int>(*count);
  spec.synthetic_seed = static_cast<std::uint64_t>(*seed);
}

void SpecParser::ParseIntensityMeasure(const toml::table& records, SweepSpec& spec) const {
  if (records.contains("scale_to") && records.contains("im")) {
    throw Error(records.get("im")->source(), "records.im",
                "give scale_to (records scaled to the im axis) or im (records unscaled), "
                "not both");
  }
  const bool scale = records.contains("scale_to");
  const std::string name = scale ? "records.scale_to" : "records.im";
  if (const toml::node* node = records.get("max_scale")) {
    if (!scale) {
      throw Error(node->source(), "records.max_scale",
                  "needs records.scale_to (only scaled records have a scale factor)");
    }
    const std::optional<double> v = node->value<double>();
    if (!v || !std::isfinite(*v) || !(*v > 0.0)) {
      throw Error(node->source(), "records.max_scale", "must be a number > 0");
    }
    spec.im.max_scale = *v;
  }
  if (const toml::node* node = records.get("beyond_max_scale")) {
    const std::optional<std::string> rule = node->value<std::string>();
    if (!rule || (*rule != "keep" && *rule != "exclude")) {
      throw Error(node->source(), "records.beyond_max_scale",
                  "must be \"keep\" (the cells beyond max_scale enter the fits) or \"exclude\" "
                  "(the fits leave them out)");
    }
    if (!records.contains("max_scale")) {
      throw Error(node->source(), "records.beyond_max_scale", "needs records.max_scale");
    }
    spec.im.exclude_beyond_max_scale = *rule == "exclude";
  }
  const toml::node* node = records.get(scale ? "scale_to" : "im");
  if (node == nullptr) return;
  const toml::table* table = node->as_table();
  if (table == nullptr) {
    throw Error(node->source(), name,
                "must be a table {measure = \"Sa\", period = \"T1\", xi = 0.05}");
  }
  for (auto&& [key, value] : *table) {
    const std::string_view k = key.str();
    if (k != "measure" && k != "period" && k != "xi") {
      throw Error(
          key.source(), name + "." + std::string(k),
          "unknown key; allowed: measure, period, xi" + DidYouMean(k, {"measure", "period", "xi"}));
    }
  }
  spec.im.scale = scale;
  const toml::node* measure = table->get("measure");
  const std::optional<std::string> m = measure ? measure->value<std::string>() : std::nullopt;
  if (!m) {
    throw Error(measure ? measure->source() : node->source(), name + ".measure",
                "must be one of \"Sa\", \"AvgSa\", \"PGA\", \"PGV\" (single records) or "
                "\"RotD50\", \"RotD100\", \"GM\", \"AvgSa_RotD50\" (record pairs)");
  }
  spec.im.measure = *m;
  if (!spec.im.Spectral() && *m != "PGA" && *m != "PGV") {
    throw Error(measure->source(), name + ".measure",
                "unknown measure '" + *m +
                    "'; allowed: Sa, AvgSa, PGA, PGV (single records), RotD50, RotD100, GM, "
                    "AvgSa_RotD50 (record pairs)" +
                    DidYouMean(*m, {"Sa", "AvgSa", "PGA", "PGV", "RotD50", "RotD100", "GM",
                                    "AvgSa_RotD50"}));
  }
  const bool spectral = spec.im.Spectral();
  const toml::node* period = table->get("period");
  const toml::node* xi = table->get("xi");
  if (!spectral) {
    if (period != nullptr || xi != nullptr) {
      throw Error((period ? period : xi)->source(), name + (period ? ".period" : ".xi"),
                  "only for Sa, AvgSa, RotD50, RotD100, GM and AvgSa_RotD50 (" + *m +
                      " has no period or damping)");
    }
    return;
  }
  if (period == nullptr) {
    if (*m != "AvgSa" && *m != "AvgSa_RotD50") {
      throw Error(
          node->source(), name + ".period",
          "missing: " + *m + " needs a period in s or \"T1\" (the model's fundamental period)");
    }
    spec.im.at_t1 = true;  // AvgSa is conditioned on T1 unless told otherwise
  } else if (const std::optional<std::string> text = period->value<std::string>()) {
    if (*text != "T1") {
      throw Error(period->source(), name + ".period",
                  "'" + *text + "' is not a period; give a number of seconds > 0 or \"T1\"");
    }
    spec.im.at_t1 = true;
  } else {
    const std::optional<double> v = period->value<double>();
    if (!v || !std::isfinite(*v) || !(*v > 0.0)) {
      throw Error(period->source(), name + ".period",
                  "must be a period > 0 s or \"T1\" (the model's fundamental period)");
    }
    spec.im.period_s = *v;
  }
  if (xi != nullptr) {
    const std::optional<double> v = xi->value<double>();
    if (!v || !(*v >= 0.0 && *v < 1.0)) {
      throw Error(xi->source(), name + ".xi", "must be a damping ratio in [0, 1)");
    }
    spec.im.xi = *v;
  }
}

void SpecParser::ParseRecordFolder(const toml::table& records, SweepSpec& spec) const {
  if (!records.contains("folder")) {
    throw InputError::AtField(source_, "records.folder",
                              "missing: pattern needs folder = \"DIR\" (relative to the spec)");
  }
  spec.record_folder = RequireString(records, "records", "folder");
  if (!records.contains("pattern")) {
    throw Error(records.get("folder")->source(), "records.pattern",
                "is required with folder (a file-name glob, e.g. \"*.AT2\")");
  }
  spec.record_pattern = RequireString(records, "records", "pattern");
  spec.record_folder_path = base_dir_ / spec.record_folder;
  spec.record_folder_at = Where(source_, records.get("folder")->source());
  spec.record_pattern_at = Where(source_, records.get("pattern")->source());
  if (const toml::node* node = records.get("units")) {
    const auto units = node->value<std::string>();
    if (!units || !spectra::KnownRecordUnits(*units)) {
      throw Error(node->source(), "records.units",
                  "must be one of g, m/s^2, cm/s^2 (the units of files that state none)");
    }
    spec.record_units = *units;
  }
  if (const toml::node* node = records.get("dt")) {
    const auto dt = node->value<double>();
    if (!node->is_number() || !dt || !std::isfinite(*dt) || *dt <= 0.0) {
      throw Error(node->source(), "records.dt",
                  "must be a number > 0 (s; the step of files that state none)");
    }
    spec.record_dt_s = *dt;
  }
  if (const toml::node* node = records.get("pairs")) {
    spec.record_pairs_at = Where(source_, node->source());
    if (const std::optional<bool> flag = node->value_exact<bool>()) {
      spec.record_pairs_by_name = *flag;
    } else if (const std::optional<std::string> table = node->value_exact<std::string>();
               table && !table->empty()) {
      spec.record_pairs_table = *table;
    } else {
      throw Error(node->source(), "records.pairs",
                  "must be true (pairs by file name) or the name of a CSV table of the folder "
                  "(h1_file, h2_file, pair)");
    }
  }
  spectra::LoadSpecRecordSet(spec);
}

std::vector<std::string> SpecParser::AllRecordLabels(const SweepSpec& spec,
                                                     const std::string& field,
                                                     const toml::source_region& where) const {
  std::vector<std::string> labels;
  if (spec.synthetic_count > 0) return spectra::AllRecordLabels(spec);
  if (spec.record_set_path.empty() && spec.record_folder.empty()) {
    throw Error(where, field,
                "\"*\" (every record) needs [records] set = \"FILE\", folder and pattern, or "
                "synthetic = {...}");
  }
  return spectra::AllRecordLabels(spec);
}

}  // namespace skewbridge::jobs
