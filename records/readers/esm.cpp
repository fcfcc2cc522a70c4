#include <map>
#include <optional>
#include <string>

#include "records/readers/readers.h"
#include "solver/common/error.h"

namespace skewbridge::records::detail {
namespace {

// "KEY: value" with an upper-case key free of blanks, e.g. "SAMPLING_INTERVAL_S: 0.005000".
std::optional<std::pair<std::string, std::string_view>> HeaderEntry(std::string_view text) {
  const std::size_t colon = text.find(':');
  if (colon == std::string_view::npos || colon == 0) return std::nullopt;
  const std::string_view key = text.substr(0, colon);
  for (char c : key) {
    if (c == ' ' || c == '\t') return std::nullopt;
  }
  return std::make_pair(std::string(key), Trim(text.substr(colon + 1)));
}

}  // namespace

GroundMotion ParseEsm(const std::vector<Line>& lines, std::string_view source,
                      const ReadOptions& options) {
  std::map<std::string, std::pair<std::string_view, long>> header;
  std::size_t first_data = 0;
  for (; first_data < lines.size(); ++first_data) {
    const auto entry = HeaderEntry(lines[first_data].text);
    if (!entry) break;
    header[entry->first] = {entry->second, lines[first_data].number};
  }
  const long header_end = first_data > 0 ? lines[first_data - 1].number : 1;
  const auto field = [&](const std::string& key) -> std::pair<std::string_view, long> {
    const auto it = header.find(key);
    if (it == header.end() || it->second.first.empty()) {
      throw InputError::AtLine(source, header_end, "ESM header has no " + key + " value");
    }
    return it->second;
  };
  const auto [dt_text, dt_line] = field("SAMPLING_INTERVAL_S");
  const auto [npts_text, npts_line] = field("NDATA");
  const auto [units_text, units_line] = field("UNITS");
  const double dt_in_file = ParseNumber(dt_text, source, dt_line);
  const long npts = ParseCount(npts_text, source, npts_line);
  const Units units =
      ResolveUnits(UnitsFromHeader(units_text, source, units_line), options, source, units_line);
  const double dt_s = ResolveDt(dt_in_file, options, source, dt_line);

  std::vector<double> values;
  const long last = ReadValues(lines, first_data, source, values);
  RequireCount(static_cast<std::size_t>(npts), values.size(), source, npts_line, "NDATA");
  GroundMotion motion =
      MakeMotion(source, Format::kEsm, units, dt_s, std::move(values), last ? last : header_end);
  const auto text = [&](const std::string& key) {
    const auto it = header.find(key);
    return it == header.end() ? std::string() : std::string(it->second.first);
  };
  motion.event = text("EVENT_NAME") + " (" + text("EVENT_ID") + ")";
  motion.station = text("NETWORK") + "." + text("STATION_CODE");
  if (const std::string name = text("STATION_NAME"); !name.empty() && name != "None") {
    motion.station += " " + name;
  }
  motion.component = text("STREAM");
  return motion;
}

}  // namespace skewbridge::records::detail
