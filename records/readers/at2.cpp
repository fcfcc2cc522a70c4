#include <optional>
#include <string>

#include "records/readers/readers.h"
#include "solver/common/error.h"

namespace skewbridge::records::detail {
namespace {

// The PEER header puts the NPTS/DT line fourth; free-text variants move it a few lines down.
constexpr std::size_t kMaxHeaderLines = 12;

std::vector<std::string> SplitCommas(std::string_view text) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= text.size(); ++i) {
    if (i == text.size() || text[i] == ',') {
      fields.emplace_back(Trim(text.substr(start, i - start)));
      start = i + 1;
    }
  }
  return fields;
}

}  // namespace

GroundMotion ParseAt2(const std::vector<Line>& lines, std::string_view source,
                      const ReadOptions& options) {
  std::size_t npts_index = lines.size();
  for (std::size_t i = 0; i < lines.size() && i < kMaxHeaderLines; ++i) {
    if (FindNoCase(lines[i].text, "NPTS") != std::string_view::npos) {
      npts_index = i;
      break;
    }
  }
  if (npts_index == lines.size()) {
    throw InputError::AtLine(source, lines.empty() ? 1 : lines.front().number,
                             "no NPTS/DT line in the first " + std::to_string(kMaxHeaderLines) +
                                 " lines of the AT2 header");
  }
  const Line& header = lines[npts_index];
  std::optional<std::string_view> npts_token = TokenAfter(header.text, "NPTS");
  std::optional<std::string_view> dt_token = TokenAfter(header.text, "DT");
  // NGA-West1 style: "4096    0.0100    NPTS, DT" puts the values before the keywords.
  const std::vector<std::string_view> tokens = Tokens(header.text);
  if (tokens.size() >= 3 && IsNumericLine(tokens[0]) && IsNumericLine(tokens[1])) {
    npts_token = tokens[0];
    dt_token = tokens[1];
  }
  if (!npts_token || !dt_token) {
    throw InputError::AtLine(source, header.number,
                             "expected NPTS and DT on the AT2 header line (e.g. 'NPTS=  5372, "
                             "DT= .0100 SEC')");
  }
  const long npts = ParseCount(*npts_token, source, header.number);
  const double dt_in_file = ParseNumber(*dt_token, source, header.number);

  std::optional<Units> in_file;
  long units_line = header.number;
  for (std::size_t i = 0; i < npts_index; ++i) {
    for (std::string_view key : {"UNITS OF", "UNITS ARE", "UNITS:"}) {
      if (const std::optional<std::string_view> spelling = TokenAfter(lines[i].text, key)) {
        in_file = UnitsFromHeader(*spelling, source, lines[i].number);
        units_line = lines[i].number;
        break;
      }
    }
    if (in_file) break;
  }
  const Units units = ResolveUnits(in_file, options, source, units_line);
  const double dt_s = ResolveDt(dt_in_file, options, source, header.number);

  std::vector<double> values;
  const long last = ReadValues(lines, npts_index + 1, source, values);
  RequireCount(static_cast<std::size_t>(npts), values.size(), source, header.number);
  GroundMotion motion =
      MakeMotion(source, Format::kAt2, units, dt_s, std::move(values), last ? last : header.number);
  if (lines.size() > 1 && npts_index > 1) {
    // "Event, date, station, component" (NGA-West2) or "EVENT DATE, STATION, COMPONENT".
    const std::vector<std::string> fields = SplitCommas(lines[1].text);
    if (fields.size() >= 3) {
      motion.event = fields.front();
      motion.station = fields[fields.size() - 2];
      motion.component = fields.back();
    } else {
      motion.event = std::string(Trim(lines[1].text));
    }
  }
  return motion;
}

}  // namespace skewbridge::records::detail
