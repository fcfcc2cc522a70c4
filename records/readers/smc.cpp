#include <cmath>
#include <string>

#include "records/readers/readers.h"
#include "solver/common/error.h"

namespace skewbridge::records::detail {
namespace {

// Layout of the USGS SMC format [USGS Open-File Report, SMC format description].
constexpr std::size_t kTextLines = 11;
constexpr std::size_t kIntegerLines = 6;  // 48 integers, 8I10
constexpr std::size_t kRealLines = 10;    // 50 reals, 5E15.7
constexpr std::size_t kCommentCountIndex = 15;
constexpr std::size_t kNptsIndex = 16;
constexpr std::size_t kSamplesPerSecondIndex = 1;

}  // namespace

GroundMotion ParseSmc(const std::vector<Line>& lines, std::string_view source,
                      const ReadOptions& options) {
  const std::size_t header_lines = kTextLines + kIntegerLines + kRealLines;
  if (lines.size() < header_lines) {
    throw InputError::AtLine(
        source, lines.empty() ? 1 : lines.back().number,
        "SMC file ends inside its " + std::to_string(header_lines) + "-line header");
  }
  const std::string_view kind = lines[0].text;
  if (FindNoCase(kind, "ACCELEROGRAM") == std::string_view::npos) {
    throw InputError::AtLine(source, lines[0].number,
                             "SMC file is not an accelerogram (first line: '" +
                                 std::string(Trim(kind).substr(0, 40)) + "')");
  }
  std::vector<double> integers;
  for (std::size_t i = kTextLines; i < kTextLines + kIntegerLines; ++i) {
    AppendNumbers(lines[i], source, integers);
  }
  std::vector<double> reals;
  for (std::size_t i = kTextLines + kIntegerLines; i < header_lines; ++i) {
    AppendNumbers(lines[i], source, reals);
  }
  const long int_line = lines[kTextLines].number;
  const long real_line = lines[kTextLines + kIntegerLines].number;
  if (integers.size() <= kNptsIndex || reals.size() <= kSamplesPerSecondIndex) {
    throw InputError::AtLine(source, int_line, "SMC integer or real header is too short");
  }
  const double npts_value = integers[kNptsIndex];
  if (npts_value < 0.0 || npts_value != std::floor(npts_value) || npts_value > 1e12) {
    throw InputError::AtLine(source, int_line, "SMC integer #17 (NPTS) is not a count");
  }
  const double sps = reals[kSamplesPerSecondIndex];
  if (!(sps > 0.0)) {
    throw InputError::AtLine(source, real_line, "SMC real #2 (samples per second) must be > 0");
  }
  const Units units = ResolveUnits(Units::kCentimetresPerSecond2, options, source, 1);
  const double dt_s = ResolveDt(1.0 / sps, options, source, real_line);

  std::size_t first = header_lines;
  while (first < lines.size() && StartsWithNoCase(Trim(lines[first].text), "|")) ++first;
  const double comments = integers[kCommentCountIndex];
  if (comments >= 0.0 && static_cast<double>(first - header_lines) != comments) {
    throw InputError::AtLine(source, int_line,
                             "SMC integer #16 announces " + std::to_string(comments) +
                                 " comment lines but " + std::to_string(first - header_lines) +
                                 " follow");
  }
  std::vector<double> values;
  const long last = ReadValues(lines, first, source, values);
  RequireCount(static_cast<std::size_t>(npts_value), values.size(), source, int_line);
  GroundMotion motion =
      MakeMotion(source, Format::kSmc, units, dt_s, std::move(values), last ? last : real_line);
  motion.event = std::string(Trim(lines[3].text));
  const std::string_view station_line = lines[5].text;
  if (const std::size_t at = FindNoCase(station_line, "station ="); at != std::string_view::npos) {
    const std::size_t comp = FindNoCase(station_line, "component=");
    motion.station = std::string(Trim(station_line.substr(
        at + 9, comp == std::string_view::npos ? std::string_view::npos : comp - at - 9)));
    if (comp != std::string_view::npos) {
      motion.component = std::string(Trim(station_line.substr(comp + 10)));
    }
  }
  return motion;
}

}  // namespace skewbridge::records::detail
