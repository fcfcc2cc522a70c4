#include "records/record_set.h"

#include <fmt/format.h>
#include <toml++/toml.h>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "records/readers/text.h"
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
  FolderSetSource source{folder_at, Where(manifest, LineOf(*pattern_node)), "", ""};
  FolderPairs pairs;
  if (const toml::node* node = root.get("pairs")) {
    source.pairs_at = Where(manifest, LineOf(*node));
    if (const std::optional<bool> flag = node->value_exact<bool>()) {
      pairs.by_name = *flag;
    } else if (const std::optional<std::string> table = node->value_exact<std::string>();
               table && !table->empty()) {
      pairs.table = manifest.parent_path() / folder / *table;
    } else {
      throw InputError::AtField(source.pairs_at, "pairs",
                                "must be true (pairs by file name) or the name of a CSV table of "
                                "the folder (h1_file, h2_file, pair)");
    }
  }
  RecordSet folder_set =
      MakeFolderSet(manifest.parent_path() / folder, pattern, defaults, source, pairs);
  set.records = std::move(folder_set.records);
  set.pairs_table = std::move(folder_set.pairs_table);
}

// The fields of one CSV line (RFC 4180 within a line: commas separate, a field in double quotes
// may hold commas and "" for a quote), each trimmed of blanks; nullopt for an unclosed quote.
std::optional<std::vector<std::string>> CsvFields(std::string_view line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        out.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        out.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  if (quoted) return std::nullopt;
  for (std::string& field : out) field = std::string(detail::Trim(field));
  return out;
}

// One pair of a folder set: its files and the label its table gives ("" for the default).
struct FolderPair {
  std::filesystem::path h1, h2;
  std::string label;
};

// The pairs of `files` (sorted by name) by PairsByName: each file must pair with exactly one
// other; H1 is the first of the two in byte order.
std::vector<FolderPair> PairFilesByName(const std::vector<std::filesystem::path>& files,
                                        std::string_view pattern, const FolderSetSource& source) {
  const std::string key = source.key_prefix + "pairs";
  std::vector<std::vector<std::size_t>> partners(files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    for (std::size_t j = i + 1; j < files.size(); ++j) {
      if (PairsByName(files[i].filename().string(), files[j].filename().string())) {
        partners[i].push_back(j);
        partners[j].push_back(i);
      }
    }
  }
  std::vector<FolderPair> out;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const std::string name = files[i].filename().string();
    if (partners[i].empty()) {
      throw InputError::AtField(
          source.pairs_at, key,
          "unpaired file " + name + " of " + files[i].parent_path().string() +
              ": no other file matching '" + std::string(pattern) +
              "' differs from its name only in the component (one run without '_', '-', '.' or "
              "blank, as 180 and 270, EW and NS); allowed: two files per station, or pairs = "
              "\"TABLE.csv\" naming them");
    }
    if (partners[i].size() > 1) {
      throw InputError::AtField(
          source.pairs_at, key,
          "file " + name + " pairs by name with both " + files[partners[i][0]].filename().string() +
              " and " + files[partners[i][1]].filename().string() +
              " (a third component, e.g. the vertical?); allowed: a pattern that leaves one "
              "out, or pairs = \"TABLE.csv\" naming the pairs");
    }
    if (partners[i][0] > i) out.push_back({files[i], files[partners[i][0]], ""});
  }
  return out;
}

// The pairs a CSV table names (columns h1_file and h2_file, optionally pair for the label;
// others ignored), in row order: the rows whose two files match the pattern. Every matching
// file must be in one such row.
std::vector<FolderPair> PairFilesByTable(const std::filesystem::path& folder,
                                         const std::vector<std::filesystem::path>& files,
                                         std::string_view pattern, const FolderPairs& pairs,
                                         const FolderSetSource& source) {
  const std::string key = source.key_prefix + "pairs";
  const std::string table = pairs.table.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(pairs.table, ec)) {
    throw InputError::AtField(source.pairs_at, key, "not a file: " + table);
  }
  std::ifstream in(pairs.table, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw InputError::AtField(source.pairs_at, key, "cannot read " + table);
  std::string contents = text.str();
  if (contents.rfind("\xEF\xBB\xBF", 0) == 0) contents.erase(0, 3);  // a UTF-8 byte-order mark
  const std::vector<detail::Line> lines = detail::SplitLines(contents);
  std::size_t k = 0;
  while (k < lines.size() && detail::IsBlank(lines[k].text)) ++k;
  if (k == lines.size()) {
    throw InputError::AtLine(table, 0,
                             "empty; allowed: a header row naming h1_file and h2_file "
                             "(and pair for the label), then one row per pair");
  }
  const long header_line = lines[k].number;
  const std::optional<std::vector<std::string>> header = CsvFields(lines[k++].text);
  std::map<std::string, std::size_t> column;
  for (std::size_t c = 0; header && c < header->size(); ++c) column.emplace((*header)[c], c);
  for (const char* name : {"h1_file", "h2_file"}) {
    if (!column.contains(name)) {
      throw InputError::AtLine(table, header_line,
                               std::string("no column ") + name +
                                   " in the header; allowed: a header row naming h1_file and "
                                   "h2_file (and pair for the label), then one row per pair");
    }
  }
  const std::set<std::string> matching = [&files] {
    std::set<std::string> names;
    for (const std::filesystem::path& f : files) names.insert(f.filename().string());
    return names;
  }();
  std::map<std::string, long> row_of;  // each file's row, to refuse a file in two pairs
  std::vector<FolderPair> out;
  for (; k < lines.size(); ++k) {
    const detail::Line& line = lines[k];
    if (detail::IsBlank(line.text)) continue;
    const std::optional<std::vector<std::string>> fields = CsvFields(line.text);
    if (!fields || fields->size() != header->size()) {
      throw InputError::AtLine(
          table, line.number,
          fields ? fmt::format("{} fields, the header has {}", fields->size(), header->size())
                 : std::string("an unclosed '\"'"));
    }
    FolderPair pair;
    std::array<std::string, 2> names;
    for (int c = 0; c < 2; ++c) {
      const char* name = c == 0 ? "h1_file" : "h2_file";
      names[c] = (*fields)[column.at(name)];
      if (names[c].empty() || names[c].find('/') != std::string::npos ||
          names[c].find('\\') != std::string::npos) {
        throw InputError::AtLine(table, line.number,
                                 std::string(name) + ": '" + names[c] +
                                     "' is not a file name (allowed: the name of a file of " +
                                     folder.string() + ", no folder)");
      }
    }
    const bool m1 = GlobMatch(pattern, names[0]);
    const bool m2 = GlobMatch(pattern, names[1]);
    if (!m1 && !m2) continue;  // a pair the pattern leaves out
    if (m1 != m2) {
      throw InputError::AtLine(
          table, line.number,
          fmt::format("{} '{}' matches pattern '{}' and {} '{}' does not; allowed: a pattern that "
                      "takes both files of a pair or neither",
                      m1 ? "h1_file" : "h2_file", m1 ? names[0] : names[1], pattern,
                      m1 ? "h2_file" : "h1_file", m1 ? names[1] : names[0]));
    }
    if (names[0] == names[1]) {
      throw InputError::AtLine(table, line.number,
                               "h2_file is the file of h1_file; a pair has two files, one per "
                               "component");
    }
    for (const std::string& name : names) {
      if (!matching.contains(name)) {
        throw InputError::AtLine(
            table, line.number,
            "no file " + name + " in " + folder.string() + " (allowed: files of the folder)");
      }
      if (const auto [it, fresh] = row_of.emplace(name, line.number); !fresh) {
        throw InputError::AtLine(table, line.number,
                                 name + " is also a component of the pair of line " +
                                     std::to_string(it->second) + "; a file is in one pair");
      }
    }
    pair.h1 = folder / names[0];
    pair.h2 = folder / names[1];
    if (const auto it = column.find("pair"); it != column.end()) pair.label = (*fields)[it->second];
    out.push_back(std::move(pair));
  }
  for (const std::filesystem::path& f : files) {
    const std::string name = f.filename().string();
    if (!row_of.contains(name)) {
      throw InputError::AtField(source.pairs_at, key,
                                "unpaired file " + name + " of " + folder.string() +
                                    ": it matches pattern '" + std::string(pattern) +
                                    "' and no row of " + table +
                                    " names it; allowed: every matching file in one row, or a "
                                    "pattern that leaves it out");
    }
  }
  return out;
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
                        const RecordEntry& defaults, const FolderSetSource& source,
                        const FolderPairs& pairs) {
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
  if (!pairs.Any()) {
    for (const std::filesystem::path& file : files) {
      RecordEntry entry = defaults;
      entry.file = file;
      set.records.push_back(std::move(entry));
    }
    return set;
  }
  if (!pairs.table.empty()) {
    // The table is never a record, whatever the pattern.
    std::error_code same;
    std::erase_if(files, [&pairs, &same](const std::filesystem::path& f) {
      return std::filesystem::equivalent(f, pairs.table, same);
    });
    set.pairs_table = pairs.table;
  }
  const std::vector<FolderPair> found =
      pairs.table.empty() ? PairFilesByName(files, pattern, source)
                          : PairFilesByTable(folder, files, pattern, pairs, source);
  if (found.empty()) {
    throw InputError::AtField(
        source.pattern_at, pattern_key,
        "no pair of files matching '" + std::string(pattern) + "' in " + folder.string());
  }
  std::map<std::string, std::filesystem::path> seen;  // label -> H1, for duplicates
  for (const FolderPair& pair : found) {
    RecordEntry entry = defaults;
    entry.file = pair.h1;
    entry.file_h2 = pair.h2;
    entry.label = pair.label;
    const std::string label = RecordLabel(entry);
    if (const auto [it, fresh] = seen.emplace(label, pair.h1); !fresh) {
      throw InputError::AtField(source.pairs_at, source.key_prefix + "pairs",
                                "two pairs of one label '" + label + "' (H1 " +
                                    it->second.filename().string() + " and " +
                                    pair.h1.filename().string() +
                                    "); give each pair its own label (the pair column of a table)");
    }
    set.records.push_back(std::move(entry));
  }
  return set;
}

bool PairsByName(std::string_view a, std::string_view b) {
  std::size_t p = 0;
  while (p < a.size() && p < b.size() && a[p] == b[p]) ++p;
  std::size_t s = 0;
  while (s < a.size() - p && s < b.size() - p && a[a.size() - 1 - s] == b[b.size() - 1 - s]) ++s;
  const std::string_view ma = a.substr(p, a.size() - p - s);
  const std::string_view mb = b.substr(p, b.size() - p - s);
  const auto plain = [](std::string_view run) {
    return !run.empty() && run.find_first_of("_-. \t") == std::string_view::npos;
  };
  return plain(ma) && plain(mb);
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
      "name", "folder", "pattern", "scale",     "units",
      "dt",   "format", "channel", "max_pga_g", "pairs"};
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
                         "units, dt, format, channel, max_pga_g, pairs; [[record]] tables are "
                         "the other form)"
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
