#include "solver/model/substructure.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <numbers>

#include "solver/common/error.h"

namespace skewbridge::model {
namespace {

// A(p): the plan displacement of deck point p for q = (x, y, theta), small rotations.
Eigen::Matrix<double, 2, 3> PointMap(const Eigen::Vector2d& p) {
  Eigen::Matrix<double, 2, 3> A;
  // clang-format off
  A << 1.0, 0.0, -p.y(),
       0.0, 1.0,  p.x();
  // clang-format on
  return A;
}

}  // namespace

Eigen::Matrix2d PlanStiffness(const PlanSpring& spring) {
  const double c = std::cos(spring.strong_axis_rad);
  const double s = std::sin(spring.strong_axis_rad);
  Eigen::Matrix2d R;
  R << c, -s, s, c;
  const Eigen::Matrix2d k =
      R * Eigen::Vector2d(spring.k_strong_Npm, spring.k_weak_Npm).asDiagonal() * R.transpose();
  return 0.5 * (k + k.transpose());
}

Eigen::Matrix3d ElementsStiffness(const std::vector<BearingSpec>& bearings,
                                  const std::vector<PierSpec>& piers) {
  Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
  // Per pier: G = sum_b K_b A_b and the pier top's own stiffness K_p + sum_b K_b.
  std::vector<Eigen::Matrix<double, 2, 3>> G(piers.size(), Eigen::Matrix<double, 2, 3>::Zero());
  std::vector<Eigen::Matrix2d> top(piers.size());
  for (std::size_t p = 0; p < piers.size(); ++p) {
    top[p] = PlanStiffness(piers[p].spring);
  }
  for (const BearingSpec& b : bearings) {
    SB_DEMAND(b.pier < static_cast<int>(piers.size()), "bearing on a pier that does not exist");
    const Eigen::Matrix<double, 2, 3> A = PointMap(b.position_m);
    const Eigen::Matrix2d k = PlanStiffness(b.spring);
    K += A.transpose() * k * A;
    if (b.pier >= 0) {
      G[static_cast<std::size_t>(b.pier)] += k * A;
      top[static_cast<std::size_t>(b.pier)] += k;
    }
  }
  // Static condensation of each pier top: its stiffness is positive definite (K_p > 0).
  for (std::size_t p = 0; p < piers.size(); ++p) {
    const Eigen::LLT<Eigen::Matrix2d> llt(top[p]);
    SB_DEMAND(llt.info() == Eigen::Success, "pier stiffness must be positive definite");
    K -= G[p].transpose() * llt.solve(G[p]);
  }
  return 0.5 * (K + K.transpose());
}

StiffnessCentre AnalyseStiffness(const Eigen::Matrix3d& K) {
  StiffnessCentre out;
  const Eigen::Matrix2d Kt = K.topLeftCorner<2, 2>();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(Kt);
  out.principal_Npm = eig.eigenvalues();
  const Eigen::Vector2d v = eig.eigenvectors().col(0);
  // An isotropic K_t has no preferred axis: report x.
  const double spread = out.principal_Npm(1) - out.principal_Npm(0);
  if (spread > 1e-12 * std::abs(out.principal_Npm(1))) {
    double angle = std::atan2(v.y(), v.x());
    if (angle <= -0.5 * std::numbers::pi) angle += std::numbers::pi;
    if (angle > 0.5 * std::numbers::pi) angle -= std::numbers::pi;
    out.axis1_rad = angle;
  }
  // Singular K_t (a stiffness-free direction): no point about which a force causes no rotation.
  out.has_centre = out.principal_Npm(0) > 1e-12 * std::abs(out.principal_Npm(1));
  if (!out.has_centre) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    out.centre_of_rigidity_m = Eigen::Vector2d(nan, nan);
    out.torsion_about_centre_Nmprad = nan;
    return out;
  }
  const Eigen::Vector2d coupling = K.topRightCorner<2, 1>();
  const Eigen::Vector2d t = Kt.ldlt().solve(coupling);
  out.centre_of_rigidity_m = Eigen::Vector2d(t.y(), -t.x());
  out.torsion_about_centre_Nmprad = K(2, 2) - t.dot(Kt * t);
  return out;
}

}  // namespace skewbridge::model
