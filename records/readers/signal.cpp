// The excitation file of a model file (docs/model-format.md, excitation.file): one or two
// columns of plain numbers, read with the strictness of the record readers.
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "records/readers/text.h"
#include "solver/common/error.h"

namespace skewbridge::records {
namespace {

using detail::Line;

// The largest excitation file read into memory [bytes]: kMaxSignalSamples lines of 100
// characters.
constexpr std::uintmax_t kMaxSignalFileBytes = std::uintmax_t{1} << 30;

std::string Show(double value) {
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

std::string Shown(std::string_view token) {
  constexpr std::size_t kMaxShown = 40;
  std::string shown(token.substr(0, kMaxShown));
  for (char& c : shown) {
    if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
  }
  if (token.size() > kMaxShown) shown += "...";
  return "'" + shown + "'";
}

// The column's name in messages: "acceleration" alone, or "time" / "acceleration" of two.
std::string ColumnName(std::size_t column, std::size_t columns) {
  if (columns == 1) return "the acceleration column";
  return column == 0 ? "column 1 (time, s)" : "column 2 (acceleration)";
}

double Number(std::string_view token, std::size_t column, std::size_t columns,
              std::string_view source, long line) {
  if (const std::optional<double> value = detail::TryParseNumber(token)) return *value;
  std::string lowered;
  for (char c : token) lowered += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::string what = lowered.find("nan") != std::string::npos   ? "NaN"
                           : lowered.find("inf") != std::string::npos ? "an infinite value"
                                                                      : "not a finite number";
  throw InputError::AtLine(source, line,
                           Shown(token) + " in " + ColumnName(column, columns) + " is " + what +
                               "; allowed: finite decimal numbers such as -1.234e-02");
}

}  // namespace

ExcitationSamples ParseExcitationSamples(std::string_view text, std::string_view source,
                                         std::optional<double> dt_s, double to_mps2) {
  std::vector<double> times, values;
  std::vector<long> time_lines;  // the line of each time (two columns)
  std::size_t columns = 0;
  long first_line = 0, last_line = 0, second_line = 0;
  for (const Line& line : detail::SplitLines(text)) {
    const std::string_view trimmed = detail::Trim(line.text);
    if (trimmed.empty() || trimmed.front() == '#') continue;
    const std::vector<std::string_view> tokens = detail::Tokens(trimmed);
    if (columns == 0) {
      if (tokens.size() != 1 && tokens.size() != 2) {
        throw InputError::AtLine(source, line.number,
                                 "the first data line has " + std::to_string(tokens.size()) +
                                     " columns; allowed: 1 (acceleration, with excitation.dt_s) "
                                     "or 2 (time in s, acceleration)");
      }
      columns = tokens.size();
      first_line = line.number;
    } else if (tokens.size() != columns) {
      throw InputError::AtLine(
          source, line.number,
          std::to_string(tokens.size()) + (tokens.size() == 1 ? " column" : " columns") +
              " where the first data line (line " + std::to_string(first_line) + ") has " +
              (columns == 1 ? "1 (acceleration)" : "2 (time in s, acceleration)") +
              "; allowed: the same columns on every data line");
    }
    if (values.size() == kMaxSignalSamples) {
      throw InputError::AtLine(
          source, line.number,
          "more than " + std::to_string(kMaxSignalSamples) + " samples; allowed: at most 1e7");
    }
    if (columns == 2) {
      const double t = Number(tokens[0], 0, 2, source, line.number);
      if (!times.empty() && !(t > times.back())) {
        throw InputError::AtLine(source, line.number,
                                 "time " + Show(t) + " s does not increase (the line before has " +
                                     Show(times.back()) +
                                     " s); allowed: times increasing by "
                                     "one constant step");
      }
      times.push_back(t);
      time_lines.push_back(line.number);
    }
    const double a = Number(tokens[columns - 1], columns - 1, columns, source, line.number);
    if (!std::isfinite(a * to_mps2)) {
      throw InputError::AtLine(source, line.number,
                               "acceleration " + Show(a) + " times units and scale (" +
                                   Show(to_mps2) + ") is not a finite number in m/s^2");
    }
    values.push_back(a);
    if (values.size() == 2) second_line = line.number;
    last_line = line.number;
  }
  if (values.empty()) {
    throw InputError::AtLine(source, 0, "no samples (only blank or '#' lines)");
  }
  if (values.size() < 2) {
    throw InputError::AtLine(source, last_line,
                             "one sample; a sampled excitation needs at least two");
  }
  ExcitationSamples out;
  if (columns == 1) {
    if (!dt_s) {
      throw InputError::AtLine(source, first_line,
                               "one column (acceleration) needs excitation.dt_s in the model "
                               "file; allowed: dt_s, or two columns (time in s, acceleration)");
    }
    out.dt_s = *dt_s;
  } else {
    // The step of the grid through the first and last times; each time within the rounding of
    // a printed column of it (the record readers' rule, records/readers/plain.cpp).
    const double n = static_cast<double>(times.size() - 1);
    const double step = (times.back() - times.front()) / n;
    const double tolerance = 1e-3 * step + 1e-9 * std::abs(times.back());
    for (std::size_t k = 0; k < times.size(); ++k) {
      const double expected = times.front() + static_cast<double>(k) * step;
      if (!(std::abs(times[k] - expected) <= tolerance)) {
        throw InputError::AtLine(source, time_lines[k],
                                 "time " + Show(times[k]) + " s is off the uniform grid of step " +
                                     Show(step) +
                                     " s (from the first and last times); allowed: "
                                     "times increasing by one constant step");
      }
    }
    out.dt_s = detail::RoundedTimeStep(step);
    if (dt_s && std::abs(*dt_s - out.dt_s) > 1e-9 * out.dt_s) {
      throw InputError::AtLine(source, second_line,
                               "the time column steps by " + Show(out.dt_s) +
                                   " s but the model file gives excitation.dt_s = " + Show(*dt_s) +
                                   " s; allowed: no dt_s, or the step of the time column");
    }
  }
  for (double& v : values) v *= to_mps2;
  out.values_mps2 = std::move(values);
  return out;
}

ExcitationSamples ReadExcitationSamples(const std::filesystem::path& path,
                                        std::optional<double> dt_s, double to_mps2) {
  const std::string source = path.string();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError::AtLine(source, 0,
                             "is a folder; excitation.file names a text file of samples");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError::AtLine(source, 0, "cannot open the excitation file");
  }
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (!ec && bytes > kMaxSignalFileBytes) {
    throw InputError::AtLine(source, 0,
                             "the excitation file has " + std::to_string(bytes) +
                                 " bytes; allowed: at most 1 GiB (1e7 samples)");
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) {
    throw InputError::AtLine(source, 0, "error while reading the excitation file");
  }
  return ParseExcitationSamples(buffer.view(), source, dt_s, to_mps2);
}

}  // namespace skewbridge::records
