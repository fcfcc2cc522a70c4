#include <string>

#include "records/readers/readers.h"
#include "solver/common/error.h"

namespace skewbridge::records::detail {

GroundMotion ParseCsmip(const std::vector<Line>& lines, std::string_view source,
                        const ReadOptions& options) {
  if (options.channel < 1) {
    throw InputError::AtLine(source, 0, "channel must be >= 1");
  }
  // The k-th "N POINTS OF ACCEL DATA EQUALLY SPACED AT dt SEC. (UNITS: ...)" line is channel k.
  int seen = 0;
  std::size_t block = lines.size();
  int channels = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (FindNoCase(lines[i].text, "POINTS OF ACCEL DATA") != std::string_view::npos) {
      ++channels;
      if (++seen == options.channel) block = i;
    }
  }
  if (block == lines.size()) {
    throw InputError::AtLine(source, lines.empty() ? 1 : lines.back().number,
                             "CSMIP V2 file has " + std::to_string(channels) +
                                 " acceleration block(s); channel " +
                                 std::to_string(options.channel) + " not found");
  }
  const Line& header = lines[block];
  const std::vector<std::string_view> tokens = Tokens(header.text);
  const long npts = ParseCount(tokens.front(), source, header.number);
  const std::optional<std::string_view> dt_token = TokenAfter(header.text, "SPACED AT");
  if (!dt_token) {
    throw InputError::AtLine(source, header.number, "expected 'EQUALLY SPACED AT dt SEC.'");
  }
  const double dt_in_file = ParseNumber(*dt_token, source, header.number);
  const std::optional<std::string_view> units_text = TokenAfter(header.text, "UNITS");
  const Units units = ResolveUnits(
      units_text ? std::optional<Units>(UnitsFromHeader(*units_text, source, header.number))
                 : std::nullopt,
      options, source, header.number);
  const double dt_s = ResolveDt(dt_in_file, options, source, header.number);

  // The acceleration block runs up to the velocity block (or the channel's end marker).
  std::vector<double> values;
  long last = header.number;
  for (std::size_t k = block + 1; k < lines.size(); ++k) {
    const std::string_view text = lines[k].text;
    if (FindNoCase(text, "POINTS OF") != std::string_view::npos ||
        StartsWithNoCase(Trim(text), "/&")) {
      break;
    }
    if (IsBlank(text)) continue;
    AppendNumbers(lines[k], source, values);
    last = lines[k].number;
  }
  RequireCount(static_cast<std::size_t>(npts), values.size(), source, header.number);
  GroundMotion motion = MakeMotion(source, Format::kCsmip, units, dt_s, std::move(values), last);
  // Channel header: line 3 names the event, line 7 the station, line 8 the channel.
  std::size_t start = 0;
  int found = 0;
  for (std::size_t i = 0; i < block; ++i) {
    if (StartsWithNoCase(Trim(lines[i].text), "CORRECTED ACCELEROGRAM")) {
      start = i;
      ++found;
    }
  }
  if (found > 0 && start + 7 < lines.size()) {
    motion.event = std::string(Trim(lines[start + 2].text));
    motion.station = std::string(Trim(lines[start + 6].text));
    motion.component = std::string(Trim(lines[start + 7].text));
  }
  return motion;
}

}  // namespace skewbridge::records::detail
