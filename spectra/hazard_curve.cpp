#include "spectra/hazard_curve.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <utility>

#include "records/readers/text.h"
#include "solver/common/error.h"

namespace skewbridge::spectra {
namespace {

namespace text = records::detail;

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string Lower(std::string_view s) {
  std::string out;
  for (char c : s) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

struct ComponentSpelling {
  std::string_view name;
  HorizontalComponent component;
};

// Canonical names first (ComponentName returns them), then aliases.
constexpr std::array kComponents = {
    ComponentSpelling{"arbitrary", HorizontalComponent::kArbitrary},
    ComponentSpelling{"geometric-mean", HorizontalComponent::kGeometricMean},
    ComponentSpelling{"GMRotI50", HorizontalComponent::kGmRotI50},
    ComponentSpelling{"RotD50", HorizontalComponent::kRotD50},
    ComponentSpelling{"RotD100", HorizontalComponent::kRotD100},
    ComponentSpelling{"one-component", HorizontalComponent::kArbitrary},
    ComponentSpelling{"single", HorizontalComponent::kArbitrary},
    ComponentSpelling{"as-recorded", HorizontalComponent::kArbitrary},
    ComponentSpelling{"geomean", HorizontalComponent::kGeometricMean},
    ComponentSpelling{"gm", HorizontalComponent::kGeometricMean},
    ComponentSpelling{"average-horizontal", HorizontalComponent::kGeometricMean},
};

std::string ReadWhole(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError::AtLine(path.string(), 0, "cannot open the hazard file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError::AtLine(path.string(), 0, "error while reading the hazard file");
  return buffer.str();
}

// The value of `key=` in OpenQuake's header comment: a quoted string ('...' or "...") or a bare
// token up to ',' or '"'.
std::optional<std::string> CommentValue(std::string_view comment, std::string_view key) {
  std::size_t at = 0;
  while ((at = comment.find(key, at)) != std::string_view::npos) {
    const bool starts = at == 0 || !(std::isalnum(static_cast<unsigned char>(comment[at - 1])) ||
                                     comment[at - 1] == '_');
    std::size_t v = at + key.size();
    while (v < comment.size() && comment[v] == ' ') ++v;
    if (!starts || v >= comment.size() || comment[v] != '=') {
      at += key.size();
      continue;
    }
    ++v;
    while (v < comment.size() && comment[v] == ' ') ++v;
    if (v < comment.size() && (comment[v] == '\'' || comment[v] == '"')) {
      const char quote = comment[v];
      const std::size_t end = comment.find(quote, v + 1);
      if (end == std::string_view::npos) return std::nullopt;
      return std::string(comment.substr(v + 1, end - v - 1));
    }
    std::size_t end = v;
    while (end < comment.size() && comment[end] != ',' && comment[end] != '"') ++end;
    return std::string(text::Trim(comment.substr(v, end - v)));
  }
  return std::nullopt;
}

// The comma-separated cells of a CSV line (no quoting: hazard-curve rows hold numbers).
std::vector<std::string_view> CsvCells(std::string_view line) {
  std::vector<std::string_view> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(text::Trim(line.substr(start, comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return cells;
}

// The measure of a file: its own IMT and component reconciled with the options.
IntensityMeasureId ResolveMeasure(std::optional<IntensityMeasureId> in_file, long imt_line,
                                  std::optional<HorizontalComponent> component_in_file,
                                  long component_line, std::optional<double> damping_in_file,
                                  const HazardReadOptions& options, const std::string& path,
                                  std::string_view how_to_name) {
  std::optional<IntensityMeasureId> from_option;
  if (!options.imt.empty()) {
    from_option = ParseImt(options.imt);
    if (!from_option) {
      throw InputError::AtField("--hazard-imt", options.imt,
                                "not an intensity-measure type (allowed: PGA, SA(T) with T in s)");
    }
  }
  if (!in_file && !from_option) {
    throw InputError::AtLine(path, 0,
                             fmt::format("names no intensity measure; {}, or give --hazard-imt "
                                         "(PGA or SA(T))",
                                         how_to_name));
  }
  if (in_file && from_option &&
      (in_file->measure != from_option->measure ||
       std::abs(in_file->period_s - from_option->period_s) > 1e-9 * (1.0 + in_file->period_s))) {
    throw InputError::AtLine(path, imt_line,
                             fmt::format("the file's IMT {} differs from --hazard-imt {}",
                                         in_file->Describe(), from_option->Describe()));
  }
  IntensityMeasureId id = in_file ? *in_file : *from_option;
  if (damping_in_file && options.damping && std::abs(*damping_in_file - *options.damping) > 1e-12) {
    throw InputError::AtLine(path, 0,
                             fmt::format("the file's damping {:g} differs from --hazard-damping "
                                         "{:g}",
                                         *damping_in_file, *options.damping));
  }
  if (damping_in_file) id.damping = *damping_in_file;
  if (options.damping) id.damping = *options.damping;
  if (!(id.damping > 0.0 && id.damping < 1.0)) {
    throw InputError::AtLine(path, 0,
                             fmt::format("damping {:g} is not a ratio in (0, 1)", id.damping));
  }
  if (id.measure == "PGA") id.period_s = 0.0;
  std::optional<HorizontalComponent> from_option_component;
  if (!options.component.empty()) {
    from_option_component = ParseComponent(options.component);
    if (!from_option_component) {
      throw InputError::AtField("--hazard-component", options.component,
                                "unknown component (allowed: " + ComponentChoices() + ")");
    }
  }
  if (component_in_file && from_option_component && *component_in_file != *from_option_component) {
    throw InputError::AtLine(
        path, component_line,
        fmt::format("the file's component {} differs from --hazard-component "
                    "{}",
                    ComponentName(*component_in_file), ComponentName(*from_option_component)));
  }
  if (component_in_file) id.component = *component_in_file;
  if (from_option_component) id.component = *from_option_component;
  return id;
}

// Checks the levels and rates shared by both formats: at least two levels, levels increasing.
void CheckCurve(const HazardCurve& c) {
  if (c.im.size() < 2) {
    throw InputError::AtLine(
        c.path, c.line.empty() ? 0 : c.line.back(),
        fmt::format("{} intensity level(s); a hazard curve needs at least 2", c.im.size()));
  }
}

}  // namespace

std::string_view ComponentName(HorizontalComponent component) {
  for (const ComponentSpelling& s : kComponents) {
    if (s.component == component) return s.name;
  }
  return "unknown";
}

std::optional<HorizontalComponent> ParseComponent(std::string_view text) {
  const std::string lowered = Lower(text::Trim(text));
  for (const ComponentSpelling& s : kComponents) {
    if (Lower(s.name) == lowered) return s.component;
  }
  return std::nullopt;
}

std::string ComponentChoices() {
  std::string out;
  for (const ComponentSpelling& s : kComponents)
    out += (out.empty() ? "" : ", ") + std::string(s.name);
  return out;
}

std::string IntensityMeasureId::Describe() const {
  const std::string comp = component == HorizontalComponent::kUnknown
                               ? "component not stated"
                               : std::string(ComponentName(component)) + " component";
  if (measure == "SA" || measure == "AvgSa") {
    return fmt::format("{}({:.4g} s, {:g} % damping, {})", measure, period_s, 100.0 * damping,
                       comp);
  }
  return fmt::format("{} ({})", measure, comp);
}

std::optional<IntensityMeasureId> ParseImt(std::string_view raw) {
  const std::string t = Lower(text::Trim(raw));
  IntensityMeasureId id;
  if (t == "pga") {
    id.measure = "PGA";
    return id;
  }
  if (t.size() < 5 || t.compare(0, 2, "sa") != 0) return std::nullopt;
  std::string_view rest = text::Trim(std::string_view(t).substr(2));
  if (rest.size() < 3 || rest.front() != '(' || rest.back() != ')') return std::nullopt;
  rest = text::Trim(rest.substr(1, rest.size() - 2));
  const std::optional<double> period = text::TryParseNumber(rest);
  if (!period || !(*period > 0.0)) return std::nullopt;
  id.measure = "SA";
  id.period_s = *period;
  return id;
}

HazardCurve ReadOpenQuakeHazardCsv(const std::filesystem::path& path,
                                   const HazardReadOptions& options) {
  const std::string contents = ReadWhole(path);
  const std::string name = path.string();
  const std::vector<text::Line> lines = text::SplitLines(contents);
  HazardCurve c;
  c.path = name;
  c.format = "openquake-csv";

  // The header comment, the column header, then one row per site; blank lines are skipped.
  std::size_t k = 0;
  auto next = [&]() -> const text::Line* {
    while (k < lines.size() && text::IsBlank(lines[k].text)) ++k;
    return k < lines.size() ? &lines[k++] : nullptr;
  };
  const text::Line* comment = next();
  if (comment == nullptr || text::Trim(comment->text).substr(0, 1) != "#") {
    throw InputError::AtLine(name, comment ? comment->number : 0,
                             "an OpenQuake hazard-curve CSV starts with its header comment "
                             "(#,,,,,\"... investigation_time=..., imt='...'\")");
  }
  const std::optional<std::string> time = CommentValue(comment->text, "investigation_time");
  const std::optional<double> t_yr = time ? text::TryParseNumber(*time) : std::nullopt;
  if (!t_yr || !(*t_yr > 0.0)) {
    throw InputError::AtLine(name, comment->number,
                             "the header comment has no investigation_time > 0 (years): the "
                             "probabilities cannot be turned into annual rates");
  }
  c.investigation_time_yr = *t_yr;
  c.kind = CommentValue(comment->text, "kind").value_or("");
  std::optional<IntensityMeasureId> in_file;
  if (const std::optional<std::string> imt = CommentValue(comment->text, "imt")) {
    in_file = ParseImt(*imt);
    if (!in_file) {
      throw InputError::AtLine(
          name, comment->number,
          fmt::format("imt '{}' is not read (allowed: PGA, SA(T) with T in s)", *imt));
    }
  }
  c.imt = ResolveMeasure(in_file, comment->number, std::nullopt, 0, std::nullopt, options, name,
                         "OpenQuake writes imt='...' in the header comment");

  const text::Line* header = next();
  if (header == nullptr) throw InputError::AtLine(name, 0, "no column header after the comment");
  const std::vector<std::string_view> columns = CsvCells(header->text);
  std::ptrdiff_t lon_col = -1, lat_col = -1;
  std::size_t first_poe = columns.size();
  for (std::size_t j = 0; j < columns.size(); ++j) {
    const std::string col = Lower(columns[j]);
    if (col.rfind("poe-", 0) == 0) {
      first_poe = std::min(first_poe, j);
      const std::optional<double> level = text::TryParseNumber(std::string_view(col).substr(4));
      if (!level || !(*level > 0.0)) {
        throw InputError::AtLine(name, header->number,
                                 fmt::format("column {} '{}': the level after poe- must be a "
                                             "number > 0",
                                             j + 1, columns[j]));
      }
      if (!c.im.empty() && !(*level > c.im.back())) {
        throw InputError::AtLine(name, header->number,
                                 fmt::format("column {} '{}': levels must increase (the one "
                                             "before is {:g})",
                                             j + 1, columns[j], c.im.back()));
      }
      c.im.push_back(*level);
      c.line.push_back(header->number);
      continue;
    }
    if (first_poe < j) {
      throw InputError::AtLine(
          name, header->number,
          fmt::format("column {} '{}' after the poe- columns", j + 1, columns[j]));
    }
    if (col == "lon") {
      lon_col = static_cast<std::ptrdiff_t>(j);
    } else if (col == "lat") {
      lat_col = static_cast<std::ptrdiff_t>(j);
    } else if (col != "depth" && col != "custom_site_id" && col != "site_id") {
      throw InputError::AtLine(name, header->number,
                               fmt::format("column {} '{}' is not a hazard-curve column (allowed: "
                                           "custom_site_id, site_id, lon, lat, depth, then "
                                           "poe-<level>)",
                                           j + 1, columns[j]));
    }
  }
  if (c.im.empty()) {
    throw InputError::AtLine(name, header->number, "no poe-<level> column");
  }

  std::vector<const text::Line*> rows;
  while (const text::Line* row = next()) {
    if (text::Trim(row->text).substr(0, 1) == "#") continue;
    rows.push_back(row);
  }
  c.sites = static_cast<int>(rows.size());
  if (rows.empty()) throw InputError::AtLine(name, header->number, "no site row after the header");
  if (!options.site && rows.size() > 1) {
    throw InputError::AtLine(
        name, rows[1]->number,
        fmt::format("{} sites; choose one with --site N (0 to {})", rows.size(), rows.size() - 1));
  }
  const int site = options.site.value_or(0);
  if (site < 0 || static_cast<std::size_t>(site) >= rows.size()) {
    throw InputError::AtField(
        "--site", std::to_string(site),
        fmt::format("{} holds {} site(s): allowed 0 to {}", name, rows.size(), rows.size() - 1));
  }
  c.site = site;
  const text::Line& row = *rows[static_cast<std::size_t>(site)];
  const std::vector<std::string_view> cells = CsvCells(row.text);
  if (cells.size() != columns.size()) {
    throw InputError::AtLine(
        name, row.number,
        fmt::format("{} cells where the header has {} columns", cells.size(), columns.size()));
  }
  auto number = [&](std::size_t j) {
    const std::optional<double> v = text::TryParseNumber(cells[j]);
    if (!v) {
      throw InputError::AtLine(
          name, row.number,
          fmt::format("column {} ({}): '{}' is not a finite number", j + 1, columns[j], cells[j]));
    }
    return *v;
  };
  if (lon_col >= 0) c.lon_deg = number(static_cast<std::size_t>(lon_col));
  if (lat_col >= 0) c.lat_deg = number(static_cast<std::size_t>(lat_col));
  double previous = 1.0;
  for (std::size_t i = 0; i < c.im.size(); ++i) {
    const std::size_t j = first_poe + i;
    const double poe = number(j);
    if (!(poe >= 0.0 && poe <= 1.0)) {
      throw InputError::AtLine(
          name, row.number,
          fmt::format("column {} ({}): probability {:g} outside [0, 1]", j + 1, columns[j], poe));
    }
    if (poe > previous) {
      throw InputError::AtLine(name, row.number,
                               fmt::format("column {} ({}): probability {:g} rises above the "
                                           "{:g} of the level before",
                                           j + 1, columns[j], poe, previous));
    }
    previous = poe;
    // lambda = -ln(1 - poe) / T, Poisson occurrence in the investigation time.
    c.rate_per_yr.push_back(poe == 1.0 ? kInf : -std::log1p(-poe) / c.investigation_time_yr);
    c.line[i] = row.number;
  }
  CheckCurve(c);
  return c;
}

HazardCurve ReadTwoColumnHazard(const std::filesystem::path& path,
                                const HazardReadOptions& options) {
  const std::string contents = ReadWhole(path);
  const std::string name = path.string();
  HazardCurve c;
  c.path = name;
  c.format = "two-column";
  std::optional<IntensityMeasureId> in_file;
  std::optional<HorizontalComponent> component;
  std::optional<double> damping;
  long imt_line = 0, component_line = 0;
  for (const text::Line& line : text::SplitLines(contents)) {
    const std::string_view t = text::Trim(line.text);
    if (t.empty()) continue;
    if (t.front() == '#') {
      // "# key = value" or "# key: value" for the keys of the measure; other comments are free.
      std::string_view body = text::Trim(t.substr(1));
      const std::size_t sep = body.find_first_of("=:");
      if (sep == std::string_view::npos) continue;
      const std::string key = Lower(text::Trim(body.substr(0, sep)));
      const std::string_view value = text::Trim(body.substr(sep + 1));
      if (key == "imt") {
        in_file = ParseImt(value);
        imt_line = line.number;
        if (!in_file) {
          throw InputError::AtLine(name, line.number,
                                   fmt::format("imt '{}' is not read (allowed: PGA, SA(T) with T "
                                               "in s)",
                                               value));
        }
      } else if (key == "component") {
        component = ParseComponent(value);
        component_line = line.number;
        if (!component) {
          throw InputError::AtLine(
              name, line.number,
              fmt::format("component '{}' unknown (allowed: {})", value, ComponentChoices()));
        }
      } else if (key == "damping") {
        damping = text::TryParseNumber(value);
        if (!damping) {
          throw InputError::AtLine(
              name, line.number,
              fmt::format("damping '{}' is not a number (a ratio, e.g. 0.05)", value));
        }
      }
      continue;
    }
    const std::vector<std::string_view> tokens = text::Tokens(t);
    if (tokens.size() != 2) {
      throw InputError::AtLine(name, line.number,
                               fmt::format("{} value(s); a line holds two: IM [g] and its annual "
                                           "rate of exceedance [1/yr]",
                                           tokens.size()));
    }
    const std::optional<double> x = text::TryParseNumber(tokens[0]);
    const std::optional<double> rate = text::TryParseNumber(tokens[1]);
    if (!x || !(*x > 0.0)) {
      throw InputError::AtLine(name, line.number,
                               fmt::format("IM '{}' is not a finite number > 0", tokens[0]));
    }
    if (!rate || !(*rate >= 0.0)) {
      throw InputError::AtLine(name, line.number,
                               fmt::format("rate '{}' is not a finite number >= 0", tokens[1]));
    }
    if (!c.im.empty() && !(*x > c.im.back())) {
      throw InputError::AtLine(
          name, line.number,
          fmt::format("IM {:g} does not increase (the line before has {:g})", *x, c.im.back()));
    }
    if (!c.rate_per_yr.empty() && *rate > c.rate_per_yr.back()) {
      throw InputError::AtLine(name, line.number,
                               fmt::format("rate {:g} rises above the {:g} of the line before: a "
                                           "rate of exceedance falls as the IM grows",
                                           *rate, c.rate_per_yr.back()));
    }
    c.im.push_back(*x);
    c.rate_per_yr.push_back(*rate);
    c.line.push_back(line.number);
  }
  c.imt = ResolveMeasure(in_file, imt_line, component, component_line, damping, options, name,
                         "add a line '# imt = SA(T)' (or PGA)");
  CheckCurve(c);
  return c;
}

HazardCurve ReadHazardCurve(const std::filesystem::path& path, const HazardReadOptions& options) {
  const std::string contents = ReadWhole(path);
  bool openquake = false;
  for (const text::Line& line : text::SplitLines(contents)) {
    const std::string_view t = text::Trim(line.text);
    if (t.empty()) continue;
    if (t.rfind("#,", 0) == 0 || (t.front() == '#' && t.find("investigation_time") != t.npos)) {
      openquake = true;
      break;
    }
    if (t.front() == '#') continue;
    const std::string lowered = Lower(t.substr(0, 16));
    openquake = lowered.rfind("lon,", 0) == 0 || lowered.rfind("custom_site_id,", 0) == 0;
    break;
  }
  return openquake ? ReadOpenQuakeHazardCsv(path, options) : ReadTwoColumnHazard(path, options);
}

}  // namespace skewbridge::spectra
