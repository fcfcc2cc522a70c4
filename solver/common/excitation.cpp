#include "solver/common/excitation.h"

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

}  // namespace skewbridge
