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
