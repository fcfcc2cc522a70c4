#include "jobs/sweep_parser.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "jobs/file_checksum.h"
#include "solver/common/file_kind.h"
#include "solver/common/nearest.h"
#include "spectra/inputs.h"
#include "spectra/limit_states.h"

namespace skewbridge::jobs {

std::string Where(std::string_view source, const toml::source_region& region) {
  if (region.begin.line == 0) {
    return std::string(source);
  }
  return fmt::format("{}:{}", source, region.begin.line);
}

SweepSpec SpecParser::Parse(std::string_view text) {
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
        k != "limit_states" && k != "ida" && k != "event_policy" && k != "time_stepping_policy") {
      throw Error(key.source(), k,
                  "unknown table; allowed: [sweep], [axes], [fixed], [records], [study], "
                  "[limit_states], [ida], [event_policy], [time_stepping_policy]" +
                      DidYouMean(k, {"sweep", "axes", "fixed", "records", "study", "limit_states",
                                     "ida", "event_policy", "time_stepping_policy"}));
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
  if (const toml::table* policy = root["event_policy"].as_table()) {
    ParseEventPolicy(*policy, spec);
  }
  if (const toml::table* policy = root["time_stepping_policy"].as_table()) {
    ParseTimeSteppingPolicy(*policy, spec);
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
      spec.key_at["axes." + axis.key] = Where(source_, key.source());
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
      spec.key_at["fixed." + value.key] = Where(source_, key.source());
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
        if (std::find(spec.responses.begin(), spec.responses.end(), name) == spec.responses.end()) {
          spec.responses.push_back(name);
        }
      }
    }
  }
  SortCanonically(spec);
  CollectInputs(spec);
  return spec;
}

void SpecParser::RejectOtherKindOfFile(const toml::table& root) const {
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

InputError SpecParser::Error(const toml::source_region& where, std::string_view field,
                             std::string_view problem) const {
  return InputError::AtField(Where(source_, where), field, problem);
}

std::string SpecParser::RequireString(const toml::table& table, std::string_view table_name,
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

std::filesystem::path SpecParser::ExistingFile(const toml::table& table,
                                               std::string_view table_name, std::string_view key,
                                               const std::string& value) const {
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

std::string SpecParser::RelativeName(const std::filesystem::path& path) const {
  const std::filesystem::path file = path.lexically_normal();
  const std::filesystem::path base =
      base_dir_.empty() ? std::filesystem::path(".") : base_dir_.lexically_normal();
  if (file.is_absolute() != base.is_absolute()) return file.generic_string();
  const std::filesystem::path relative = file.lexically_relative(base);
  return relative.empty() ? file.generic_string() : relative.generic_string();
}

void SpecParser::AddInput(SweepSpec& spec, std::string role,
                          const std::filesystem::path& path) const {
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

void SpecParser::CollectInputs(SweepSpec& spec) const {
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

void SpecParser::SortCanonically(SweepSpec& spec) {
  auto rank = [](std::string_view key) { return FindParameter(key) - KnownParameters().data(); };
  std::stable_sort(spec.axes.begin(), spec.axes.end(),
                   [&](const Axis& x, const Axis& y) { return rank(x.key) < rank(y.key); });
  std::stable_sort(spec.fixed.begin(), spec.fixed.end(),
                   [&](const auto& x, const auto& y) { return rank(x.key) < rank(y.key); });
}

SweepSpec ParseSweepSpec(std::string_view text, std::string_view source,
                         const std::filesystem::path& base_dir) {
  return SpecParser(source, base_dir).Parse(text);
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

}  // namespace skewbridge::jobs
