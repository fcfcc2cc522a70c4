#include <string>

#include "records/readers/readers.h"
#include "solver/common/error.h"

namespace skewbridge::records::detail {
namespace {

// Real-header value #62 is the sampling interval in ms [COSMOS strong-motion data format v1.20].
constexpr std::size_t kDtRealIndex = 61;

const Line& At(const std::vector<Line>& lines, std::size_t i, std::string_view source,
               std::string_view expected) {
  if (i >= lines.size()) {
    throw InputError::AtLine(source, lines.empty() ? 1 : lines.back().number,
                             "COSMOS file ends before " + std::string(expected));
  }
  return lines[i];
}

// "N <what> ... follow on M lines": the leading count N and the count before "lines".
std::pair<long, long> CountAndLines(const Line& line, std::string_view source) {
  const std::vector<std::string_view> tokens = Tokens(line.text);
  long lines_count = -1;
  for (std::size_t i = 1; i < tokens.size(); ++i) {
    if (StartsWithNoCase(tokens[i], "line") && IsNumericLine(tokens[i - 1])) {
      lines_count = ParseCount(tokens[i - 1], source, line.number);
    }
  }
  if (tokens.empty() || lines_count < 0) {
    throw InputError::AtLine(source, line.number,
                             "expected 'N ... values follow on M lines' in the COSMOS header");
  }
  return {ParseCount(tokens.front(), source, line.number), lines_count};
}

// A line count read from the header, checked against the file so that offsets cannot overflow.
std::size_t Bounded(long count, const std::vector<Line>& lines, std::string_view source,
                    long line) {
  if (static_cast<std::size_t>(count) > lines.size()) {
    throw InputError::AtLine(source, line,
                             "header announces " + std::to_string(count) +
                                 " lines but the file has only " + std::to_string(lines.size()));
  }
  return static_cast<std::size_t>(count);
}

}  // namespace

GroundMotion ParseCosmos(const std::vector<Line>& lines, std::string_view source,
                         const ReadOptions& options) {
  const Line& first = At(lines, 0, source, "its first line");
  const std::optional<std::string_view> text_count = TokenAfter(first.text, "with");
  if (!text_count) {
    throw InputError::AtLine(source, first.number,
                             "expected '(Format v01.20 with 13 text lines)' on the first line");
  }
  std::size_t i =
      Bounded(ParseCount(*text_count, source, first.number), lines, source, first.number);
  const auto [n_int, int_lines] = CountAndLines(At(lines, i, source, "the integer header"), source);
  (void)n_int;
  i += 1 + Bounded(int_lines, lines, source, lines[i].number);
  const Line& real_header = At(lines, i, source, "the real header");
  const auto [n_real, real_lines] = CountAndLines(real_header, source);
  std::vector<double> reals;
  Bounded(real_lines, lines, source, real_header.number);
  for (long k = 0; k < real_lines; ++k) {
    AppendNumbers(At(lines, i + 1 + static_cast<std::size_t>(k), source, "the real values"), source,
                  reals);
  }
  if (reals.size() != static_cast<std::size_t>(n_real) || reals.size() <= kDtRealIndex) {
    throw InputError::AtLine(source, real_header.number,
                             "the real header declares " + std::to_string(n_real) +
                                 " values but holds " + std::to_string(reals.size()) +
                                 " (need at least 62)");
  }
  const double dt_in_file = reals[kDtRealIndex] / 1000.0;
  i += 1 + static_cast<std::size_t>(real_lines);
  const Line& comments = At(lines, i, source, "the comment count");
  const std::vector<std::string_view> comment_tokens = Tokens(comments.text);
  if (comment_tokens.empty()) {
    throw InputError::AtLine(source, comments.number, "expected 'N Comment line(s) follow'");
  }
  i += 1 + Bounded(ParseCount(comment_tokens.front(), source, comments.number), lines, source,
                   comments.number);
  const Line& data_header = At(lines, i, source, "the data header");
  const std::vector<std::string_view> tokens = Tokens(data_header.text);
  if (tokens.size() < 2 || !StartsWithNoCase(tokens[1], "acceleration")) {
    throw InputError::AtLine(source, data_header.number,
                             "expected 'N acceleration pts, ..., units=...' (is this an "
                             "acceleration file?)");
  }
  const long npts = ParseCount(tokens.front(), source, data_header.number);
  const std::optional<std::string_view> units_text = TokenAfter(data_header.text, "units");
  const Units units = ResolveUnits(
      units_text ? std::optional<Units>(UnitsFromHeader(*units_text, source, data_header.number))
                 : std::nullopt,
      options, source, data_header.number);
  const double dt_s = ResolveDt(dt_in_file, options, source, real_header.number);

  std::vector<double> values;
  long last = data_header.number;
  std::string component;
  for (std::size_t k = i + 1; k < lines.size(); ++k) {
    if (StartsWithNoCase(Trim(lines[k].text), "End-of-data")) {
      if (const auto chan = TokenAfter(lines[k].text, "for Chan")) component = std::string(*chan);
      break;
    }
    if (IsBlank(lines[k].text)) continue;
    AppendNumbers(lines[k], source, values);
    last = lines[k].number;
  }
  RequireCount(static_cast<std::size_t>(npts), values.size(), source, data_header.number);
  GroundMotion motion = MakeMotion(source, Format::kCosmos, units, dt_s, std::move(values), last);
  if (lines.size() > 4) {
    motion.event = std::string(Trim(lines[1].text));
    motion.station = std::string(Trim(lines[4].text));
  }
  motion.component = component;
  return motion;
}

}  // namespace skewbridge::records::detail
