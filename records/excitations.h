#pragma once
/// @file
/// The ground motions the solver consumes: one-cycle pulses and sampled records, both behind
/// skewbridge::Excitation (solver/common/excitation.h).

#include <Eigen/Core>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
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
  /// True for both pieces: PieceAt depends on t only through t >= the period.
  bool PieceHolds(const ExcitationPiece& piece) const override {
    (void)piece;
    return true;
  }
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

/// The pieces of a sampled record that can hold the acceleration peak (Excitation::Peak at one
/// ramp horizon) of the record times any factor along any unit direction (ScaledExcitation).
struct PeakPieces {
  double ramp_horizon_s = 0.0;      ///< the ramp horizon (s) of Peak they hold for
  double largest_mps2 = 0.0;        ///< the largest |sample| of the record (m/s^2)
  std::vector<std::size_t> pieces;  ///< piece numbers k (of [k dt, (k + 1) dt]), ascending
};

/// The pieces of the record `acc_mps2` (at least two samples, finite) sampled at `dt_s` whose
/// terms of Peak(ramp_horizon_s) come within 1e-9 of the largest sample of the largest term:
/// the record times any factor along any unit direction takes its peak at one of them, to the
/// bit (the proof is at the definition).
PeakPieces FindPeakPieces(std::span<const double> acc_mps2, double dt_s, double ramp_horizon_s);

class SampledExcitation;

/// `motion` with every acceleration times `factor` (left as read when the factor is 1), linear
/// between samples, along the unit (x, y) `direction`: ToExcitation of the scaled motion, sample
/// for sample, in one pass. With `peak_pieces` (FindPeakPieces of the motion), Peak at their
/// horizon reads those pieces only, with the bits of the walk over every piece.
/// @throws InputError as ToExcitation.
SampledExcitation ScaledExcitation(const GroundMotion& motion, double factor,
                                   const Eigen::Vector2d& direction,
                                   std::shared_ptr<const PeakPieces> peak_pieces = nullptr);

/// A uniformly sampled ground motion, linear between samples (the Nigam-Jennings assumption),
/// starting at t = 0 and at rest after the last sample. Each sample is a kink.
class SampledExcitation final : public Excitation {
 public:
  /// @param dt_s sample interval (s) > 0; @param ax_mps2, ay_mps2 the components (m/s^2),
  /// ay empty or of the same length as ax.
  /// @throws InputError when dt <= 0, ax is empty, lengths differ or a value is not finite.
  SampledExcitation(double dt_s, std::vector<double> ax_mps2, std::vector<double> ay_mps2 = {});

  ExcitationPiece PieceAt(double t) const override;
  /// Piece k + 1 from piece k (its index) with PieceAt's operations: PieceAt(t) at t = (k + 1) dt
  /// exactly, the piece's end, is piece k + 1 (or the rest after the last sample), so the same
  /// bits without the division and floor.
  void NextPiece(ExcitationPiece& piece) const override;
  /// True for the rest after the last sample (PieceAt gives it at every t >= Duration(), its
  /// start); false for a ramp, whose floor may round a time just below its end to the next.
  bool PieceHolds(const ExcitationPiece& piece) const override {
    return piece.t_end == std::numeric_limits<double>::infinity() && piece.t_begin == Duration();
  }
  /// The samples: ax, ay (null when ay is empty) and dt.
  SampleView Samples() const override {
    return {dt_s_, ax_.data(), ay_.empty() ? nullptr : ay_.data(), ax_.size()};
  }
  double Duration() const override;
  /// Excitation::Peak from the samples in order, without PieceAt: piece k of [k dt, (k + 1) dt]
  /// is the one PieceAt gives at t = k dt (the guard of its floor), so the same bits. An
  /// excitation made by ScaledExcitation with PeakPieces of that horizon reads only those pieces.
  double Peak(double ramp_horizon_s) const override;

  double dt_s() const { return dt_s_; }
  const std::vector<double>& ax_mps2() const { return ax_; }
  const std::vector<double>& ay_mps2() const { return ay_; }

 private:
  friend SampledExcitation ScaledExcitation(const GroundMotion&, double, const Eigen::Vector2d&,
                                            std::shared_ptr<const PeakPieces>);

  Eigen::Vector2d Sample(std::size_t k) const;
  /// Piece k's terms of Peak: the largest of |a_begin| and |a_begin + slope min(dt_k, horizon)|.
  double PiecePeak(std::size_t k, double ramp_horizon_s) const;

  double dt_s_;
  std::vector<double> ax_;
  std::vector<double> ay_;
  /// The pieces that hold Peak, when the samples are a record's times a factor along a direction.
  std::shared_ptr<const PeakPieces> peak_pieces_;
};

/// Samples of a model file's excitation file (docs/model-format.md, excitation.file).
struct ExcitationSamples {
  std::vector<double> values_mps2;  ///< each value of the file times to_mps2
  double dt_s = 0.0;                ///< the given dt, or the step of the time column
};

/// The most samples a sampled signal may hold (80 MB of doubles; 28 h at 100 Hz).
inline constexpr std::size_t kMaxSignalSamples = 10'000'000;

/// Parses the text of a model file's excitation file, as strictly as the record readers: every
/// line is blank, a comment ('#' first) or a data line; the first data line fixes the columns,
/// one (acceleration, with `dt_s` given) or two (time in s, acceleration; blanks or commas
/// between), and every data line has as many; every token is a decimal number (NaN, Inf and
/// trailing characters are refused on their line); the times increase on one uniform grid
/// (within 1e-3 of a step, the rounding of a printed column) and its step must agree with a
/// given `dt_s` (to 1e-9). Each value times `to_mps2` (units x scale) must be finite. At least
/// two and at most kMaxSignalSamples samples. The first sample is applied at t = 0.
/// @throws InputError "SOURCE:LINE: problem; allowed: ..." for the first line at fault.
ExcitationSamples ParseExcitationSamples(std::string_view text, std::string_view source,
                                         std::optional<double> dt_s, double to_mps2);

/// Reads a model file's excitation file through ParseExcitationSamples. `skewbridge run` and
/// model-file sweeps read the file through here.
/// @throws InputError naming the file: unreadable, larger than 1 GiB, or as
/// ParseExcitationSamples.
ExcitationSamples ReadExcitationSamples(const std::filesystem::path& path,
                                        std::optional<double> dt_s, double to_mps2);

/// The record as the solver's excitation along `direction` (unit (x, y)), each sample a kink.
/// @throws InputError when the direction is not a unit vector (see SampledExcitation).
SampledExcitation ToExcitation(const GroundMotion& motion,
                               Eigen::Vector2d direction = Eigen::Vector2d::UnitX());

}  // namespace skewbridge::records
