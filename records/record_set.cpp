#include "records/record_set.h"

#include <fmt/format.h>
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

// The file of a [[record]] table (file), or the two of a pair (h1 and h2), resolved against the
// manifest's folder, with their component labels.
void ReadEntryFiles(const toml::table& table, const std::filesystem::path& manifest,
                    RecordEntry& entry) {
  const std::filesystem::path base = manifest.parent_path();
  const bool pair = table.contains("h1") || table.contains("h2");
  if (!pair) {
    for (const char* key : {"component_h1", "component_h2"}) {
      if (const toml::node* node = table.get(key)) {
        throw InputError::AtField(Where(manifest, LineOf(*node)), key,
                                  "only for a pair (h1 and h2); a single record takes component");
      }
    }
    entry.file = base / RequireString(table, "file", manifest, true);
    entry.component = RequireString(table, "component", manifest, false);
    return;
  }
  for (const char* key : {"file", "component"}) {
    if (const toml::node* node = table.get(key)) {
      throw InputError::AtField(Where(manifest, LineOf(*node)), key,
                                std::string("a pair names its files h1 and h2 (and their "
                                            "components component_h1, component_h2), not ") +
                                    key);
    }
  }
  for (const char* key : {"h1", "h2"}) {
    if (!table.contains(key)) {
      throw InputError::AtField(Where(manifest, LineOf(table)), key,
                                "is required for a pair: the files of both horizontal "
                                "components, h1 and h2");
    }
  }
  entry.file = base / RequireString(table, "h1", manifest, true);
  entry.file_h2 = base / RequireString(table, "h2", manifest, true);
  if (entry.file.lexically_normal() == entry.file_h2.lexically_normal()) {
    throw InputError::AtField(Where(manifest, LineOf(*table.get("h2"))), "h2",
                              "is the file of h1; a pair has two files, one per component");
  }
  entry.component = RequireString(table, "component_h1", manifest, false);
  entry.component_h2 = RequireString(table, "component_h2", manifest, false);
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
      "file",    "label",     "component", "scale", "units",        "dt",          "format",
      "channel", "max_pga_g", "h1",        "h2",    "component_h1", "component_h2"};
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
            "max_pga_g; h1, h2, component_h1, component_h2 for a pair)" +
                DidYouMean(key.str(), std::vector<std::string>(kKeys.begin(), kKeys.end())));
      }
    }
    RecordEntry entry;
    entry.line = LineOf(*table);
    ReadEntryFiles(*table, manifest, entry);
    entry.label = RequireString(*table, "label", manifest, false);
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

std::string PairLabel(const std::filesystem::path& h1, const std::filesystem::path& h2) {
  const std::string a = h1.filename().string();
  const std::string b = h2.filename().string();
  std::size_t n = 0;
  while (n < a.size() && n < b.size() && a[n] == b[n]) ++n;
  while (n > 0 && (a[n - 1] == '_' || a[n - 1] == '-' || a[n - 1] == '.' || a[n - 1] == ' ')) --n;
  return n == 0 ? a : a.substr(0, n);
}

std::string RecordLabel(const RecordEntry& entry) {
  if (!entry.label.empty()) return entry.label;
  return entry.IsPair() ? PairLabel(entry.file, entry.file_h2) : entry.file.filename().string();
}

namespace {

// ReadRecord of one file with the entry's options, scaled, with the manifest's component.
GroundMotion ReadComponent(const std::filesystem::path& file, const RecordEntry& entry,
                           const std::string& component) {
  GroundMotion motion = ReadRecord(file, entry.options);
  if (entry.scale != 1.0) {
    for (double& a : motion.acc_mps2) a *= entry.scale;
  }
  if (!component.empty()) motion.component = component;
  return motion;
}

}  // namespace

GroundMotion LoadRecord(const RecordEntry& entry) {
  if (entry.IsPair()) {
    throw InputError("record '" + RecordLabel(entry) +
                     "' is a pair of two horizontal components (h1 " + entry.file.string() +
                     ", h2 " + entry.file_h2.string() + "); this use takes a single record");
  }
  return ReadComponent(entry.file, entry, entry.component);
}

RecordComponents MatchPair(GroundMotion h1, GroundMotion h2) {
  const double dt1 = h1.dt_s;
  const double dt2 = h2.dt_s;
  if (std::abs(dt1 - dt2) > 1e-9 * std::max(dt1, dt2)) {
    throw InputError(fmt::format(
        "{}, {}: the two components of a pair have different time steps ({:g} s and {:g} s); "
        "allowed: two components sampled at one dt (resample one of them outside skewbridge)",
        h1.file, h2.file, dt1, dt2));
  }
  if (!h1.station.empty() && !h2.station.empty() && h1.station != h2.station) {
    throw InputError(fmt::format(
        "{}, {}: the two components of a pair are of different stations ('{}' and '{}' in "
        "their headers); allowed: two horizontal components of one station",
        h1.file, h2.file, h1.station, h2.station));
  }
  RecordComponents out;
  const std::size_t n = std::max(h1.npts(), h2.npts());
  for (std::size_t k = 0; k < 2; ++k) {
    GroundMotion& m = k == 0 ? h1 : h2;
    const GroundMotion& other = k == 0 ? h2 : h1;
    if (m.npts() == n) continue;
    out.padded_samples[k] = n - m.npts();
    m.notes.push_back(fmt::format(
        "{}: padded with {} zero sample(s) at the end to the {} samples of its pair's {} ({})",
        m.file, n - m.npts(), n, k == 0 ? "H2" : "H1", other.file));
    m.acc_mps2.resize(n, 0.0);
  }
  h2.dt_s = h1.dt_s;  // one time grid for both (equal within the check above)
  out.motions.push_back(std::move(h1));
  out.motions.push_back(std::move(h2));
  return out;
}

RecordComponents LoadComponents(const RecordEntry& entry) {
  if (!entry.IsPair()) {
    RecordComponents out;
    out.motions.push_back(LoadRecord(entry));
    return out;
  }
  return MatchPair(ReadComponent(entry.file, entry, entry.component),
                   ReadComponent(entry.file_h2, entry, entry.component_h2));
}

}  // namespace skewbridge::records
