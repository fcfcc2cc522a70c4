#include "records/readers/text.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "solver/common/error.h"

namespace skewbridge::records::detail {
namespace {

bool IsBlankChar(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v' || c == '\0';
}

bool IsSeparator(char c) { return IsBlankChar(c) || c == ','; }

char Lower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }

std::string Quote(std::string_view token) {
  constexpr std::size_t kMaxShown = 40;
  std::string shown(token.substr(0, kMaxShown));
  for (char& c : shown) {
    if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
  }
  if (token.size() > kMaxShown) shown += "...";
  return "'" + shown + "'";
}

// Parses without throwing; nullopt when the token is not a finite number.
std::optional<double> TryNumber(std::string_view token) {
  if (token.empty()) return std::nullopt;
  std::string buffer(token);
  if (buffer.front() == '+') buffer.erase(0, 1);
  if (buffer.empty()) return std::nullopt;
  // Only plain decimal notation: from_chars would also accept "nan", "inf" and hex digits.
  for (char& c : buffer) {
    if (c == 'D' || c == 'd') c = 'E';
    if (!(std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == 'E' || c == 'e' ||
          c == '-' || c == '+')) {
      return std::nullopt;
    }
  }
  double value = 0.0;
  const char* end = buffer.data() + buffer.size();
  const auto [ptr, ec] = std::from_chars(buffer.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

// Splits a blank-free chunk at signs that follow a digit or '.', the mark of packed fields.
template <typename Fn>
void ForEachPackedNumber(std::string_view chunk, Fn&& fn) {
  std::size_t start = 0;
  for (std::size_t i = 1; i < chunk.size(); ++i) {
    const char c = chunk[i];
    const char prev = chunk[i - 1];
    if ((c == '-' || c == '+') && (std::isdigit(static_cast<unsigned char>(prev)) || prev == '.')) {
      fn(chunk.substr(start, i - start));
      start = i;
    }
  }
  fn(chunk.substr(start));
}

template <typename Fn>
void ForEachChunk(std::string_view text, Fn&& fn) {
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && IsSeparator(text[i])) ++i;
    const std::size_t start = i;
    while (i < text.size() && !IsSeparator(text[i])) ++i;
    if (i > start) fn(text.substr(start, i - start));
  }
}

}  // namespace

std::vector<Line> SplitLines(std::string_view text) {
  std::vector<Line> lines;
  std::size_t start = 0;
  long number = 1;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n' || c == '\r') {
      lines.push_back({text.substr(start, i - start), number++});
      if (c == '\r') {
        while (i < text.size() && text[i] == '\r') ++i;
        if (i < text.size() && text[i] == '\n') ++i;
      } else {
        ++i;
      }
      start = i;
    } else {
      ++i;
    }
  }
  if (start < text.size()) lines.push_back({text.substr(start), number});
  return lines;
}

std::string_view Trim(std::string_view text) {
  std::size_t b = 0;
  std::size_t e = text.size();
  while (b < e && IsBlankChar(text[b])) ++b;
  while (e > b && IsBlankChar(text[e - 1])) --e;
  return text.substr(b, e - b);
}

bool StartsWithNoCase(std::string_view text, std::string_view prefix) {
  if (text.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i) {
    if (Lower(text[i]) != Lower(prefix[i])) return false;
  }
  return true;
}

std::size_t FindNoCase(std::string_view text, std::string_view key) {
  if (key.empty() || text.size() < key.size()) return std::string_view::npos;
  for (std::size_t i = 0; i + key.size() <= text.size(); ++i) {
    if (StartsWithNoCase(text.substr(i), key)) return i;
  }
  return std::string_view::npos;
}

bool IsBlank(std::string_view text) { return Trim(text).empty(); }

bool IsNumericLine(std::string_view text) {
  bool any = false;
  bool ok = true;
  ForEachChunk(text, [&](std::string_view chunk) {
    ForEachPackedNumber(chunk, [&](std::string_view token) {
      any = true;
      if (ok && !TryNumber(token)) ok = false;
    });
  });
  return any && ok;
}

std::optional<double> TryParseNumber(std::string_view token) { return TryNumber(token); }

double RoundedTimeStep(double step_s) {
  const double scaled = step_s * 1e9;
  if (!std::isfinite(scaled)) return step_s;
  const double rounded = std::round(scaled) / 1e9;
  return rounded > 0.0 ? rounded : step_s;
}

double ParseNumber(std::string_view token, std::string_view source, long line) {
  if (const std::optional<double> value = TryNumber(token)) return *value;
  std::string lowered;
  for (char c : token) lowered += Lower(c);
  if (lowered.find("nan") != std::string::npos) {
    throw InputError::AtLine(source, line,
                             "NaN is not an acceleration (token " + Quote(token) + ")");
  }
  if (lowered.find("inf") != std::string::npos) {
    throw InputError::AtLine(source, line, "infinite value " + Quote(token));
  }
  throw InputError::AtLine(source, line,
                           Quote(token) + " is not a finite number (expected e.g. -1.234E-02)");
}

long ParseCount(std::string_view token, std::string_view source, long line) {
  std::string_view digits = token;
  if (!digits.empty() && digits.back() == '.') digits.remove_suffix(1);
  long value = 0;
  const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || ec != std::errc() || ptr != digits.data() + digits.size() || value < 0) {
    throw InputError::AtLine(source, line,
                             "count " + Quote(token) + " is not a non-negative integer");
  }
  return value;
}

void AppendNumbers(const Line& line, std::string_view source, std::vector<double>& out) {
  ForEachChunk(line.text, [&](std::string_view chunk) {
    ForEachPackedNumber(chunk, [&](std::string_view token) {
      out.push_back(ParseNumber(token, source, line.number));
    });
  });
}

std::vector<std::string_view> Tokens(std::string_view text) {
  std::vector<std::string_view> tokens;
  ForEachChunk(text, [&](std::string_view chunk) { tokens.push_back(chunk); });
  return tokens;
}

std::optional<std::string_view> TokenAfter(std::string_view text, std::string_view key) {
  const std::size_t at = FindNoCase(text, key);
  if (at == std::string_view::npos) return std::nullopt;
  std::size_t i = at + key.size();
  while (i < text.size() && (IsBlankChar(text[i]) || text[i] == '=' || text[i] == ':')) ++i;
  const std::size_t start = i;
  while (i < text.size() && !IsSeparator(text[i])) ++i;
  if (i == start) return std::nullopt;
  return text.substr(start, i - start);
}

Units UnitsFromHeader(std::string_view spelling, std::string_view source, long line) {
  std::string_view s = Trim(spelling);
  while (!s.empty() && (s.front() == '(' || s.front() == '[')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == '.' || s.back() == ',' || s.back() == ')' || s.back() == ']' ||
                        s.back() == ';')) {
    s.remove_suffix(1);
  }
  // COSMOS appends its unit code: "cm/sec2(04)".
  if (const std::size_t paren = s.find('('); paren != std::string_view::npos && paren > 0) {
    s = s.substr(0, paren);
  }
  if (const std::optional<Units> units = ParseUnits(s)) return *units;
  throw InputError::AtLine(
      source, line,
      "unknown units " + Quote(spelling) + " (allowed: " + std::string(AllowedUnitsText()) + ")");
}

Units ResolveUnits(std::optional<Units> in_file, const ReadOptions& options,
                   std::string_view source, long line) {
  if (in_file && options.units && *in_file != *options.units) {
    throw InputError::AtLine(source, line,
                             "the file states units " + std::string(UnitsName(*in_file)) + " but " +
                                 std::string(UnitsName(*options.units)) + " were given");
  }
  if (in_file) return *in_file;
  if (options.units) return *options.units;
  throw InputError::AtLine(source, line,
                           "the file does not state its units: give them (g, m/s^2 or cm/s^2) "
                           "with --units of `skewbridge records info`, or `units` in a "
                           "record set or model file");
}

double ResolveDt(std::optional<double> in_file, const ReadOptions& options, std::string_view source,
                 long line) {
  if (options.dt_s && !(std::isfinite(*options.dt_s) && *options.dt_s > 0.0)) {
    throw InputError::AtLine(source, 0,
                             fmt::format("the given dt must be > 0 s (got {})", *options.dt_s));
  }
  if (in_file) {
    if (!(*in_file > 0.0)) {
      throw InputError::AtLine(source, line,
                               fmt::format("dt must be > 0 s (the file states {:.10g})", *in_file));
    }
    if (options.dt_s && std::abs(*options.dt_s - *in_file) > 1e-9 * *in_file) {
      throw InputError::AtLine(
          source, line,
          fmt::format("the file states dt = {:.10g} s but dt = {:.10g} s was given", *in_file,
                      *options.dt_s));
    }
    return *in_file;
  }
  if (options.dt_s) return *options.dt_s;
  throw InputError::AtLine(source, line,
                           "the file does not state its time step: give dt (s) with --dt of "
                           "`skewbridge records info`, `dt` in a record set or `dt_s` in a "
                           "model file");
}

GroundMotion MakeMotion(std::string_view source, Format format, Units units, double dt_s,
                        std::vector<double> values, long last_line) {
  if (values.empty()) {
    throw InputError::AtLine(source, last_line > 0 ? last_line : 1, "no samples in the file");
  }
  GroundMotion motion;
  motion.file = std::string(source);
  motion.format = std::string(FormatName(format));
  motion.original_units = std::string(UnitsName(units));
  motion.dt_s = dt_s;
  const double factor = ToMetresPerSecond2(units);
  for (double& v : values) v *= factor;
  motion.acc_mps2 = std::move(values);
  return motion;
}

}  // namespace skewbridge::records::detail
