#include "jobs/sweep_spec.h"

#include <fmt/format.h>

#include <toml++/toml.h>
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "jobs/file_checksum.h"
#include "solver/common/error.h"
#include "solver/common/file_kind.h"
#include "solver/common/nearest.h"
#include "spectra/inputs.h"
#include "spectra/limit_states.h"
#include "spectra/study.h"

namespace skewbridge::jobs {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The one table of parameter names. The spectra mapping extends it here (and in
// docs/sweep-format.md); the order is the canonical axis order of every cube.
// clang-format off
constexpr std::array<ParameterInfo, 24> kParameters{{
  {"record", "record", "", "ground-motion record, by its label in the [records] set",
   ParameterKind::kLabel, 0, true, 0, true, false, ""},
  {"pulse", "pulse", "", "one cycle of a_g cos(w_g t) or a_g sin(w_g t) [docs/theory.md §5]",
   ParameterKind::kLabel, 0, true, 0, true, false, "cosine|sine"},
  {"spans", "spans", "1", "number of deck spans", ParameterKind::kNumber, 1, true, 64, true,
   true, ""},
  {"a_g_g", "a_g", "g", "pulse amplitude a_g (cancels out of the dimensionless responses)",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"w_g", "w_g", "rad/s", "pulse frequency w_g (family model-file; or T_g)",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"T_g", "T_g", "s", "pulse period T_g = 2 pi / w_g (family model-file; or w_g)",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"scale", "scale", "1", "factor on the excitation's accelerations (family model-file)",
   ParameterKind::kNumber, 0, false, 1e6, true, false, ""},
  {"im_g", "IM", "g", "intensity the records are scaled to: Sa, AvgSa or PGA in g ([records] scale_to)",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"im_mps", "IM_v", "m/s", "intensity the records are scaled to: PGV in m/s ([records] scale_to)",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"a_deg", "a", "deg", "skew angle a", ParameterKind::kNumber, 0, true, 90, false, false, ""},
  {"eta0", "eta0", "1", "skew ratio eta0 = sin 2a / (2 W/L)", ParameterKind::kNumber, 0, false,
   kInf, false, false, ""},
  {"W_over_L", "W/L", "1", "deck width over length", ParameterKind::kNumber, 0, false, kInf,
   false, false, ""},
  {"delta_over_L", "delta/L", "1", "joint gap over deck length", ParameterKind::kNumber, 0,
   true, kInf, false, false, ""},
  {"L_over_Le", "L/L_e", "1", "deck length over the persistency a_g / w_g^2 (when delta/L is not given)",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"W0_over_w0", "W0/w0", "1", "torsional over translational frequency of the substructure",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"xi", "xi", "1", "modal damping ratio", ParameterKind::kNumber, 0, true, 1, false, false,
   ""},
  {"eps_N", "eps_N", "1", "normal coefficient of restitution", ParameterKind::kNumber, 0, true,
   1, true, false, ""},
  {"mu", "mu", "1", "Coulomb friction coefficient", ParameterKind::kNumber, 0, true, kInf,
   false, false, ""},
  {"Pi_delta", "Pi_delta", "1", "gap over persistency: delta w_g^2 / a_g",
   ParameterKind::kNumber, 0, true, kInf, false, false, ""},
  {"gap_m", "delta", "m", "every gap, abutments and joints, along x (family model-file; or Pi_delta)",
   ParameterKind::kNumber, 0, true, kInf, false, false, ""},
  {"k_factor", "k_factor", "1", "factor on the substructure stiffness K (family model-file)",
   ParameterKind::kNumber, 0, false, 1e6, true, false, ""},
  {"seat_over_L", "seat/L", "1", "support seat width over span length (unseating margins)",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"w0_over_wg", "w0/w_g", "1", "substructure over excitation frequency w0 / w_g",
   ParameterKind::kNumber, 0, false, kInf, false, false, ""},
  {"method", "method", "", "integrator: event-driven, or Moreau-Jean time-stepping with h = 1e-4 of the excitation period",
   ParameterKind::kLabel, 0, true, 0, true, false, "event-driven|time-stepping"},
}};
// clang-format on

constexpr std::array<std::string_view, 4> kFamilies{"subsystem", "pilot-bridge", "model-file",
                                                    "multi-span"};

// "file:line" when the node has a position, for InputError::AtField.
std::string Where(std::string_view source, const toml::source_region& region) {
  if (region.begin.line == 0) {
    return std::string(source);
  }
  return fmt::format("{}:{}", source, region.begin.line);
}

std::string Fmt(double v) { return fmt::format("{}", v); }

// 16 hex digits of the 64-bit FNV-1a hash of `bytes`.
std::string Fnv1a(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a 64 offset basis
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return fmt::format("{:016x}", h);
}

std::string AllowedRange(const ParameterInfo& p) {
  std::string lo = p.min_inclusive ? ">= " + Fmt(p.min) : "> " + Fmt(p.min);
  if (std::isinf(p.max)) {
    return "a number " + lo;
  }
  std::string hi = p.max_inclusive ? "<= " + Fmt(p.max) : "< " + Fmt(p.max);
  return "a number " + lo + " and " + hi;
}

class Parser {
 public:
  Parser(std::string_view source, std::filesystem::path base_dir)
      : source_(source), base_dir_(std::move(base_dir)) {}

  SweepSpec Parse(std::string_view text) {
    if (HasHdf5Signature(text)) {
      throw InputError::AtLine(source_, 0,
                               "this is an HDF5 file (a sweep cube or a run file), not a sweep "
                               "specification (TOML, docs/sweep-format.md); `skewbridge inspect` "
                               "summarises a cube");
    }
    toml::table root;
    try {
      root = toml::parse(text, source_);
    } catch (const toml::parse_error& e) {
      // A record or signal file given as the specification reads as bad TOML.
      const bool toml_name = std::filesystem::path(source_).extension() == ".toml";
      throw InputError::AtLine(
          source_, static_cast<long>(e.source().begin.line),
          std::string(e.description()) +
              (toml_name ? "" : " (a sweep specification is TOML, docs/sweep-format.md)"));
    }
    SweepSpec spec;
    spec.source = source_;
    spec.text = std::string(text);
    RejectOtherKindOfFile(root);
    for (auto&& [key, node] : root) {
      const std::string k(key.str());
      if (k != "sweep" && k != "axes" && k != "fixed" && k != "records" && k != "study" &&
          k != "limit_states" && k != "ida") {
        throw Error(key.source(), k,
                    "unknown table; allowed: [sweep], [axes], [fixed], [records], [study], "
                    "[limit_states], [ida]" +
                        DidYouMean(k, {"sweep", "axes", "fixed", "records", "study", "limit_states",
                                       "ida"}));
      }
      if (!node.is_table()) {
        throw Error(node.source(), k, "must be a table [" + k + "]");
      }
    }
    const toml::table* sweep = root["sweep"].as_table();
    if (sweep == nullptr) {
      throw InputError::AtField(source_, "sweep", "missing table [sweep] (name, family)");
    }
    ParseSweepTable(*sweep, spec);
    if (const toml::table* records = root["records"].as_table()) {
      ParseRecordsTable(*records, spec);
    }
    if (const toml::table* study = root["study"].as_table()) {
      ParseStudyTable(*study, spec);
    }
    if (const toml::table* limits = root["limit_states"].as_table()) {
      ParseLimitStates(*limits, spec);
    }
    if (const toml::table* ida = root["ida"].as_table()) {
      ParseIda(*ida, spec);
    }
    if (const toml::table* axes = root["axes"].as_table()) {
      for (auto&& [key, node] : *axes) {
        Axis axis = ParseAxis(std::string(key.str()), key.source(), node, spec);
        // A key and its symbol (w0_over_wg and "w0/w_g") name one parameter: TOML sees two.
        if (spec.FindAxis(axis.key) != nullptr) {
          throw Error(key.source(), "axes." + std::string(key.str()),
                      "names the parameter " + axis.key + " a second time (a key and its " +
                          "symbol are the same parameter); give it once");
        }
        spec.axes.push_back(std::move(axis));
      }
    }
    if (const toml::table* fixed = root["fixed"].as_table()) {
      for (auto&& [key, node] : *fixed) {
        FixedValue value = ParseFixed(std::string(key.str()), key.source(), node, spec);
        if (spec.FindFixed(value.key) != nullptr) {
          throw Error(key.source(), "fixed." + std::string(key.str()),
                      "names the parameter " + value.key + " a second time (a key and its " +
                          "symbol are the same parameter); give it once");
        }
        spec.fixed.push_back(std::move(value));
      }
    }
    // [records] without a record key (and without a pulse) means every record of the set.
    const bool has_records =
        !spec.record_set.empty() || !spec.record_folder.empty() || spec.synthetic_count > 0;
    if (has_records && spec.FindAxis("record") == nullptr && spec.FindFixed("record") == nullptr &&
        spec.FindAxis("pulse") == nullptr && spec.FindFixed("pulse") == nullptr) {
      Axis axis;
      axis.key = "record";
      axis.kind = ParameterKind::kLabel;
      axis.spacing = "all";
      axis.labels = AllRecordLabels(spec, "records", toml::source_region{});
      spec.axes.push_back(std::move(axis));
    }
    if (spec.axes.empty()) {
      throw InputError::AtField(source_, "axes",
                                "give at least one axis (a single cell is `skewbridge run`)");
    }
    CheckCrossFields(spec);
    // A subset of responses still stores every limit state's demand and exceedance.
    if (!spec.responses.empty()) {
      for (const spectra::LimitState& ls : spec.limit_states) {
        const auto [demand, exceeded] = spectra::LimitStateResponseNames(ls);
        for (const std::string& name : {demand, exceeded}) {
          if (std::find(spec.responses.begin(), spec.responses.end(), name) ==
              spec.responses.end()) {
            spec.responses.push_back(name);
          }
        }
      }
    }
    SortCanonically(spec);
    CollectInputs(spec);
    return spec;
  }

 private:
  // A model file or a record-set manifest given where a sweep specification belongs is named
  // as what it is, not by its first table foreign to a specification.
  void RejectOtherKindOfFile(const toml::table& root) const {
    if (root.contains("sweep")) {
      return;
    }
    for (const char* table : {"deck", "substructure", "abutments", "excitation"}) {
      if (root.contains(table)) {
        throw InputError::AtLine(
            source_, 0,
            fmt::format("this is a model file ([{}] table), not a sweep specification "
                        "(docs/sweep-format.md); `skewbridge run` and `skewbridge modes` take "
                        "it, and a sweep of it names it in [sweep] model = \"FILE\" with "
                        "family = \"model-file\"",
                        table));
      }
    }
    if (const toml::node* record = root.get("record"); record != nullptr && record->is_array()) {
      throw InputError::AtLine(source_, 0,
                               "this is a record-set manifest ([[record]] tables), not a sweep "
                               "specification (docs/sweep-format.md); a sweep names it in "
                               "[records] set = \"FILE\"");
    }
  }

  InputError Error(const toml::source_region& where, std::string_view field,
                   std::string_view problem) const {
    return InputError::AtField(Where(source_, where), field, problem);
  }

  std::string RequireString(const toml::table& table, std::string_view table_name,
                            std::string_view key) const {
    const toml::node* node = table.get(key);
    const std::string field = std::string(table_name) + "." + std::string(key);
    if (node == nullptr) {
      throw InputError::AtField(source_, field, "missing (a string is required)");
    }
    const auto value = node->value<std::string>();
    if (!node->is_string() || !value || value->empty()) {
      throw Error(node->source(), field, "must be a non-empty string");
    }
    return *value;
  }

  std::filesystem::path ExistingFile(const toml::table& table, std::string_view table_name,
                                     std::string_view key, const std::string& value) const {
    std::filesystem::path path(value);
    if (path.is_relative()) {
      path = base_dir_ / path;
    }
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
      throw Error(table.get(key)->source(), std::string(table_name) + "." + std::string(key),
                  "file not found: " + path.string());
    }
    return path;
  }

  void ParseSweepTable(const toml::table& sweep, SweepSpec& spec) const {
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
    if (std::find(kFamilies.begin(), kFamilies.end(), spec.family) == kFamilies.end()) {
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
        throw Error(node->source(), "sweep.responses",
                    "must be a non-empty list of response names");
      }
      for (const toml::node& item : *list) {
        const auto name = item.value<std::string>();
        if (!item.is_string() || !name || name->empty()) {
          throw Error(item.source(), "sweep.responses", "entries must be non-empty strings");
        }
        if (std::find(spec.responses.begin(), spec.responses.end(), *name) !=
            spec.responses.end()) {
          throw Error(item.source(), "sweep.responses", "duplicate response '" + *name + "'");
        }
        spec.responses.push_back(*name);
      }
    }
  }

  void ParseRecordsTable(const toml::table& records, SweepSpec& spec) const {
    const bool folder_form = records.contains("folder") || records.contains("pattern");
    for (auto&& [key, node] : records) {
      const std::string_view k = key.str();
      const bool folder_key = k == "folder" || k == "pattern" || k == "units" || k == "dt";
      const bool im_key = k == "scale_to" || k == "im" || k == "max_scale";
      if (k != "set" && k != "synthetic" && !im_key && !(folder_form && folder_key)) {
        throw Error(key.source(), "records." + std::string(k),
                    "unknown key; allowed: set, synthetic, or folder and pattern (with units, "
                    "dt); scale_to or im, max_scale" +
                        DidYouMean(k, {"set", "synthetic", "folder", "pattern", "units", "dt",
                                       "scale_to", "im", "max_scale"}));
      }
    }
    ParseIntensityMeasure(records, spec);
    if (static_cast<int>(records.contains("set")) +
            static_cast<int>(records.contains("synthetic")) + static_cast<int>(folder_form) !=
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

  // [records] scale_to = {measure, period, xi} (stripes) or im = {...} (cloud), and max_scale.
  void ParseIntensityMeasure(const toml::table& records, SweepSpec& spec) const {
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
        throw Error(key.source(), name + "." + std::string(k),
                    "unknown key; allowed: measure, period, xi" +
                        DidYouMean(k, {"measure", "period", "xi"}));
      }
    }
    spec.im.scale = scale;
    const toml::node* measure = table->get("measure");
    const std::optional<std::string> m = measure ? measure->value<std::string>() : std::nullopt;
    if (!m) {
      throw Error(measure ? measure->source() : node->source(), name + ".measure",
                  "must be one of \"Sa\", \"AvgSa\", \"PGA\", \"PGV\"");
    }
    if (*m != "Sa" && *m != "AvgSa" && *m != "PGA" && *m != "PGV") {
      throw Error(measure->source(), name + ".measure",
                  "unknown measure '" + *m + "'; allowed: Sa, AvgSa, PGA, PGV");
    }
    spec.im.measure = *m;
    const bool spectral = *m == "Sa" || *m == "AvgSa";
    const toml::node* period = table->get("period");
    const toml::node* xi = table->get("xi");
    if (!spectral) {
      if (period != nullptr || xi != nullptr) {
        throw Error((period ? period : xi)->source(), name + (period ? ".period" : ".xi"),
                    "only for Sa and AvgSa (" + *m + " has no period or damping)");
      }
      return;
    }
    if (period == nullptr) {
      if (*m == "Sa") {
        throw Error(node->source(), name + ".period",
                    "missing: Sa needs a period in s or \"T1\" (the model's fundamental period)");
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

  // [records] folder and pattern: a folder set without a manifest; the folder is listed now,
  // so a missing folder, a bad pattern or an empty match fails here.
  void ParseRecordFolder(const toml::table& records, SweepSpec& spec) const {
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
    spectra::LoadSpecRecordSet(spec);
  }

  // A threshold of a limit state: a finite number >= 0.
  double Threshold(const toml::node& node, const std::string& field, std::string_view unit) const {
    const std::optional<double> v = node.value<double>();
    if (!node.is_number() || !v || !std::isfinite(*v) || *v < 0.0) {
      throw Error(node.source(), field, "must be a number >= 0 (" + std::string(unit) + ")");
    }
    return *v;
  }

  // A limit state given as `key = {above_<unit> = v}`.
  double Above(const toml::node& node, const std::string& field, std::string_view key) const {
    const toml::table* table = node.as_table();
    if (table == nullptr || table->size() != 1 || !table->contains(key)) {
      throw Error(node.source(), field,
                  "must be a table {" + std::string(key) + " = VALUE} (the value it must exceed)");
    }
    return Threshold(*table->get(key), field + "." + std::string(key), key.substr(6));
  }

  // [ida] (docs/sweep-format.md): the hunt-and-fill search's intensities, in the unit of the
  // scale_to measure, and its run budget.
  void ParseIda(const toml::table& table, SweepSpec& spec) const {
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
        throw Error(key.source(), field,
                    "unknown key; allowed: " + allowed +
                        DidYouMean(k, {"start", "step", "step_increase", "tolerance", "max_im",
                                       "max_runs"}));
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

  // [limit_states] (docs/sweep-format.md): kept in canonical order, the responses by name.
  void ParseLimitStates(const toml::table& limits, SweepSpec& spec) const {
    using spectra::LimitState;
    using spectra::LimitStateKind;
    constexpr std::array<std::string_view, 6> kKeys{
        "unseating", "rotation", "seat_displacement", "residual", "joint_closing", "response"};
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

  void ParseStudyTable(const toml::table& study, SweepSpec& spec) const {
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

  // Every label of the spec's record set, in set order ([records] must come first in the file
  // only as far as TOML goes: tables are parsed before axes whatever their order).
  std::vector<std::string> AllRecordLabels(const SweepSpec& spec, const std::string& field,
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

  // "; did you mean `a_deg` (skew angle a)?" for the parameter nearest to `word` by its key,
  // its symbol or the model-file key of the same quantity (skew_deg), or "".
  static std::string NearestParameter(const std::string& word) {
    std::vector<std::string> names;
    std::vector<const ParameterInfo*> owners;
    for (const ParameterInfo& p : kParameters) {
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

  const ParameterInfo& Known(const std::string& field, const std::string& key,
                             const toml::source_region& where) const {
    const ParameterInfo* info = FindParameter(key);
    if (info == nullptr) {
      std::string allowed;
      for (const ParameterInfo& p : kParameters) {
        allowed += (allowed.empty() ? "" : ", ") + std::string(p.key);
      }
      throw Error(where, field, "unknown parameter; allowed: " + allowed + NearestParameter(key));
    }
    return *info;
  }

  void CheckNumber(const ParameterInfo& p, double v, const std::string& field,
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

  void CheckLabel(const ParameterInfo& p, const std::string& v, const std::string& field,
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

  double Number(const toml::node& node, const std::string& field) const {
    const auto v = node.value<double>();
    if (!node.is_number() || !v) {
      throw Error(node.source(), field, "must be a number");
    }
    return *v;
  }

  Axis ParseAxis(const std::string& key, const toml::source_region& key_where,
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

  FixedValue ParseFixed(const std::string& key, const toml::source_region& key_where,
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

  void CheckCrossFields(const SweepSpec& spec) const {
    auto given = [&spec](std::string_view key) {
      return spec.FindAxis(key) != nullptr || spec.FindFixed(key) != nullptr;
    };
    if (spec.ida.enabled && !(spec.im.scale && !spec.im.measure.empty())) {
      throw InputError::AtField(source_, "ida",
                                "needs [records] scale_to = {measure = \"Sa\", period = \"T1\", "
                                "xi = 0.05} (or another measure): the intensity it scales to");
    }
    if (spec.ida.enabled && !spec.responses.empty()) {
      throw InputError::AtField(source_, "sweep.responses",
                                "not with [ida]: an IDA cell stores its search (the runs and the "
                                "capacities), not the responses of one run");
    }
    if (spec.ida.enabled && spec.limit_states.empty()) {
      throw InputError::AtField(source_, "ida",
                                "needs [limit_states]: the search scales each record until they "
                                "are exceeded");
    }
    for (const Axis& axis : spec.axes) {
      if (spec.FindFixed(axis.key) != nullptr) {
        throw InputError::AtField(source_, "fixed." + axis.key, "is also an axis");
      }
    }
    if (given("eta0") && given("W_over_L")) {
      throw InputError::AtField(source_, "eta0",
                                "give eta0 or W_over_L, not both (eta0 = sin 2a / (2 W/L))");
    }
    static constexpr std::array<std::string_view, 5> kModelFileOnly{"w_g", "T_g", "scale", "gap_m",
                                                                    "k_factor"};
    if (spec.family != "model-file") {
      for (std::string_view key : kModelFileOnly) {
        if (given(key)) {
          throw InputError::AtField(source_, key,
                                    "only a parameter of family \"model-file\" (this sweep's "
                                    "family is \"" +
                                        spec.family + "\")");
        }
      }
    }
    if (given("w_g") && given("T_g")) {
      throw InputError::AtField(source_, "T_g", "give w_g or T_g, not both (T_g = 2 pi / w_g)");
    }
    if (given("gap_m") && given("Pi_delta")) {
      throw InputError::AtField(source_, "gap_m",
                                "give gap_m or Pi_delta, not both (the gap is Pi_delta L_e)");
    }
    if (given("pulse") && given("record")) {
      throw InputError::AtField(source_, "record",
                                "give pulse or record, not both (one excitation per cell)");
    }
    if (given("record") && spec.record_set.empty() && spec.record_folder.empty() &&
        spec.synthetic_count == 0) {
      throw InputError::AtField(source_, "records.set",
                                "missing: a record axis or value needs [records] set = \"FILE\"");
    }
    CheckIntensityFields(spec, given);
  }

  // The intensity axis and [records] scale_to / im belong together (docs/sweep-format.md).
  template <typename Given>
  void CheckIntensityFields(const SweepSpec& spec, const Given& given) const {
    const spectra::IntensityMeasureSpec& im = spec.im;
    if (im.measure.empty()) {
      for (std::string_view key : {"im_g", "im_mps"}) {
        if (given(key)) {
          throw InputError::AtField(source_, key,
                                    "an intensity axis needs [records] scale_to = {measure = "
                                    "\"Sa\", period = \"T1\", xi = 0.05} (or another measure) "
                                    "to scale the records to it");
        }
      }
      return;
    }
    const std::string name = im.scale ? "records.scale_to" : "records.im";
    if (spec.family != "model-file") {
      throw InputError::AtField(
          source_, name,
          "only for family \"model-file\": in \"" + spec.family +
              "\" the gap is Pi_delta L_e of each record, so a scaled record gives the same "
              "dimensionless responses (self-similarity, docs/theory.md §4); give the bridge as "
              "a model file with gaps in metres");
    }
    if (!given("record")) {
      throw InputError::AtField(source_, name,
                                "needs records: a [records] set, folder or synthetic suite");
    }
    const std::string axis = im.AxisKey();
    const std::string other = axis == "im_g" ? "im_mps" : "im_g";
    if (given(other)) {
      throw InputError::AtField(source_, other,
                                "not the axis of " + im.measure + ": give " + axis + " (" +
                                    (axis == "im_g" ? "g" : "m/s") + ")");
    }
    if (im.scale && spec.ida.enabled) {
      // The hunt-and-fill search chooses each cell's intensities: no stripes to give.
      for (std::string_view key : {std::string_view(axis), std::string_view("scale")}) {
        if (given(key)) {
          throw InputError::AtField(source_, key,
                                    "not with [ida]: the hunt-and-fill search chooses each "
                                    "record's intensities (remove it, or remove [ida] for "
                                    "stripes)");
        }
      }
    } else if (im.scale) {
      if (!given(axis)) {
        throw InputError::AtField(source_, "axes." + axis,
                                  "missing: records.scale_to needs an intensity axis " + axis +
                                      " = [...] (" + (axis == "im_g" ? "g" : "m/s") +
                                      "), the values each record is scaled to");
      }
      if (given("scale")) {
        throw InputError::AtField(source_, "scale",
                                  "give scale or records.scale_to, not both (scale_to sets "
                                  "each cell's factor)");
      }
    } else if (given(axis)) {
      throw InputError::AtField(source_, axis,
                                "records.im leaves the records unscaled (cloud); to scale them "
                                "to " +
                                    axis + " use records.scale_to");
    }
  }

  // The name of an input in the cube and the identity: relative to the specification's folder
  // when it was found from there, so that the identity does not depend on the working folder.
  std::string RelativeName(const std::filesystem::path& path) const {
    const std::filesystem::path file = path.lexically_normal();
    const std::filesystem::path base =
        base_dir_.empty() ? std::filesystem::path(".") : base_dir_.lexically_normal();
    if (file.is_absolute() != base.is_absolute()) return file.generic_string();
    const std::filesystem::path relative = file.lexically_relative(base);
    return relative.empty() ? file.generic_string() : relative.generic_string();
  }

  // Reads and checksums one input file (once: a file named twice is listed once).
  void AddInput(SweepSpec& spec, std::string role, const std::filesystem::path& path) const {
    InputFile input;
    input.file = RelativeName(path);
    for (const InputFile& known : spec.inputs) {
      if (known.file == input.file) return;
    }
    const FileChecksum sum = ChecksumFile(path);
    input.role = std::move(role);
    input.path = path;
    input.sha256 = sum.sha256;
    input.bytes = sum.bytes;
    spec.inputs.push_back(std::move(input));
  }

  // The input manifest: every file the cells read, each hashed once here (not per cell).
  void CollectInputs(SweepSpec& spec) const {
    InputFile self;
    self.role = "spec";
    self.file = std::filesystem::path(source_).filename().generic_string();
    self.path = source_;
    self.sha256 = Sha256Hex(spec.text);
    self.bytes = spec.text.size();
    spec.inputs.push_back(std::move(self));
    for (const spectra::GridInput& input : spectra::GridInputFiles(spec)) {
      AddInput(spec, input.role, input.path);
    }
  }

  static void SortCanonically(SweepSpec& spec) {
    auto rank = [](std::string_view key) { return FindParameter(key) - kParameters.data(); };
    std::stable_sort(spec.axes.begin(), spec.axes.end(),
                     [&](const Axis& x, const Axis& y) { return rank(x.key) < rank(y.key); });
    std::stable_sort(spec.fixed.begin(), spec.fixed.end(),
                     [&](const auto& x, const auto& y) { return rank(x.key) < rank(y.key); });
  }

  std::string source_;
  std::filesystem::path base_dir_;
};

}  // namespace

std::span<const ParameterInfo> KnownParameters() { return kParameters; }

const ParameterInfo* FindParameter(std::string_view name) {
  for (const ParameterInfo& p : kParameters) {
    if (p.key == name || p.symbol == name) {
      return &p;
    }
  }
  return nullptr;
}

std::span<const std::string_view> KnownFamilies() { return kFamilies; }

std::string SweepSpec::CanonicalText() const {
  std::ostringstream out;
  auto str = [](const std::string& s) {
    std::string q = "\"";
    for (char c : s) {
      if (c == '"' || c == '\\') {
        q += '\\';
      }
      q += c;
    }
    return q + "\"";
  };
  out << "sweep.name = " << str(name) << "\n";
  out << "sweep.family = " << str(family) << "\n";
  if (!model_file.empty()) {
    out << "sweep.model = " << str(model_file) << "\n";
  }
  if (!record_set.empty()) {
    out << "records.set = " << str(record_set) << "\n";
  }
  if (!record_folder.empty()) {
    out << "records.folder = " << str(record_folder) << "\n";
    out << "records.pattern = " << str(record_pattern) << "\n";
    if (!record_units.empty()) out << "records.units = " << str(record_units) << "\n";
    if (record_dt_s > 0.0) out << "records.dt = " << Fmt(record_dt_s) << "\n";
  }
  if (synthetic_count > 0) {
    out << "records.synthetic = {count = " << synthetic_count << ", seed = " << synthetic_seed
        << "}\n";
  }
  if (!im.measure.empty()) {
    out << (im.scale ? "records.scale_to" : "records.im") << " = {measure = " << str(im.measure);
    if (im.measure == "Sa" || im.measure == "AvgSa") {
      out << ", period = " << (im.at_t1 ? std::string("\"T1\"") : Fmt(im.period_s))
          << ", xi = " << Fmt(im.xi);
    }
    out << "}\n";
  }
  if (im.max_scale > 0.0) out << "records.max_scale = " << Fmt(im.max_scale) << "\n";
  if (ida.enabled) {
    out << "ida = {start = " << Fmt(ida.start) << ", step = " << Fmt(ida.step)
        << ", step_increase = " << Fmt(ida.step_increase) << ", tolerance = " << Fmt(ida.tolerance)
        << ", max_im = " << Fmt(ida.max_im) << ", max_runs = " << ida.max_runs << "}\n";
  }
  if (!study_bands.empty()) {
    out << "study.bands = [";
    for (std::size_t i = 0; i < study_bands.size(); ++i) {
      out << (i ? ", " : "") << Fmt(study_bands[i]);
    }
    out << "]\n";
  }
  for (const Axis& axis : axes) {
    out << "axes." << axis.key << " = [";
    for (std::size_t i = 0; i < axis.Size(); ++i) {
      out << (i ? ", " : "")
          << (axis.kind == ParameterKind::kNumber ? Fmt(axis.values[i]) : str(axis.labels[i]));
    }
    out << "]\n";
  }
  for (const FixedValue& f : fixed) {
    out << "fixed." << f.key << " = "
        << (f.kind == ParameterKind::kNumber ? Fmt(f.value) : str(f.label)) << "\n";
  }
  for (const spectra::LimitState& ls : limit_states) {
    out << "limit_states." << spectra::LimitStateKindName(ls.kind);
    if (ls.kind == spectra::LimitStateKind::kResponse) out << "." << ls.response;
    out << " = {threshold = " << Fmt(ls.threshold) << ", seat_m = [";
    for (std::size_t i = 0; i < ls.seat_m.size(); ++i) out << (i ? ", " : "") << Fmt(ls.seat_m[i]);
    out << "]}\n";
  }
  out << "sweep.responses = [";
  for (std::size_t i = 0; i < responses.size(); ++i) {
    out << (i ? ", " : "") << str(responses[i]);
  }
  out << "]\n";
  return out.str();
}

std::string SweepSpec::InputsText() const {
  std::string out = fmt::format("program.version = \"{}\"\n", SKEWBRIDGE_VERSION);
  for (const InputFile& input : inputs) {
    if (input.role == "spec") continue;
    out += fmt::format("{} \"{}\" = {}\n", input.role, input.file, input.sha256);
  }
  return out;
}

std::string SweepSpec::Hash() const { return Fnv1a(CanonicalText() + InputsText()); }

namespace {

// The lines of a canonical or input text as key -> value, in order. Keys of the specification
// hold no space and end at the first " = "; a value of the input manifest (a hex checksum or a
// quoted version) holds none, so an input's key ends at the last one.
std::vector<std::pair<std::string, std::string>> KeyedLines(const std::string& text, bool inputs) {
  std::vector<std::pair<std::string, std::string>> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t at = inputs ? line.rfind(" = ") : line.find(" = ");
    if (at == std::string::npos) {
      out.emplace_back(line, "");
    } else {
      out.emplace_back(line.substr(0, at), line.substr(at + 3));
    }
  }
  return out;
}

// The first key whose value differs between the two texts, present in either: {key, old, new}
// with "(absent)" for a key that one side lacks; all empty when the texts agree.
std::array<std::string, 3> FirstDifference(const std::string& before, const std::string& now,
                                           bool inputs) {
  const auto old_lines = KeyedLines(before, inputs);
  const auto new_lines = KeyedLines(now, inputs);
  auto find = [](const auto& lines, const std::string& key) -> const std::string* {
    for (const auto& [k, v] : lines) {
      if (k == key) return &v;
    }
    return nullptr;
  };
  for (const auto& [key, value] : new_lines) {
    const std::string* was = find(old_lines, key);
    if (was == nullptr) return {key, "(absent)", value};
    if (*was != value) return {key, *was, value};
  }
  for (const auto& [key, value] : old_lines) {
    if (find(new_lines, key) == nullptr) return {key, value, "(absent)"};
  }
  return {};
}

// A value for a message: whole when short, else its start and length.
std::string Shortened(const std::string& value) {
  constexpr std::size_t kMax = 72;
  if (value.size() <= kMax) return value;
  return value.substr(0, kMax) + fmt::format("... ({} characters)", value.size());
}

}  // namespace

std::string DescribeIdentityChange(const std::string& stored_canonical,
                                   const std::string& stored_inputs, const SweepSpec& spec) {
  const auto spec_change = FirstDifference(stored_canonical, spec.CanonicalText(), false);
  if (!spec_change[0].empty()) {
    return fmt::format(
        "{}: key {} differs from the specification the cube was computed with "
        "(cube: {}; now: {})",
        spec.source, spec_change[0], Shortened(spec_change[1]), Shortened(spec_change[2]));
  }
  const auto input_change = FirstDifference(stored_inputs, spec.InputsText(), true);
  if (input_change[0].empty()) return "";
  const std::string& key = input_change[0];
  if (key == "program.version") {
    if (input_change[1] == "(absent)") {
      return "the cube holds no input manifest (it was written before the checksums of its "
             "input files were stored), so its inputs cannot be checked";
    }
    auto bare = [](std::string v) {
      v.erase(std::remove(v.begin(), v.end(), '"'), v.end());
      return v;
    };
    return fmt::format(
        "the cube was computed by skewbridge {}, this is {} (its results may "
        "differ)",
        bare(input_change[1]), bare(input_change[2]));
  }
  // `ROLE "FILE"`: name the file where this run reads it.
  const std::size_t quote = key.find('"');
  const std::string role = key.substr(0, quote == std::string::npos ? key.size() : quote - 1);
  const std::string file =
      quote == std::string::npos ? key : key.substr(quote + 1, key.size() - quote - 2);
  std::string where = file;
  for (const InputFile& input : spec.inputs) {
    if (input.file == file) where = input.path.string();
  }
  if (input_change[1] == "(absent)") {
    return fmt::format("{} ({}) is an input the cube was not computed from", where, role);
  }
  if (input_change[2] == "(absent)") {
    return fmt::format("{} ({}) was an input of the cube and is no longer one", where, role);
  }
  return fmt::format("{} ({}) has changed since the cube was computed from it (sha256 {}, now {})",
                     where, role, input_change[1], input_change[2]);
}

SweepSpec ParseSweepSpec(std::string_view text, std::string_view source,
                         const std::filesystem::path& base_dir) {
  return Parser(source, base_dir).Parse(text);
}

SweepSpec LoadSweepSpec(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw InputError::AtLine(file.string(), 0, "cannot read the sweep specification");
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  return ParseSweepSpec(buffer.str(), file.string(), file.parent_path());
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
