#include <cmath>
#include <string>

#include <fmt/format.h>

#include "records/readers/readers.h"
#include "solver/common/error.h"

namespace skewbridge::records::detail {

long ReadValues(const std::vector<Line>& lines, std::size_t first, std::string_view source,
                std::vector<double>& out) {
  long last = 0;
  for (std::size_t i = first; i < lines.size(); ++i) {
    if (IsBlank(lines[i].text)) continue;
    AppendNumbers(lines[i], source, out);
    last = lines[i].number;
  }
  return last;
}

void RequireCount(std::size_t declared, std::size_t found, std::string_view source,
                  long header_line, std::string_view what) {
  if (declared != found) {
    throw InputError::AtLine(source, header_line,
                             "header declares " + std::string(what) + " = " +
                                 std::to_string(declared) + " but the file holds " +
                                 std::to_string(found) + " values");
  }
}

GroundMotion ParsePlainText(const std::vector<Line>& lines, std::string_view source,
                            const ReadOptions& options) {
  const long first_line = lines.empty() ? 1 : lines.front().number;
  const Units units = ResolveUnits(std::nullopt, options, source, 0);
  const double dt_s = ResolveDt(std::nullopt, options, source, 0);
  std::vector<double> values;
  const long last = ReadValues(lines, 0, source, values);
  return MakeMotion(source, Format::kPlainText, units, dt_s, std::move(values),
                    last ? last : first_line);
}

GroundMotion ParseTimeSeries(const std::vector<Line>& lines, std::string_view source,
                             const ReadOptions& options) {
  const Units units = ResolveUnits(std::nullopt, options, source, 0);
  std::vector<double> times;
  std::vector<double> values;
  std::vector<long> line_of;
  std::vector<double> row;
  for (const Line& line : lines) {
    if (IsBlank(line.text)) continue;
    row.clear();
    AppendNumbers(line, source, row);
    if (row.size() != 2) {
      throw InputError::AtLine(
          source, line.number,
          "expected two columns (time, acceleration), found " + std::to_string(row.size()));
    }
    times.push_back(row[0]);
    values.push_back(row[1]);
    line_of.push_back(line.number);
  }
  if (values.size() < 2) {
    throw InputError::AtLine(source, line_of.empty() ? 1 : line_of.back(),
                             "a (time, acceleration) file needs at least two rows");
  }
  const double dt_in_file = (times.back() - times.front()) / static_cast<double>(times.size() - 1);
  if (!(dt_in_file > 0.0)) {
    throw InputError::AtLine(source, line_of.back(), "time column must increase (dt > 0)");
  }
  // The time column is printed with a few decimals: accept rounding, not an uneven grid.
  const double tolerance = 1e-3 * dt_in_file + 1e-9 * std::abs(times.back());
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double expected = times.front() + static_cast<double>(k) * dt_in_file;
    if (std::abs(times[k] - expected) > tolerance) {
      throw InputError::AtLine(
          source, line_of[k],
          fmt::format("time {} is off the uniform grid of dt = {:.6g} s", times[k], dt_in_file));
    }
  }
  const double dt_s = ResolveDt(RoundedTimeStep(dt_in_file), options, source, line_of.front());
  return MakeMotion(source, Format::kTimeSeries, units, dt_s, std::move(values), line_of.back());
}

}  // namespace skewbridge::records::detail
