#include "solver/model/checks.h"

#include <charconv>
#include <cmath>

#include "solver/common/error.h"

namespace skewbridge::model::detail {

void Fail(const Where& where, std::string_view field, std::string_view problem) {
  std::string message(field);
  message += ": ";
  message += problem;
  throw InputError::AtLine(where.source, where.line, message);
}

std::string Show(double value) {
  if (std::isnan(value)) {
    return "nan";
  }
  if (std::isinf(value)) {
    return value > 0 ? "inf" : "-inf";
  }
  char buffer[64];
  const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

void CheckFinite(double value, std::string_view field, const Where& where) {
  if (!std::isfinite(value)) {
    Fail(where, field,
         std::string("must be a finite number (got ").append(Show(value)).append(")"));
  }
}

void CheckPositive(double value, std::string_view field, const Where& where) {
  CheckFinite(value, field, where);
  if (!(value > 0.0)) {
    Fail(where, field, std::string("must be > 0 (got ").append(Show(value)).append(")"));
  }
}

void CheckNonNegative(double value, std::string_view field, const Where& where) {
  CheckFinite(value, field, where);
  if (!(value >= 0.0)) {
    Fail(where, field, std::string("must be >= 0 (got ").append(Show(value)).append(")"));
  }
}

void CheckRange(double value, double lo, double hi, bool hi_open, std::string_view field,
                const Where& where, std::string_view unit) {
  CheckFinite(value, field, where);
  const bool inside = value >= lo && (hi_open ? value < hi : value <= hi);
  if (!inside) {
    std::string problem = "must be in [";
    problem.append(Show(lo)).append(", ").append(Show(hi)).append(hi_open ? ")" : "]");
    if (!unit.empty()) {
      problem.append(" ").append(unit);
    }
    problem.append(" (got ").append(Show(value)).append(")");
    Fail(where, field, problem);
  }
}

}  // namespace skewbridge::model::detail
