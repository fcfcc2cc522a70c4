#include "solver/common/schema.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>

#include "solver/common/error.h"

namespace skewbridge::schema {

std::string FormatNumber(double x) {
  if (!std::isfinite(x)) return fmt::format("{}", x);
  if (x == std::trunc(x) && std::abs(x) < 1e5) return fmt::format("{}", x);
  // The fewest significant digits that read back as x, in %g's choice of notation, with the
  // exponent's sign and leading zeros dropped where they say nothing (1e-10, 2e6).
  std::string text;
  for (int digits = 1; digits <= 17; ++digits) {
    text = fmt::format("{:.{}g}", x, digits);
    if (std::strtod(text.c_str(), nullptr) == x) break;
  }
  const std::size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string mantissa = text.substr(0, e);
  const bool negative = text[e + 1] == '-';
  std::size_t digits_at = e + 2;
  while (digits_at + 1 < text.size() && text[digits_at] == '0') ++digits_at;
  return mantissa + (negative ? "e-" : "e") + text.substr(digits_at);
}

bool Interval::Admits(double x) const {
  if (!std::isfinite(x)) return false;
  if (power_of_two) {
    // An integral member: 1, 2, 4, ... are exact in a double up to 2^53.
    int exponent = 0;
    return x >= 1.0 && std::frexp(x, &exponent) == 0.5;
  }
  const bool above = lower_open ? x > lower : x >= lower;
  const bool below = upper_open ? x < upper : x <= upper;
  return above && below;
}

std::string Interval::Text() const {
  if (power_of_two) return "a power of two (1, 2, 4, ...)";
  const bool has_lower = std::isfinite(lower);
  const bool has_upper = std::isfinite(upper);
  if (has_lower && has_upper) {
    return fmt::format("in {}{}, {}{}", lower_open ? "(" : "[", FormatNumber(lower),
                       FormatNumber(upper), upper_open ? ")" : "]");
  }
  if (has_lower) {
    return fmt::format("{} {}", lower_open ? "greater than" : "at least", FormatNumber(lower));
  }
  if (has_upper) {
    return fmt::format("{} {}", upper_open ? "less than" : "at most", FormatNumber(upper));
  }
  return "finite";
}

std::string Violation(const std::string& name, const Interval& allowed, double value) {
  return fmt::format("{}: must be {} (got {})", name, allowed.Text(), FormatNumber(value));
}

void ThrowInvalid(std::string_view source, const std::string& problem) {
  throw InputError(fmt::format("{}: {}", source, problem));
}

std::string MarkdownRow(const Entry& e) {
  // A '|' inside a cell ("max(1 s, |t|)") is escaped, so that it does not end the cell.
  const auto cell = [](std::string text) {
    for (std::size_t at = text.find('|'); at != std::string::npos; at = text.find('|', at + 2)) {
      text.insert(at, 1, '\\');
    }
    return text;
  };
  const std::string value =
      e.kind == Kind::kRule ? (e.value != 0.0 ? "on" : "off") : FormatNumber(e.value);
  const std::string allowed = e.kind == Kind::kRule ? "on or off" : e.allowed.Text();
  return fmt::format("| `{}` | {} | {} | {} | {} |", e.name, value, cell(e.unit),
                     cell(e.relative_to), allowed);
}

}  // namespace skewbridge::schema
