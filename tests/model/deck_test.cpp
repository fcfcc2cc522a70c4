// The deck geometry against independent forms: the parallelogram's spanning vectors, the second
// moment of area by exact Gauss quadrature, and the skew ratio's lever-arm meaning.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "solver/model/deck.h"

namespace skewbridge::model {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(DeckGeometry, CornersSpanTheParallelogramOfLengthAndSkewedWidth) {
  const DeckGeometry deck{30.0, 10.0, 35.0 * kDeg};
  const Eigen::Vector2d along_width(10.0 * std::tan(35.0 * kDeg), 10.0);  // W (tan a, 1)
  EXPECT_LT((Corner(deck, 1) - Corner(deck, 2) - along_width).norm(), 1e-12);
  EXPECT_LT((Corner(deck, 4) - Corner(deck, 3) - along_width).norm(), 1e-12);
  // Mid-points of the end edges are (+-L/2, 0).
  EXPECT_LT((0.5 * (Corner(deck, 1) + Corner(deck, 2)) - Eigen::Vector2d(15.0, 0.0)).norm(), 1e-12);
  EXPECT_LT((0.5 * (Corner(deck, 3) + Corner(deck, 4)) - Eigen::Vector2d(-15.0, 0.0)).norm(),
            1e-12);
  // P1 is the acute corner: the interior angle there is 90 deg - a.
  const Eigen::Vector2d e1 = (Corner(deck, 4) - Corner(deck, 1)).normalized();
  const Eigen::Vector2d e2 = (Corner(deck, 2) - Corner(deck, 1)).normalized();
  EXPECT_NEAR(std::acos(e1.dot(e2)), (90.0 - 35.0) * kDeg, 1e-12);
}

// Polar second moment per unit mass of the parallelogram, by 2-point Gauss-Legendre quadrature
// on (s, v) in [-1/2, 1/2]^2, exact for the quadratic integrand.
double GaussRadiusOfGyrationSquared(const DeckGeometry& deck) {
  const double g = 0.5 / std::sqrt(3.0);
  double sum = 0.0;
  for (double s : {-g, g}) {
    for (double v : {-g, g}) {
      const double X = s * deck.length_m + v * deck.width_m * std::tan(deck.skew_rad);
      const double Y = v * deck.width_m;
      sum += 0.25 * (X * X + Y * Y);
    }
  }
  return sum;
}

TEST(DeckGeometry, UniformInertiaEqualsTheQuadratureOfTheParallelogram) {
  for (double a_deg : {0.0, 15.0, 30.0, 45.0, 60.0}) {
    for (double W : {5.0, 19.36, 40.0}) {
      const DeckGeometry deck{89.14, W, a_deg * kDeg};
      const double rho2 = GaussRadiusOfGyrationSquared(deck);
      EXPECT_NEAR(UniformRadiusOfGyrationSquared(deck), rho2, 1e-12 * rho2);
      EXPECT_NEAR(UniformDeckInertia(1547e3, deck), 1547e3 * rho2, 1e-12 * 1547e3 * rho2);
    }
  }
}

TEST(DeckGeometry, Eta0AndWidthAreInverseAndEta0OneIsWhereR2VanishesWithSign) {
  for (double a_deg : {10.0, 20.0, 30.0, 45.0, 70.0}) {
    for (double eta0 : {0.3, 0.87, 1.0, 1.48, 3.0}) {
      const double W = WidthFromEta0(eta0, a_deg * kDeg, 50.0);
      const DeckGeometry deck{50.0, W, a_deg * kDeg};
      EXPECT_NEAR(Eta0(deck), eta0, 1e-14 * eta0);
      // [docs/theory.md §4 fact 1]: eta0 <= 1 iff r_2 <= 0; r_2 = (L sin a - W / cos a) / 2.
      const double r2 = 0.5 * (50.0 * std::sin(a_deg * kDeg) - W / std::cos(a_deg * kDeg));
      EXPECT_NEAR(ComputeLeverArms(deck).r2_m, r2, 1e-12 * 50.0);
      if (eta0 < 1.0) {
        EXPECT_LT(ComputeLeverArms(deck).r2_m, 0.0);
      } else if (eta0 > 1.0) {
        EXPECT_GT(ComputeLeverArms(deck).r2_m, 0.0);
      } else {
        EXPECT_NEAR(ComputeLeverArms(deck).r2_m, 0.0, 1e-12 * 50.0);
      }
    }
  }
}

TEST(DeckGeometry, PilotBridgeDimensionsGiveEta0OfOnePointFourEightAndItsInertia) {
  // [docs/theory.md §6]: L = 89.14 m, W = 19.36 m, a = 20 deg, eta0 = 1.48, I_m = 1 079 100 t m^2
  // with the uniform-deck relation; the published figures are rounded to 4 digits.
  const DeckGeometry deck{89.14, 19.36, 20.0 * kDeg};
  EXPECT_NEAR(Eta0(deck), 1.48, 0.5e-2);
  EXPECT_NEAR(UniformDeckInertia(1547e3, deck), 1079100e3, 1e-3 * 1079100e3);
}

TEST(DeckGeometry, FrictionalSkewRatioOfTheWorkedExample) {
  // [docs/theory.md §4 fact 2]: a = 30 deg, eta0 = 0.87: mu = 0.08 -> eta1 = 0.99, mu = 0.10
  // -> 1.02.
  const DeckGeometry deck{1.0, WidthFromEta0(0.87, 30.0 * kDeg, 1.0), 30.0 * kDeg};
  EXPECT_NEAR(Eta1(deck, 0.08), 0.99, 0.005);
  EXPECT_NEAR(Eta1(deck, 0.10), 1.02, 0.005);
}

TEST(DeckGeometry, CornerTravelOfATranslationIsItsComponentNormalToTheEndLine) {
  // a = 30 deg: n_e = (cos 30, -sin 30) = (0.8660254037844386, -0.5).
  const DeckGeometry deck{30.0, 10.0, 30.0 * kDeg};
  EXPECT_NEAR(CornerTravelAt(deck, {0.2, -0.1, 0.0}), 0.2 * 0.8660254037844386 + 0.05, 1e-15);
  EXPECT_NEAR(CornerTravelAt(deck, {0.2, 0.1, 0.0}), 0.2 * 0.8660254037844386 - 0.05, 1e-15);
  // The bound from the maxima adds the two components whatever their signs were.
  EXPECT_NEAR(CornerTravelBound(deck, {0.2, 0.1, 0.0}), 0.2 * 0.8660254037844386 + 0.05, 1e-15);
}

TEST(DeckGeometry, CornerTravelOfARotationFollowsTheLeverArmsOfTheAcuteCorner) {
  // Turned by theta about its mass centre, corner P1 moves normal to the end line by
  // n_e . (R - E) P1 = (cos theta - 1) r_T - sin theta r_1 (n_e . P1 = r_T = L cos a / 2,
  // n_e . (-P1y, P1x) = -r_1), the obtuse P2 by the same with r_2, P3 and P4 by the opposite;
  // |r_2| < r_1, so the travel is r_1 |sin theta| + sign(theta) r_T (1 - cos theta), and the
  // bound over both signs r_1 |sin theta| + r_T (1 - cos theta) [docs/theory.md §2 lever arms].
  // L = 30, W = 10, a = 30 deg: r_1 = (15 + 10 / cos 30) / 2 = 13.273502691896258,
  // r_T = 15 cos 30 = 12.99038105676658.
  const DeckGeometry deck{30.0, 10.0, 30.0 * kDeg};
  for (double theta : {0.02, -0.02, 0.3, -0.3}) {
    const double lever = 13.273502691896258 * std::abs(std::sin(theta));
    const double chord = 12.99038105676658 * (1.0 - std::cos(theta));
    EXPECT_NEAR(CornerTravelAt(deck, {0.0, 0.0, theta}), lever + std::copysign(chord, theta), 1e-13)
        << theta;
    EXPECT_NEAR(CornerTravelBound(deck, {0.0, 0.0, std::abs(theta)}), lever + chord, 1e-13)
        << theta;
  }
}

TEST(DeckGeometry, CornerTravelOfATranslatedAndRotatedRectangleByHand) {
  // a = 0, L = 30, W = 10: n_e = x; corner (-15, -5) moves x - 15 (cos - 1) + 5 sin, the most.
  const DeckGeometry deck{30.0, 10.0, 0.0};
  const double theta = 0.01;
  EXPECT_NEAR(CornerTravelAt(deck, {0.1, 0.3, theta}),
              0.1 - 15.0 * (std::cos(theta) - 1.0) + 5.0 * std::sin(theta), 1e-15);
}

TEST(DeckGeometry, CornerTravelBoundFromTheMaximaCoversEveryInstant) {
  // Any state q is within its own maxima |q|, so the bound is never below the exact travel.
  const DeckGeometry deck{40.0, 12.0, 45.0 * kDeg};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d q(0.3 * u(rng), 0.3 * u(rng), 0.05 * u(rng));
    const double exact = CornerTravelAt(deck, q);
    EXPECT_GE(CornerTravelBound(deck, q.cwiseAbs()), exact * (1.0 - 1e-14));
  }
}

}  // namespace
}  // namespace skewbridge::model
