#include <cctype>
#include <string>

#include "records/readers/readers.h"
#include "solver/common/error.h"

namespace skewbridge::records::detail {
namespace {

bool StartsLikeNumber(std::string_view text) {
  const std::string_view t = Trim(text);
  return !t.empty() && (std::isdigit(static_cast<unsigned char>(t.front())) || t.front() == '-' ||
                        t.front() == '+' || t.front() == '.');
}

// The value of a "Key : value" header line whose key starts with `key`.
std::optional<std::pair<std::string_view, long>> Value(const std::vector<Line>& lines,
                                                       std::size_t end, std::string_view key) {
  for (std::size_t i = 0; i < end; ++i) {
    if (StartsWithNoCase(Trim(lines[i].text), key)) {
      const std::size_t colon = lines[i].text.find(':');
      if (colon == std::string_view::npos) return std::nullopt;
      return std::make_pair(Trim(lines[i].text.substr(colon + 1)), lines[i].number);
    }
  }
  return std::nullopt;
}

}  // namespace

GroundMotion ParseSmtk(const std::vector<Line>& lines, std::string_view source,
                       const ReadOptions& options) {
  std::size_t first = 0;
  while (first < lines.size() && !StartsLikeNumber(lines[first].text)) ++first;
  const long header_end = first > 0 ? lines[first - 1].number : 1;
  const auto dt = Value(lines, first, "Time Increment");
  const auto npts = Value(lines, first, "Number of Data");
  if (!dt || !npts) {
    throw InputError::AtLine(source, header_end,
                             "smtk header needs 'Time Increment (s) :' and 'Number of Data :'");
  }
  std::optional<Units> in_file;
  long units_line = header_end;
  for (std::size_t i = 0; i < first; ++i) {
    if (const auto spelling = TokenAfter(lines[i].text, "time series in")) {
      in_file = UnitsFromHeader(*spelling, source, lines[i].number);
      units_line = lines[i].number;
    }
  }
  const Units units = ResolveUnits(in_file, options, source, units_line);
  const double dt_s =
      ResolveDt(ParseNumber(dt->first, source, dt->second), options, source, dt->second);
  const long declared = ParseCount(npts->first, source, npts->second);
  std::vector<double> values;
  const long last = ReadValues(lines, first, source, values);
  RequireCount(static_cast<std::size_t>(declared), values.size(), source, npts->second,
               "Number of Data");
  GroundMotion motion =
      MakeMotion(source, Format::kSmtk, units, dt_s, std::move(values), last ? last : header_end);
  if (const auto event = Value(lines, first, "Event Date")) motion.event = event->first;
  if (const auto station = Value(lines, first, "Station Code")) motion.station = station->first;
  if (const auto orientation = Value(lines, first, "Orientation")) {
    motion.component = orientation->first;
  }
  return motion;
}

}  // namespace skewbridge::records::detail
