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
  const auto visit = [&](std::size_t k) {
    const double t = static_cast<double>(k) * dt_s_;
    const double t_end = static_cast<double>(k + 1) * dt_s_;
    const Eigen::Vector2d a_begin = Sample(k);
    const Eigen::Vector2d slope = (Sample(k + 1) - Sample(k)) / dt_s_;
    const double begin = a_begin.norm();
    a_peak = std::max(
        {a_peak, begin, (a_begin + slope * std::min(t_end - t, ramp_horizon_s)).norm(), begin});
  };
  if (peak_pieces_ && peak_pieces_->ramp_horizon_s == ramp_horizon_s) {
    // Every other piece's terms lie below one of these pieces' (FindPeakPieces), so the max over
    // these is the max over all, and a max of doubles does not depend on the order.
    for (const std::size_t k : peak_pieces_->pieces) visit(k);
    return a_peak;
  }
  for (std::size_t k = 0; k + 1 < n; ++k) visit(k);
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
  if (!NextSampledPiece(Samples(), piece)) {
    piece = PieceAt(piece.t_end);
  }
}

SampledExcitation ToExcitation(const GroundMotion& motion, Eigen::Vector2d direction) {
  return ScaledExcitation(motion, 1.0, direction);
}

PeakPieces FindPeakPieces(std::span<const double> acc_mps2, double dt_s, double ramp_horizon_s) {
  // Why these pieces hold the peak of the record scaled by f along a unit direction d. Write
  // u = 2^-53, A the largest |a_k|, w_k = min((k + 1) dt - k dt, horizon) (the same double in
  // every computation below) and Q_k = max(|a_k|, |a_k + (a_{k+1} - a_k) w_k / dt|) in exact
  // arithmetic. The scaled samples are d (f a_k) each rounded twice (relative 2u), and piece k's
  // terms of Peak are a few roundings of sums and products of them, w_k / dt <= 1 + 1e-12, so
  // they are |f| |d| Q_k within 50 u |f| A; the terms below, from the unscaled samples in one
  // dimension, are Q_k within 50 u A. A piece left out has a term q_k < M - 1e-9 A, M = q_j the
  // largest, so Q_j - Q_k > (1e-9 - 100 u) A, and its scaled terms lie below piece j's by more
  // than |f| |d| A (1e-9 - 200 u) > 0: a kept piece holds the largest term, whatever f and d.
  // (|d| = 1 within 1e-12 is a common factor; ScaledExcitation keeps the pieces only while
  // |f| A lies well inside the normal range, where these relative bounds hold.)
  PeakPieces out;
  out.ramp_horizon_s = ramp_horizon_s;
  const std::size_t n = acc_mps2.size();
  for (const double a : acc_mps2) out.largest_mps2 = std::max(out.largest_mps2, std::abs(a));
  if (n < 2) return out;
  std::vector<double> term(n - 1);
  double largest_term = 0.0;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double t = static_cast<double>(k) * dt_s;
    const double t_end = static_cast<double>(k + 1) * dt_s;
    const double slope = (acc_mps2[k + 1] - acc_mps2[k]) / dt_s;
    term[k] = std::max(std::abs(acc_mps2[k]),
                       std::abs(acc_mps2[k] + slope * std::min(t_end - t, ramp_horizon_s)));
    largest_term = std::max(largest_term, term[k]);
  }
  const double floor = largest_term - 1e-9 * out.largest_mps2;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    if (term[k] >= floor) out.pieces.push_back(k);
  }
  return out;
}

SampledExcitation ScaledExcitation(const GroundMotion& motion, double factor,
                                   const Eigen::Vector2d& direction,
                                   std::shared_ptr<const PeakPieces> peak_pieces) {
  if (!direction.allFinite() || std::abs(direction.norm() - 1.0) > 1e-12) {
    throw InputError::AtField(motion.file, "direction", "must be a unit vector");
  }
  // Each sample as a scaled copy of the motion and ToExcitation would make it: (a f) d_x, and
  // (a f) d_y when d_y is not zero; a times 1 is a itself.
  const std::size_t n = motion.acc_mps2.size();
  std::vector<double> ax(n);
  std::vector<double> ay;
  for (std::size_t k = 0; k < n; ++k) ax[k] = direction.x() * (motion.acc_mps2[k] * factor);
  if (direction.y() != 0.0) {
    ay.resize(n);
    for (std::size_t k = 0; k < n; ++k) ay[k] = direction.y() * (motion.acc_mps2[k] * factor);
  }
  SampledExcitation excitation(motion.dt_s, std::move(ax), std::move(ay));
  if (peak_pieces && n >= 2 && !peak_pieces->pieces.empty() && motion.dt_s > 1e-100) {
    // The bounds of FindPeakPieces are relative: they hold while no scaled sample, slope, square
    // or product comes near overflow or the subnormal range.
    const double top = std::abs(factor) * peak_pieces->largest_mps2;
    if (top == 0.0 || (top > 1e-100 && top < 1e100)) {
      excitation.peak_pieces_ = std::move(peak_pieces);
    }
  }
  return excitation;
}

}  // namespace skewbridge::records
