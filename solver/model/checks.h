#pragma once
/// @file
/// Range checks shared by the Model constructor, BuildDeckModel and the model-file parser, so
/// that every path reports a bad value with the same words: "SOURCE[:LINE]: FIELD: must be ...
/// (got VALUE)". Internal to solver/model.

#include <Eigen/Core>
#include <string>
#include <string_view>

namespace skewbridge::model::detail {

/// Where a value came from: the input's name and, when known, its line (0 = unknown).
struct Where {
  std::string_view source;
  long line = 0;
};

/// Throws InputError "SOURCE[:LINE]: FIELD: PROBLEM".
[[noreturn]] void Fail(const Where& where, std::string_view field, std::string_view problem);

/// A number as it appears in messages (shortest round-trip form).
std::string Show(double value);

/// @throws InputError unless value is finite.
void CheckFinite(double value, std::string_view field, const Where& where);
/// @throws InputError unless value > 0 (and finite).
void CheckPositive(double value, std::string_view field, const Where& where);
/// @throws InputError unless value >= 0 (and finite).
void CheckNonNegative(double value, std::string_view field, const Where& where);
/// @throws InputError unless lo <= value <= hi (closed) or lo <= value < hi (hi_open), finite;
/// `unit` follows the bounds in the message ("deg" or "").
void CheckRange(double value, double lo, double hi, bool hi_open, std::string_view field,
                const Where& where, std::string_view unit = "");
/// @throws InputError unless A is n x n, finite and symmetric within a relative 1e-9 of its
/// largest entry, and (require_psd) positive semi-definite within that.
void CheckSymmetricPsd(const Eigen::MatrixXd& A, int n, std::string_view field, const Where& where,
                       bool require_psd);

}  // namespace skewbridge::model::detail
