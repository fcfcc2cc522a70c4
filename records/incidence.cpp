#include "records/incidence.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "solver/common/error.h"

namespace skewbridge::records {

Eigen::Vector2d DirectionAt(double angle_deg) {
  constexpr double kDegToRad = std::numbers::pi / 180.0;
  return {std::cos(angle_deg * kDegToRad), std::sin(angle_deg * kDegToRad)};
}

SampledExcitation PairExcitation(const GroundMotion& h1, const GroundMotion& h2,
                                 double incidence_deg, double factor) {
  if (!std::isfinite(incidence_deg)) {
    throw InputError::AtField(h1.file, "incidence_deg", "must be finite");
  }
  return PairExcitation(h1, h2, DirectionAt(incidence_deg), factor);
}

SampledExcitation PairExcitation(const GroundMotion& h1, const GroundMotion& h2,
                                 const Eigen::Vector2d& h1_direction, double factor) {
  if (!(std::abs(h2.dt_s - h1.dt_s) <= 1e-9 * std::max(h1.dt_s, h2.dt_s))) {
    throw InputError::AtField(h2.file, "dt",
                              fmt::format("{} s differs from the first component's {} s ({}): "
                                          "the two components of a pair share one time step",
                                          h2.dt_s, h1.dt_s, h1.file));
  }
  if (h2.npts() != h1.npts()) {
    throw InputError::AtField(h2.file, "npts",
                              fmt::format("{} samples differ from the first component's {} ({}): "
                                          "the two components of a pair have one length",
                                          h2.npts(), h1.npts(), h1.file));
  }
  const double c = h1_direction.x(), s = h1_direction.y();
  std::vector<double> ax(h1.npts()), ay(h1.npts());
  for (std::size_t k = 0; k < ax.size(); ++k) {
    const double a1 = factor == 1.0 ? h1.acc_mps2[k] : h1.acc_mps2[k] * factor;
    const double a2 = factor == 1.0 ? h2.acc_mps2[k] : h2.acc_mps2[k] * factor;
    ax[k] = c * a1 - s * a2;
    ay[k] = s * a1 + c * a2;
  }
  return SampledExcitation(h1.dt_s, std::move(ax), std::move(ay));
}

}  // namespace skewbridge::records
