#include <algorithm>
#include <string>

#include "records/readers/readers.h"
#include "solver/common/error.h"

namespace skewbridge::records::detail {

GroundMotion ParseItsak(const std::vector<Line>& lines, std::string_view source,
                        const ReadOptions& options) {
  if (lines.size() < 2) {
    throw InputError::AtLine(source, lines.empty() ? 1 : lines.back().number,
                             "ITSAK file ends inside its 2-line header");
  }
  const Line& title = lines[0];
  const std::vector<std::string_view> title_tokens = Tokens(title.text);
  if (title_tokens.size() < 2 || !StartsWithNoCase(title_tokens.back(), "Values")) {
    throw InputError::AtLine(source, title.number,
                             "expected the ITSAK title line 'NAME STATION N Values'");
  }
  const long npts = ParseCount(title_tokens[title_tokens.size() - 2], source, title.number);
  const Line& format_line = lines[1];
  const std::vector<std::string_view> format_tokens = Tokens(format_line.text);
  if (format_tokens.size() < 2 || format_tokens.front().empty() ||
      format_tokens.front().front() != '(') {
    throw InputError::AtLine(source, format_line.number,
                             "expected the ITSAK format line '(8F15.0)  dt'");
  }
  const double dt_in_file = ParseNumber(format_tokens.back(), source, format_line.number);
  const Units units = ResolveUnits(std::nullopt, options, source, title.number);
  const double dt_s = ResolveDt(dt_in_file, options, source, format_line.number);

  std::vector<double> values;
  std::vector<long> line_of;
  for (std::size_t i = 2; i < lines.size(); ++i) {
    AppendNumbers(lines[i], source, values);
    line_of.resize(values.size(), lines[i].number);
  }
  const auto declared = static_cast<std::size_t>(npts);
  if (values.size() < declared) {
    RequireCount(declared, values.size(), source, title.number, "the title's value count");
  }
  // The declared count is authoritative. What follows it is the zero padding of the last
  // line; ITSAK files are also seen with a few genuine samples before that padding (A299_T: one
  // sample, then nine zeros). Those are dropped with a note only when they are fewer than one
  // line of the 8-value format and exact zero padding follows them; anything else means the
  // count and the data disagree.
  constexpr std::size_t kValuesPerLine = 8;
  std::size_t padding_start = values.size();
  while (padding_start > declared && values[padding_start - 1] == 0.0) --padding_start;
  const std::size_t extra = padding_start - std::min(padding_start, declared);
  if (extra > 0 && (extra >= kValuesPerLine || padding_start == values.size())) {
    throw InputError::AtLine(source, line_of[declared],
                             "value " + std::to_string(declared + 1) +
                                 " lies beyond the declared " + std::to_string(declared) +
                                 " values and is not zero padding");
  }
  std::string note;
  if (extra > 0) {
    // Appending (not "literal" + string) avoids g++ 12's false -Wrestrict warning.
    note = source;
    note += ':';
    note += std::to_string(line_of[declared]);
    note += ": dropped ";
    note += std::to_string(extra);
    note += " non-zero value(s) beyond the declared ";
    note += std::to_string(declared);
    note += " (the header's count is authoritative)";
  }
  values.resize(declared);
  GroundMotion motion = MakeMotion(source, Format::kItsak, units, dt_s, std::move(values),
                                   line_of.empty() ? format_line.number : line_of.back());
  if (!note.empty()) motion.notes.push_back(note);
  motion.component = std::string(title_tokens.front());
  std::string station;
  for (std::size_t i = 1; i + 2 < title_tokens.size(); ++i) {
    if (!station.empty()) station += ' ';
    station += title_tokens[i];
  }
  motion.station = station;
  return motion;
}

}  // namespace skewbridge::records::detail
