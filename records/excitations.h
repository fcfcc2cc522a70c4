#pragma once
/// @file
/// The ground motions the solver consumes: one-cycle pulses and sampled records, both behind
/// skewbridge::Excitation (solver/common/excitation.h).

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <vector>

#include "records/ground_motion.h"
#include "solver/common/excitation.h"

namespace skewbridge::records {

/// Shape of a one-cycle pulse [Makris and Black 2004]: type-A (cosine) or type-B (sine).
enum class PulseShape { kCosine, kSine };

/// One full cycle of a_g cos(w_g t) or a_g sin(w_g t) on 0 <= t <= 2 pi / w_g, zero after.
class PulseExcitation final : public Excitation {
 public:
  /// @param amplitude_mps2 a_g (m/s^2), any sign; @param omega_radps w_g > 0 (rad/s);
  /// @param direction unit (x, y) direction of the ground motion.
  /// @throws InputError when w_g <= 0, a value is not finite, or the direction is not a unit
  /// vector.
  PulseExcitation(PulseShape shape, double amplitude_mps2, double omega_radps,
                  Eigen::Vector2d direction = Eigen::Vector2d::UnitX());

  ExcitationPiece PieceAt(double t) const override;
  double Duration() const override { return period_s_; }

  PulseShape shape() const { return shape_; }
  double amplitude_mps2() const { return amplitude_mps2_; }
  double omega_radps() const { return omega_radps_; }

 private:
  PulseShape shape_;
  double amplitude_mps2_;
  double omega_radps_;
  double period_s_;
  Eigen::Vector2d direction_;
};

/// A uniformly sampled ground motion, linear between samples (the Nigam-Jennings assumption),
/// starting at t = 0 and at rest after the last sample. Each sample is a kink.
class SampledExcitation final : public Excitation {
 public:
  /// @param dt_s sample interval (s) > 0; @param ax_mps2, ay_mps2 the components (m/s^2),
  /// ay empty or of the same length as ax.
  /// @throws InputError when dt <= 0, ax is empty, lengths differ or a value is not finite.
  SampledExcitation(double dt_s, std::vector<double> ax_mps2, std::vector<double> ay_mps2 = {});

  ExcitationPiece PieceAt(double t) const override;
  double Duration() const override;

  double dt_s() const { return dt_s_; }
  const std::vector<double>& ax_mps2() const { return ax_; }
  const std::vector<double>& ay_mps2() const { return ay_; }

 private:
  Eigen::Vector2d Sample(std::size_t k) const;

  double dt_s_;
  std::vector<double> ax_;
  std::vector<double> ay_;
};

/// Samples of a model file's excitation file (docs/model-format.md, excitation.file).
struct ExcitationSamples {
  std::vector<double> values_mps2;  ///< each value of the file times to_mps2
  double dt_s = 0.0;                ///< the given dt, or the step of the time column
};

/// Reads a plain text excitation file: one column (acceleration) with `dt_s` given, or two
/// (time, acceleration) whose times advance by one constant step (within 1e-6 of the first);
/// '#' lines and empty lines are skipped. Each value is multiplied by `to_mps2` (units x scale)
/// and must then be finite. `skewbridge run` and model-file sweeps read the file through here.
/// @throws InputError naming the file and the line: unreadable file, a token that is not a
/// number, a non-finite value, an uneven time column, fewer than two samples, or one column
/// without dt_s.
ExcitationSamples ReadExcitationSamples(const std::filesystem::path& path,
                                        std::optional<double> dt_s, double to_mps2);

/// The record as the solver's excitation along `direction` (unit (x, y)), each sample a kink.
/// @throws InputError when the direction is not a unit vector (see SampledExcitation).
SampledExcitation ToExcitation(const GroundMotion& motion,
                               Eigen::Vector2d direction = Eigen::Vector2d::UnitX());

}  // namespace skewbridge::records
