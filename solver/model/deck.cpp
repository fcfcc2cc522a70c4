#include "solver/model/deck.h"

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
