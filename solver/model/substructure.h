#pragma once
/// @file
/// A deck's substructure from its elements: bearings, each on a pier or on the ground (an
/// abutment seat), piers as plan springs at their tops [docs/model-format.md, kind =
/// "elements"], and what any 3 x 3 deck stiffness says about itself: the centre of rigidity,
/// the principal translational stiffnesses and their axes, the torsional stiffness about the
/// centre [docs/theory.md §6].
///
/// Frames and signs follow builders.h: q = (x, y, theta) of the mass centre, a point p of the
/// deck moves by A(p) q with A(p) = [[1, 0, -p_y], [0, 1, p_x]] (small rotations).

#include <Eigen/Core>
#include <vector>

namespace skewbridge::model {

/// A spring in plan, stiff along two perpendicular axes: k = R(phi) diag(k_strong, k_weak)
/// R(phi)^T, phi the angle of the strong axis from x (CCW).
struct PlanSpring {
  double k_strong_Npm = 0.0;     ///< stiffness along the strong axis (N/m) >= 0
  double k_weak_Npm = 0.0;       ///< stiffness along the weak axis (N/m) >= 0
  double strong_axis_rad = 0.0;  ///< phi: strong axis from the deck's x axis (rad, CCW)
};

/// The 2 x 2 stiffness (N/m) of a plan spring in the deck frame: R(phi) diag(k_s, k_w) R(phi)^T.
Eigen::Matrix2d PlanStiffness(const PlanSpring& spring);

/// A pier: its top translates in plan against the ground through `spring`; its own torsion and
/// the rotation of its top in plan are not modelled (the bearings on one pier share its top's
/// displacement).
struct PierSpec {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();  ///< axis in the deck frame at rest (m)
  PlanSpring spring;  ///< pier top against the ground; both stiffnesses > 0
};

/// A bearing between the deck at `position_m` and the top of pier `pier`, or the ground
/// (an abutment seat) when pier < 0.
struct BearingSpec {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();  ///< on the deck, deck frame at rest (m)
  PlanSpring spring;  ///< deck against the pier top; stiffnesses >= 0
  int pier = -1;      ///< index into the piers, or -1 for a bearing on the ground
};

/// The deck stiffness (N/m, N, N m/rad about the mass centre) of bearings in series with their
/// piers: each pier's top displacement u_p is condensed out of
///   E = 1/2 sum_b (A(p_b) q - u_p)^T K_b (A(p_b) q - u_p) + 1/2 u_p^T K_p u_p,
/// giving sum_b A_b^T K_b A_b - G^T (K_p + sum_b K_b)^{-1} G, G = sum_b K_b A_b, per pier; a
/// bearing on the ground adds A_b^T K_b A_b. One bearing on a pier is the series spring
/// K_b (K_b + K_p)^{-1} K_p (k_b k_p / (k_b + k_p) along common axes).
/// @pre every pier index < piers.size(); every pier's stiffnesses > 0; bearings' >= 0.
Eigen::Matrix3d ElementsStiffness(const std::vector<BearingSpec>& bearings,
                                  const std::vector<PierSpec>& piers);

/// What a deck stiffness K (3 x 3 about the mass centre) says about itself: K = T^T K_cr T with
/// K_cr = blockdiag(K_t, k_theta,cr) about the centre of rigidity e and T as in
/// PrincipalAxesStiffness, so e = (t_2, -t_1) with t = K_t^{-1} (K_xtheta, K_ytheta) and
/// k_theta,cr = K_thetatheta - t^T K_t t; the principal axes are the eigenvectors of K_t.
struct StiffnessCentre {
  /// False when the translational block K_t is singular (no centre of rigidity): then
  /// centre_of_rigidity_m and torsion_about_centre_Nmprad are NaN.
  bool has_centre = false;
  Eigen::Vector2d centre_of_rigidity_m = Eigen::Vector2d::Zero();  ///< e from the mass centre
  double torsion_about_centre_Nmprad = 0.0;                        ///< k_theta,cr (N m/rad)
  Eigen::Vector2d principal_Npm = Eigen::Vector2d::Zero();  ///< eigenvalues of K_t, ascending
  /// Angle (rad, in (-pi/2, pi/2]) of the axis of principal_Npm(0) from x; the other axis is
  /// perpendicular. 0 when K_t is isotropic.
  double axis1_rad = 0.0;
};

/// Analyses a deck stiffness as StiffnessCentre describes.
/// @pre K symmetric.
StiffnessCentre AnalyseStiffness(const Eigen::Matrix3d& K);

}  // namespace skewbridge::model
