#include "solver/model/deck.h"

#include <algorithm>
#include <cmath>

#include "solver/common/error.h"

namespace skewbridge::model {

Eigen::Vector2d Corner(const DeckGeometry& deck, int k) {
  SB_DEMAND(k >= 1 && k <= 4, "corner index must be 1..4");
  const double half_L = 0.5 * deck.length_m;
  const double half_W = 0.5 * deck.width_m;
  // The end edges are parallel to W (tan a, 1): offset (W/2) tan a along x [docs/theory.md §2].
  const double shift = half_W * std::tan(deck.skew_rad);
  switch (k) {
    case 1:
      return {half_L + shift, half_W};
    case 2:
      return {half_L - shift, -half_W};
    case 3:
      return {-half_L - shift, -half_W};
    default:
      return {-half_L + shift, half_W};
  }
}

double CornerTravelBound(const DeckGeometry& deck, const Eigen::Vector3d& max_abs_q) {
  const double a = deck.skew_rad;
  const Eigen::Vector2d n_e(std::cos(a), -std::sin(a));
  double rotational = 0.0;
  for (int k = 1; k <= 4; ++k) {
    const Eigen::Vector2d P = Corner(deck, k);
    for (double sign : {-1.0, 1.0}) {
      const double th = sign * max_abs_q(2);
      const Eigen::Vector2d moved(std::cos(th) * P.x() - std::sin(th) * P.y() - P.x(),
                                  std::sin(th) * P.x() + std::cos(th) * P.y() - P.y());
      rotational = std::max(rotational, std::abs(n_e.dot(moved)));
    }
  }
  // The translation's largest normal component: x and y may reach their maxima with the signs
  // that add up.
  const double translational = std::cos(a) * max_abs_q(0) + std::sin(a) * max_abs_q(1);
  return translational + rotational;
}

double CornerTravelAt(const DeckGeometry& deck, const Eigen::Vector3d& q) {
  const double a = deck.skew_rad;
  const Eigen::Vector2d n_e(std::cos(a), -std::sin(a));
  const double c = std::cos(q(2));
  const double s = std::sin(q(2));
  double travel = 0.0;
  for (int k = 1; k <= 4; ++k) {
    const Eigen::Vector2d P = Corner(deck, k);
    const Eigen::Vector2d moved(q(0) + c * P.x() - s * P.y() - P.x(),
                                q(1) + s * P.x() + c * P.y() - P.y());
    travel = std::max(travel, std::abs(n_e.dot(moved)));
  }
  return travel;
}

double UniformRadiusOfGyrationSquared(const DeckGeometry& deck) {
  const double c = std::cos(deck.skew_rad);
  const double L = deck.length_m;
  const double W = deck.width_m;
  return (L * L + W * W / (c * c)) / 12.0;
}

double UniformDeckInertia(double mass_kg, const DeckGeometry& deck) {
  return mass_kg * UniformRadiusOfGyrationSquared(deck);
}

double Eta0(const DeckGeometry& deck) {
  return std::sin(2.0 * deck.skew_rad) / (2.0 * deck.width_m / deck.length_m);
}

double WidthFromEta0(double eta0, double skew_rad, double length_m) {
  return length_m * std::sin(2.0 * skew_rad) / (2.0 * eta0);
}

double Eta1(const DeckGeometry& deck, double mu) {
  return Eta0(deck) * (1.0 + mu / std::tan(deck.skew_rad));
}

LeverArms ComputeLeverArms(const DeckGeometry& deck) {
  const double s = std::sin(deck.skew_rad);
  const double c = std::cos(deck.skew_rad);
  const double L = deck.length_m;
  const double W = deck.width_m;
  return {0.5 * (L * s + W / c), 0.5 * (L * s - W / c), 0.5 * L * c};
}

}  // namespace skewbridge::model
