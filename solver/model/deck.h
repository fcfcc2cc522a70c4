#pragma once
/// @file
/// The plan geometry of a skew deck (a parallelogram) and its rigid-body properties
/// [docs/theory.md §2, deck geometry; Dimitrakopoulos 2011, Fig. 1]. Body frame: origin at the mass
/// centre, x along the deck axis, y transverse, corners numbered as in NOTATION.md.

#include <Eigen/Core>
#include <string>

namespace skewbridge::model {

/// Plan geometry of a parallelogram deck spanned by (L, 0) and W (tan a, 1).
struct DeckGeometry {
  double length_m = 0.0;  ///< L: distance between the mid-points of the two end edges (m)
  double width_m = 0.0;   ///< W: width perpendicular to the deck axis (m)
  double skew_rad = 0.0;  ///< a: skew angle, 0 <= a < pi/2 (rad)
};

/// Corner P_k (k = 1..4) in the body frame (m) [docs/theory.md §2]:
/// P1 = (L/2 + (W/2) tan a, W/2), P2 = (L/2 - (W/2) tan a, -W/2),
/// P3 = (-L/2 - (W/2) tan a, -W/2), P4 = (-L/2 + (W/2) tan a, W/2).
/// P1, P3 are the acute corners, P2, P4 the obtuse ones.
/// @pre 1 <= k <= 4 (SB_DEMAND).
Eigen::Vector2d Corner(const DeckGeometry& deck, int k);

/// Largest travel of a corner normal to its end line (m), bounded from the maxima of a
/// response: with n_e = (cos a, -sin a) the unit normal of the end lines,
///     t = cos a x_m + sin a y_m + max over corners P_k and s = +-1 of |n_e . (R(s theta_m) - E)
///     P_k|,
/// an upper bound of the true largest travel, since the three maxima need not coincide.
/// Every sweep family stores it as travel_bound_m[_d<i>]; their margins and limit states use
/// the exact largest travel that the integrators track (dynamics::RunResult::max_travel_m).
/// @param max_abs_q (x_m, y_m, theta_m): the deck's max |x|, |y| (m) and |theta| (rad).
double CornerTravelBound(const DeckGeometry& deck, const Eigen::Vector3d& max_abs_q);

/// Travel of the farthest corner normal to its end line at one instant (m), exact:
///     max over corners P_k of |n_e . ((x, y) + (R(theta) - E) P_k)|,  n_e = (cos a, -sin a).
/// The residual limit states of every sweep family use it with q = q(t_end).
/// @param q (x, y, theta): the deck's displacement (m, m, rad) relative to its rest position.
double CornerTravelAt(const DeckGeometry& deck, const Eigen::Vector3d& q);

/// Radius of gyration squared of a uniform deck (m^2): rho^2 = (L^2 + W^2 / cos^2 a) / 12
/// [docs/theory.md §2].
double UniformRadiusOfGyrationSquared(const DeckGeometry& deck);

/// Polar mass moment of inertia of a uniform deck (kg m^2): I_m = m rho^2 [docs/theory.md §2].
double UniformDeckInertia(double mass_kg, const DeckGeometry& deck);

/// The frictionless skew ratio eta0 = sin 2a / (2 W / L) [Dimitrakopoulos 2011, eq. 14;
/// docs/theory.md §4 fact 1]. eta0 <= 1 iff the obtuse-corner lever arm r_2 <= 0.
double Eta0(const DeckGeometry& deck);

/// The width that gives a skew ratio: W = L sin 2a / (2 eta0) (m), the inverse of Eta0.
/// @pre eta0 > 0, 0 < a < pi/2.
double WidthFromEta0(double eta0, double skew_rad, double length_m);

/// The frictional skew ratio eta1 = eta0 (1 + mu / tan a) [Dimitrakopoulos 2011, eq. 20;
/// docs/theory.md §4 fact 2, sigma = +1].
double Eta1(const DeckGeometry& deck, double mu);

/// Lever arms of the +x abutment's closed forms (m) [docs/theory.md §2]:
/// r_1 = (L sin a + W / cos a) / 2, r_2 = (L sin a - W / cos a) / 2, r_T = L cos a / 2.
struct LeverArms {
  double r1_m = 0.0;
  double r2_m = 0.0;
  double rT_m = 0.0;
};

/// The lever arms r_1, r_2, r_T of a deck [docs/theory.md §2].
LeverArms ComputeLeverArms(const DeckGeometry& deck);

/// One planar rigid body (a deck): its generalised coordinates (x, y, theta) relative to the
/// ground occupy DOFs 3 i .. 3 i + 2 of the model, i its index. Its mass centre sits at
/// rest_position_m when q = 0, so that the mass centre is at rest_position_m + (x, y); a single
/// deck sits at the origin, the decks of a multi-span bridge one after the other along x.
struct Body {
  std::string name = "deck";
  double mass_kg = 0.0;       ///< m (kg) > 0
  double inertia_kgm2 = 0.0;  ///< I_m (kg m^2) > 0, about the mass centre
  DeckGeometry geometry;      ///< plan shape in the body frame
  Eigen::Vector2d rest_position_m = Eigen::Vector2d::Zero();  ///< X: mass centre at q = 0 (m)
};

}  // namespace skewbridge::model
