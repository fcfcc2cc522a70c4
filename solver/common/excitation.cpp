#include "solver/common/excitation.h"

#include <algorithm>
#include <cmath>

namespace skewbridge {

Eigen::Vector2d ExcitationPiece::At(double t) const {
  const double tau = t - t_begin;
  Eigen::Vector2d a = a_begin + slope * tau;
  if (omega != 0.0) {
    a += cos_amplitude * std::cos(omega * tau) + sin_amplitude * std::sin(omega * tau);
  }
  return a;
}

double Excitation::Peak(double ramp_horizon_s) const {
  double a_peak = 0.0;
  const double duration = Duration();
  for (double t = 0.0; t < duration;) {
    const ExcitationPiece piece = PieceAt(t);
    // |a_begin| + |c| + |s|; a record's pieces have no harmonic part, and a norm >= +0.0 plus
    // +0.0 is itself, so their two norms are left out there.
    const double begin = piece.a_begin.norm();
    const double harmonic = piece.cos_amplitude.isZero(0.0) && piece.sin_amplitude.isZero(0.0)
                                ? begin
                                : begin + piece.cos_amplitude.norm() + piece.sin_amplitude.norm();
    a_peak =
        std::max({a_peak, begin,
                  (piece.a_begin + piece.slope * std::min(piece.t_end - t, ramp_horizon_s)).norm(),
                  harmonic});
    if (!(piece.t_end > t)) {
      break;
    }
    t = piece.t_end;
  }
  return a_peak;
}

}  // namespace skewbridge
