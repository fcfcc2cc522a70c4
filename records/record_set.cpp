#include "records/record_set.h"

#include <toml++/toml.h>
#include <algorithm>
#include <cmath>
#include <set>

#include "solver/common/error.h"
#include "solver/common/nearest.h"

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

// The options a [[record]] table or a folder set's top level may give (scale, units, dt,
// format, channel), read from `table`.
void ReadEntryOptions(const toml::table& table, const std::filesystem::path& manifest,
                      RecordEntry& entry) {
  entry.scale = PositiveNumber(table, "scale", manifest).value_or(1.0);
  if (!(entry.scale <= 1e6)) {  // beyond, accelerations overflow into unit errors
    throw InputError::AtField(Where(manifest, LineOf(*table.get("scale"))), "scale",
                              "must be a number > 0 and at most 1e6");
  }
  entry.options.dt_s = PositiveNumber(table, "dt", manifest);
  if (const toml::node* bound = table.get("max_pga_g")) {
    // A number > 0, or inf for no bound (the user means the amplitudes as they are).
    const std::optional<double> value = bound->value<double>();
    if (!value || !(*value > 0.0)) {
      throw InputError::AtField(Where(manifest, LineOf(*bound)), "max_pga_g",
                                "must be a number > 0 (g), or inf for no bound");
    }
    entry.options.max_pga_g = *value;
  }
  if (const std::string units = RequireString(table, "units", manifest, false); !units.empty()) {
    entry.options.units = ParseUnits(units);
    if (!entry.options.units) {
      throw InputError::AtField(
          Where(manifest, LineOf(*table.get("units"))), "units",
          "unknown units '" + units + "' (allowed: " + std::string(AllowedUnitsText()) + ")");
    }
  }
  if (const std::string format = RequireString(table, "format", manifest, false); !format.empty()) {
    const std::optional<Format> parsed = ParseFormat(format);
    if (!parsed) {
      throw InputError::AtField(Where(manifest, LineOf(*table.get("format"))), "format",
                                "unknown format '" + format +
                                    "' (allowed: auto, at2, esm, itsak, cosmos, csmip, smc, "
                                    "smtk, plain, time-acc)");
    }
    entry.options.format = *parsed;
  }
  if (const toml::node* channel = table.get("channel")) {
    const std::optional<int64_t> value = channel->value<int64_t>();
    if (!value || *value < 1 || *value > 1000) {
      throw InputError::AtField(Where(manifest, LineOf(*channel)), "channel",
                                "must be an integer >= 1");
    }
    entry.options.channel = static_cast<int>(*value);
  }
}

// The folder form: every regular file of `folder` whose name matches `pattern`, in byte order
// of the names (a stable set order whatever the file system lists first), each with the
// top-level options.
void ReadFolderSet(const toml::table& root, const std::filesystem::path& manifest, RecordSet& set) {
  const std::string folder = RequireString(root, "folder", manifest, true);
  const std::string folder_at = Where(manifest, LineOf(*root.get("folder")));
  const toml::node* pattern_node = root.get("pattern");
  if (pattern_node == nullptr) {
    throw InputError::AtField(folder_at, "pattern",
                              "is required with folder (a file-name glob, e.g. \"*.AT2\")");
  }
  const std::string pattern = RequireString(root, "pattern", manifest, true);
  RecordEntry defaults;
  ReadEntryOptions(root, manifest, defaults);
  defaults.line = LineOf(*root.get("folder"));
  const RecordSet folder_set =
      MakeFolderSet(manifest.parent_path() / folder, pattern, defaults,
                    {folder_at, Where(manifest, LineOf(*pattern_node)), ""});
  set.records = folder_set.records;
}

}  // namespace

std::string GlobProblem(std::string_view pattern) {
  if (pattern.empty()) return "empty pattern";
  // Appending (not "literal" + string) avoids g++ 12's false -Wrestrict warning.
  std::string quoted = "'";
  quoted += pattern;
  quoted += '\'';
  if (pattern.find('/') != std::string_view::npos) {
    return quoted + " names a folder; give it in folder, the pattern matches file names only";
  }
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '[') continue;
    std::size_t j = i + 1;
    if (j < pattern.size() && pattern[j] == '!') ++j;
    if (j < pattern.size() && pattern[j] == ']') ++j;  // a leading ']' is a member
    while (j < pattern.size() && pattern[j] != ']') ++j;
    if (j >= pattern.size()) return quoted + " has an unclosed '['";
    i = j;
  }
  return {};
}

bool GlobMatch(std::string_view pattern, std::string_view name) {
  // Iterative matching with one back-track point for the last '*' (linear in practice).
  std::size_t p = 0, n = 0, star = std::string_view::npos, star_n = 0;
  auto class_end = [&pattern](std::size_t at) {
    std::size_t j = at + 1;
    if (j < pattern.size() && pattern[j] == '!') ++j;
    if (j < pattern.size() && pattern[j] == ']') ++j;
    while (j < pattern.size() && pattern[j] != ']') ++j;
    return j;  // the closing ']' (GlobProblem guarantees one)
  };
  auto in_class = [&pattern](std::size_t at, std::size_t end, char c) {
    std::size_t j = at + 1;
    const bool negate = j < end && pattern[j] == '!';
    if (negate) ++j;
    bool hit = false;
    for (bool first = true; j < end; ++j, first = false) {
      if (!first && pattern[j] == ']') break;
      if (j + 2 < end && pattern[j + 1] == '-') {
        hit = hit || (pattern[j] <= c && c <= pattern[j + 2]);
        j += 2;
      } else {
        hit = hit || pattern[j] == c;
      }
    }
    return hit != negate;
  };
  while (n < name.size()) {
    if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      star_n = n;
      continue;
    }
    if (p < pattern.size()) {
      if (pattern[p] == '?') {
        ++p;
        ++n;
        continue;
      }
      if (pattern[p] == '[') {
        const std::size_t end = class_end(p);
        if (end < pattern.size() && in_class(p, end, name[n])) {
          p = end + 1;
          ++n;
          continue;
        }
      } else if (pattern[p] == name[n]) {
        ++p;
        ++n;
        continue;
      }
    }
    if (star == std::string_view::npos) return false;
    p = star + 1;
    n = ++star_n;
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

RecordSet MakeFolderSet(const std::filesystem::path& folder, std::string_view pattern,
                        const RecordEntry& defaults, const FolderSetSource& source) {
  const std::string folder_key = source.key_prefix + "folder";
  const std::string pattern_key = source.key_prefix + "pattern";
  if (const std::string problem = GlobProblem(pattern); !problem.empty()) {
    throw InputError::AtField(source.pattern_at, pattern_key,
                              problem + " (allowed: a file name with *, ? and [...] classes)");
  }
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) {
    throw InputError::AtField(source.folder_at, folder_key, "not a folder: " + folder.string());
  }
  std::vector<std::filesystem::path> files;
  for (const std::filesystem::directory_entry& item :
       std::filesystem::directory_iterator(folder, ec)) {
    if (item.is_regular_file(ec) && GlobMatch(pattern, item.path().filename().string())) {
      files.push_back(item.path());
    }
  }
  if (ec) {
    throw InputError::AtField(source.folder_at, folder_key,
                              "cannot list " + folder.string() + ": " + ec.message());
  }
  if (files.empty()) {
    throw InputError::AtField(
        source.pattern_at, pattern_key,
        "no file of " + folder.string() + " matches '" + std::string(pattern) + "'");
  }
  std::sort(files.begin(), files.end(), [](const auto& a, const auto& b) {
    return a.filename().string() < b.filename().string();
  });
  RecordSet set;
  // The folder itself stands for the manifest: record paths are relative to its parent.
  set.manifest = folder.filename().empty() ? folder.parent_path() : folder;
  set.name = set.manifest.filename().string();
  for (const std::filesystem::path& file : files) {
    RecordEntry entry = defaults;
    entry.file = file;
    set.records.push_back(std::move(entry));
  }
  return set;
}

RecordSet LoadRecordSet(const std::filesystem::path& manifest) {
  std::error_code ec;
  if (!std::filesystem::exists(manifest, ec)) {
    throw InputError::AtLine(manifest.string(), 0, "the record-set manifest does not exist");
  }
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
  const bool folder_form = root.contains("folder") || root.contains("pattern");
  static const std::set<std::string_view> kFolderKeys = {
      "name", "folder", "pattern", "scale", "units", "dt", "format", "channel", "max_pga_g"};
  // A sweep specification or a model file is named as what it is, not by its first table.
  if (!root.contains("record") && !folder_form) {
    if (root.contains("sweep")) {
      throw InputError::AtLine(manifest.string(), 0,
                               "this is a sweep specification ([sweep] table), not a record-set "
                               "manifest (docs/records.md); `skewbridge sweep SPEC --out "
                               "FILE.h5` takes it");
    }
    if (root.contains("deck") || root.contains("substructure")) {
      throw InputError::AtLine(manifest.string(), 0,
                               "this is a model file ([deck] table), not a record-set manifest "
                               "(docs/records.md); `skewbridge run` and `skewbridge modes` take "
                               "it");
    }
  }
  for (const auto& [key, node] : root) {
    if (folder_form ? !kFolderKeys.contains(key.str()) : key != "name" && key != "record") {
      const std::vector<std::string> allowed =
          folder_form ? std::vector<std::string>(kFolderKeys.begin(), kFolderKeys.end())
                      : std::vector<std::string>{"name", "record", "folder", "pattern"};
      throw InputError::AtField(
          Where(manifest, LineOf(node)), key.str(),
          (folder_form ? "unknown key of a folder set (allowed: name, folder, pattern, scale, "
                         "units, dt, format, channel, max_pga_g; [[record]] tables are the "
                         "other form)"
                       : "unknown key (allowed: name, [[record]], or folder and pattern)") +
              DidYouMean(key.str(), allowed));
    }
  }
  if (const toml::node* name = root.get("name")) {
    if (!name->is_string()) {
      throw InputError::AtField(Where(manifest, LineOf(*name)), "name", "must be a string");
    }
    set.name = *name->value<std::string>();
  }
  if (folder_form) {
    ReadFolderSet(root, manifest, set);
    return set;
  }
  const toml::array* records = root.get_as<toml::array>("record");
  if (records == nullptr || records->empty()) {
    throw InputError::AtLine(manifest.string(), 0, "no [[record]] entries");
  }
  const std::filesystem::path base = manifest.parent_path();
  static const std::set<std::string_view> kKeys = {
      "file", "label", "component", "scale", "units", "dt", "format", "channel", "max_pga_g"};
  for (const toml::node& item : *records) {
    const toml::table* table = item.as_table();
    if (table == nullptr) {
      throw InputError::AtLine(manifest.string(), LineOf(item),
                               "record must be a [[record]] table");
    }
    for (const auto& [key, value] : *table) {
      if (!kKeys.contains(key.str())) {
        throw InputError::AtField(
            Where(manifest, LineOf(value)), key.str(),
            "unknown key (allowed: file, label, component, scale, units, dt, format, channel, "
            "max_pga_g)" +
                DidYouMean(key.str(), std::vector<std::string>(kKeys.begin(), kKeys.end())));
      }
    }
    RecordEntry entry;
    entry.line = LineOf(*table);
    entry.file = base / RequireString(*table, "file", manifest, true);
    entry.label = RequireString(*table, "label", manifest, false);
    entry.component = RequireString(*table, "component", manifest, false);
    ReadEntryOptions(*table, manifest, entry);
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
