#pragma once
/// @file
/// The ground-acceleration interface the integrators consume.
///
/// A ground motion is a sequence of smooth pieces separated by kinks (a pulse's end, each
/// sample of a record). On a piece [t_begin, t_end) the two horizontal components are
///
///     a_g(t) = a_begin + slope (t - t_begin) + c cos(omega (t - t_begin)) + s sin(omega (t -
///     t_begin))
///
/// which covers the piecewise-linear interpolation of a sampled record (c = s = 0) and the
/// one-cycle pulses of Makris and Black (2004) (a_begin = slope = 0) exactly, so the
/// contact-free state transition can be exact on every piece ([docs/theory.md §3, smooth phases]).

#include <Eigen/Core>
#include <cstddef>
#include <limits>

namespace skewbridge {

/// One smooth piece of a ground motion; components are (x, y) in m/s^2, times in s.
struct ExcitationPiece {
  double t_begin = 0.0;                                     ///< s
  double t_end = std::numeric_limits<double>::infinity();   ///< s (kink or +inf)
  Eigen::Vector2d a_begin = Eigen::Vector2d::Zero();        ///< m/s^2 at t_begin (linear part)
  Eigen::Vector2d slope = Eigen::Vector2d::Zero();          ///< m/s^3
  double omega = 0.0;                                       ///< rad/s of the harmonic part
  Eigen::Vector2d cos_amplitude = Eigen::Vector2d::Zero();  ///< m/s^2
  Eigen::Vector2d sin_amplitude = Eigen::Vector2d::Zero();  ///< m/s^2
  /// The piece's number in an excitation that numbers its pieces (Excitation::NextPiece), else
  /// -1.
  long index = -1;

  /// Ground acceleration (x, y) in m/s^2 at time t (s) inside the piece.
  Eigen::Vector2d At(double t) const;
};

/// The samples of an excitation that is linear between uniformly spaced samples from t = 0, each
/// a kink (Excitation::Samples): piece k is [k dt, (k + 1) dt] from sample k to sample k + 1.
struct SampleView {
  double dt_s = 0.0;                ///< sample interval (s)
  const double* ax_mps2 = nullptr;  ///< the x components (m/s^2), `count` of them
  const double* ay_mps2 = nullptr;  ///< the y components (m/s^2), or null: y is 0
  std::size_t count = 0;            ///< the samples; 0: the excitation has no such view
};

/// Excitation::NextPiece of an excitation with the samples `view`, inline: piece k + 1 from
/// piece k (its index) when it is a ramp between two samples, then true; false, `piece`
/// untouched, where the piece's end is not sample k + 1's time (k + 1) dt, the piece has no
/// number, or the ramps end (the caller asks the excitation). PieceAt at t = (k + 1) dt gives
/// piece k + 1 there (its floor's guard), so these operations are its bits.
inline bool NextSampledPiece(const SampleView& view, ExcitationPiece& piece) {
  const std::size_t k = piece.index < 0 ? 0 : static_cast<std::size_t>(piece.index) + 1;
  if (piece.index < 0 || k + 1 >= view.count || piece.t_end != static_cast<double>(k) * view.dt_s) {
    return false;
  }
  const double* ax = view.ax_mps2;
  const double* ay = view.ay_mps2;
  const double y0 = ay != nullptr ? ay[k] : 0.0;
  const double y1 = ay != nullptr ? ay[k + 1] : 0.0;
  piece.t_begin = piece.t_end;
  piece.t_end = static_cast<double>(k + 1) * view.dt_s;
  piece.a_begin = Eigen::Vector2d(ax[k], y0);
  piece.slope = Eigen::Vector2d((ax[k + 1] - ax[k]) / view.dt_s, (y1 - y0) / view.dt_s);
  piece.index = static_cast<long>(k);
  return true;
}

/// A horizontal ground motion, the same for every support (uniform excitation).
/// Implementations are immutable and thread-compatible: the integrators only call const methods.
class Excitation {
 public:
  virtual ~Excitation() = default;

  /// The smooth piece containing t (s); for t at a kink, the piece that starts there.
  /// @pre t >= 0.
  virtual ExcitationPiece PieceAt(double t) const = 0;

  /// Turns `piece`, one this excitation gave, into the piece that starts at its end: the bits of
  /// PieceAt(piece.t_end). A subclass that numbers its pieces finds it by the number, without
  /// PieceAt's search (a free step per record sample asks this once).
  /// @pre piece.t_end finite.
  virtual void NextPiece(ExcitationPiece& piece) const { piece = PieceAt(piece.t_end); }

  /// True when PieceAt(t) gives `piece`'s bits at every t in [piece.t_begin, piece.t_end), for a
  /// `piece` this excitation gave: a caller whose time moves inside the piece may keep it
  /// instead of asking again. The default promises nothing (false).
  virtual bool PieceHolds(const ExcitationPiece& piece) const {
    (void)piece;
    return false;
  }

  /// The samples of an excitation whose pieces are ramps between uniform samples (SampleView),
  /// valid while the excitation lives: NextSampledPiece over them gives NextPiece's bits, so a
  /// caller that steps piece by piece reads them without a virtual call per piece. count 0 (the
  /// default): no such view.
  virtual SampleView Samples() const { return {}; }

  /// Ground acceleration (x, y) in m/s^2 at t (s); zero after Duration().
  Eigen::Vector2d At(double t) const { return PieceAt(t).At(t); }

  /// Time (s) after which the ground is at rest.
  virtual double Duration() const = 0;

  /// The acceleration scale of a run (m/s^2): over the pieces from t = 0 to Duration(), the
  /// largest of |a_begin|, |a_begin + slope min(t_end - t_begin, ramp_horizon_s)| and |a_begin|
  /// plus the harmonic amplitudes' norms. This walks PieceAt; a subclass may give the same bits
  /// without it.
  virtual double Peak(double ramp_horizon_s) const;
};

}  // namespace skewbridge
