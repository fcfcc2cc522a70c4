#include "records/excitations.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "solver/common/error.h"

namespace skewbridge::records {

PulseExcitation::PulseExcitation(PulseShape shape, double amplitude_mps2, double omega_radps,
                                 Eigen::Vector2d direction)
    : shape_(shape),
      amplitude_mps2_(amplitude_mps2),
      omega_radps_(omega_radps),
      period_s_(0.0),
      direction_(direction) {
  if (!std::isfinite(amplitude_mps2)) {
    throw InputError::AtField("pulse", "a_g", "must be finite");
  }
  if (!std::isfinite(omega_radps) || omega_radps <= 0.0) {
    throw InputError::AtField("pulse", "w_g",
                              fmt::format("must be > 0 rad/s (got {})", omega_radps));
  }
  if (!direction.allFinite() || std::abs(direction.norm() - 1.0) > 1e-12) {
    throw InputError::AtField("pulse", "direction", "must be a unit vector");
  }
  period_s_ = 2.0 * std::numbers::pi / omega_radps;
}

ExcitationPiece PulseExcitation::PieceAt(double t) const {
  ExcitationPiece piece;
  if (t >= period_s_) {
    piece.t_begin = period_s_;
    return piece;  // at rest
  }
  piece.t_begin = 0.0;
  piece.t_end = period_s_;
  piece.omega = omega_radps_;
  const Eigen::Vector2d a = amplitude_mps2_ * direction_;
  if (shape_ == PulseShape::kCosine) {
    piece.cos_amplitude = a;
  } else {
    piece.sin_amplitude = a;
  }
  return piece;
}

SampledExcitation::SampledExcitation(double dt_s, std::vector<double> ax_mps2,
                                     std::vector<double> ay_mps2)
    : dt_s_(dt_s), ax_(std::move(ax_mps2)), ay_(std::move(ay_mps2)) {
  if (!std::isfinite(dt_s) || dt_s <= 0.0) {
    throw InputError::AtField("sampled excitation", "dt", "must be > 0 s");
  }
  if (ax_.empty()) {
    throw InputError::AtField("sampled excitation", "values", "must not be empty");
  }
  if (!ay_.empty() && ay_.size() != ax_.size()) {
    throw InputError::AtField("sampled excitation", "y values",
                              "must have as many samples as x (" + std::to_string(ax_.size()) +
                                  "), got " + std::to_string(ay_.size()));
  }
  for (std::size_t k = 0; k < ax_.size(); ++k) {
    if (!std::isfinite(ax_[k]) || (!ay_.empty() && !std::isfinite(ay_[k]))) {
      throw InputError::AtField("sampled excitation", "sample " + std::to_string(k),
                                "must be finite");
    }
  }
}

double SampledExcitation::Duration() const { return dt_s_ * static_cast<double>(ax_.size() - 1); }

double SampledExcitation::Peak(double ramp_horizon_s) const {
  const std::size_t n = ax_.size();
  if (n < 2) return Excitation::Peak(ramp_horizon_s);
  // Excitation::Peak visits t = k dt for k = 0 .. n - 2 (each below Duration() = dt (n - 1), so
  // no rest piece), where PieceAt returns piece k: its operations, and the same max, here.
  double a_peak = 0.0;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double t = static_cast<double>(k) * dt_s_;
    const double t_end = static_cast<double>(k + 1) * dt_s_;
    const Eigen::Vector2d a_begin = Sample(k);
    const Eigen::Vector2d slope = (Sample(k + 1) - Sample(k)) / dt_s_;
    const double begin = a_begin.norm();
    a_peak = std::max(
        {a_peak, begin, (a_begin + slope * std::min(t_end - t, ramp_horizon_s)).norm(), begin});
  }
  return a_peak;
}

Eigen::Vector2d SampledExcitation::Sample(std::size_t k) const {
  return {ax_[k], ay_.empty() ? 0.0 : ay_[k]};
}

ExcitationPiece SampledExcitation::PieceAt(double t) const {
  ExcitationPiece piece;
  const std::size_t n = ax_.size();
  const double k_real = std::floor(t / dt_s_);
  // Compare against the end time itself, not only its sample index: (n - 1) dt / dt can round
  // below n - 1, and a last ramp returned at its own end time would have zero length.
  if (n < 2 || k_real >= static_cast<double>(n - 1) || t >= Duration()) {
    piece.t_begin = Duration();
    return piece;  // at rest after the last sample
  }
  auto k = static_cast<std::size_t>(k_real < 0.0 ? 0.0 : k_real);
  // Guard the floor against rounding: t exactly on a kink belongs to the piece starting there.
  if (static_cast<double>(k + 1) * dt_s_ <= t && k + 1 < n - 1) {
    ++k;
  }
  piece.t_begin = static_cast<double>(k) * dt_s_;
  piece.t_end = static_cast<double>(k + 1) * dt_s_;
  piece.a_begin = Sample(k);
  piece.slope = (Sample(k + 1) - Sample(k)) / dt_s_;
  piece.index = static_cast<long>(k);
  return piece;
}

void SampledExcitation::NextPiece(ExcitationPiece& piece) const {
  // At t = (k + 1) dt, PieceAt's floor gives k or k + 1 and its guard k + 1 whenever
  // k + 2 < n; for k + 2 >= n, t is Duration() (the same product) and the piece is the rest.
  const std::size_t n = ax_.size();
  const std::size_t k = piece.index < 0 ? 0 : static_cast<std::size_t>(piece.index) + 1;
  if (piece.index < 0 || k + 1 >= n || piece.t_end != static_cast<double>(k) * dt_s_) {
    piece = PieceAt(piece.t_end);
    return;
  }
  piece.t_begin = piece.t_end;
  piece.t_end = static_cast<double>(k + 1) * dt_s_;
  piece.a_begin = Sample(k);
  piece.slope = (Sample(k + 1) - Sample(k)) / dt_s_;
  piece.index = static_cast<long>(k);
}

SampledExcitation ToExcitation(const GroundMotion& motion, Eigen::Vector2d direction) {
  if (!direction.allFinite() || std::abs(direction.norm() - 1.0) > 1e-12) {
    throw InputError::AtField(motion.file, "direction", "must be a unit vector");
  }
  std::vector<double> ax(motion.acc_mps2.size());
  std::vector<double> ay;
  for (std::size_t k = 0; k < ax.size(); ++k) ax[k] = direction.x() * motion.acc_mps2[k];
  if (direction.y() != 0.0) {
    ay.resize(ax.size());
    for (std::size_t k = 0; k < ay.size(); ++k) ay[k] = direction.y() * motion.acc_mps2[k];
  }
  return SampledExcitation(motion.dt_s, std::move(ax), std::move(ay));
}

}  // namespace skewbridge::records
