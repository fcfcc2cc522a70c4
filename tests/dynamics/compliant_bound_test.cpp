// The closing bound of a compliant run's free steps (SpringGapBound, solver/dynamics/
// compliant_run.h) [docs/theory.md §3.18] against a dense evaluation of every spring's
// deformation along the exact flow, propagated on the augmented path (the matrix exponential, no
// modal code), with the deformation written here from the spring's point and face: backfill
// springs on both skewed walls and the four shear keys of an eccentric deck, random states and
// inputs, forcing alone, an undamped deck and long steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>
#include <vector>

#include "solver/dynamics/compliant_run.h"
#include "solver/dynamics/gap_bound.h"
#include "solver/dynamics/linear_flow.h"
#include "tests/dynamics/eccentric_deck.h"

namespace skewbridge::dynamics::compliant_bound_test {
namespace {

// The eccentric deck's springs: five backfill springs on each wall (P1-P2, P3-P4) and the two
// exterior keys of each abutment.
std::vector<CompliantSpring> DeckSprings(const model::Model& deck) {
  const joint::HyperbolicGap wall{4e8, 4e8, 0.7, 6e6, 0.0};
  std::vector<CompliantSpring> springs = WallSprings(deck, 0, 1, wall, 5, "+x");
  const std::vector<CompliantSpring> minus = WallSprings(deck, 2, 3, wall, 5, "-x");
  springs.insert(springs.end(), minus.begin(), minus.end());
  joint::ShearKey key;
  key.gap_m = 0.02;
  key.v_n_N = 2e6;
  key.d3_m = 0.02;
  key.dd_m = 0.1;
  for (const auto& [first, last, prefix] : {std::tuple{0, 1, "+x"}, std::tuple{3, 2, "-x"}}) {
    const std::vector<CompliantSpring> keys = AbutmentShearKeys(deck, first, last, key, prefix);
    springs.insert(springs.end(), keys.begin(), keys.end());
  }
  return springs;
}

// The deformation d = -n . (X + (x, y) + R(theta) p - A) of spring s at the positions q (m).
double Deformation(const model::Model& deck, const CompliantSpring& s, const Eigen::VectorXd& q) {
  const int b = 3 * s.body;
  const double c = std::cos(q[b + 2]), sn = std::sin(q[b + 2]);
  const Eigen::Vector2d point = deck.body(s.body).rest_position_m +
                                Eigen::Vector2d(q[b], q[b + 1]) +
                                Eigen::Vector2d(c * s.point_m.x() - sn * s.point_m.y(),
                                                sn * s.point_m.x() + c * s.point_m.y());
  return -s.face.normal.dot(point - s.face.point_m);
}

// Random steps of one kind: each spring's largest rise of d over 256 points of the step must lie
// within the bound's closure sum_k W_jk D_k.
void CheckSteps(double xi, int count, unsigned seed, double q_scale, double u_scale, double a_scale,
                double tau_s) {
  const model::Model deck = testing::EccentricDeck(xi);
  const std::vector<CompliantSpring> springs = DeckSprings(deck);
  const int ns = static_cast<int>(springs.size());
  ASSERT_EQ(ns, 14);
  LinearFlow modal(deck.M(), deck.K(), deck.C(), deck.r());
  LinearFlow augmented(deck.M(), deck.K(), deck.C(), deck.r(), FlowPath::kAugmented);
  ASSERT_TRUE(modal.modal());
  const ModalGapBound bound = SpringGapBound(modal.modal_flow(), springs);
  ASSERT_TRUE(bound.applies());
  ASSERT_EQ(bound.n_contacts, ns);
  const int n = deck.n_dof();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  double tightest = 0.0;  // the largest dense rise / bound seen
  for (int step = 0; step < count; ++step) {
    Eigen::VectorXd z = Eigen::VectorXd::Zero(modal.augmented_size());
    for (int i = 0; i < n; ++i) {
      const double length = i % 3 == 2 ? 1.0 / 15.0 : 1.0;  // theta in rad, x and y in m
      z[i] = q_scale * length * unit(rng);
      z[n + i] = u_scale * length * unit(rng);
    }
    for (int j = 0; j < 8; ++j) z[2 * n + j] = a_scale * unit(rng);
    z[2 * n + 2] *= 50.0;  // slopes of a record: the acceleration changes by 0.5 a per 0.01 s
    z[2 * n + 3] *= 50.0;
    const double omega = step % 2 == 0 ? 0.0 : 40.0 * std::abs(unit(rng));
    // The bound from the modal path's coordinates of the step's start.
    Eigen::VectorXd z_next = z;
    modal.Apply(modal.Propagator(tau_s, omega, false), z, z_next);
    std::vector<double> drift(static_cast<std::size_t>(bound.n_modes));
    ModalDrift(bound, modal.modal_coordinates().data(), tau_s, drift.data());
    // The dense rise along the augmented flow.
    constexpr int kPoints = 256;
    const FreePropagator& p = augmented.Propagator(tau_s / kPoints, omega, false);
    std::vector<double> d0(static_cast<std::size_t>(ns)), rise(static_cast<std::size_t>(ns), 0.0);
    for (int j = 0; j < ns; ++j) d0[j] = Deformation(deck, springs[j], z.head(n));
    Eigen::VectorXd zz = z, zz_next = z;
    for (int i = 1; i <= kPoints; ++i) {
      augmented.Apply(p, zz, zz_next);
      zz.swap(zz_next);
      for (int j = 0; j < ns; ++j) {
        rise[j] = std::max(rise[j], Deformation(deck, springs[j], zz.head(n)) - d0[j]);
      }
    }
    for (int j = 0; j < ns; ++j) {
      const double closure = GapClosureBound(bound, j, drift.data());
      // The bound is exact arithmetic of the flow; the dense deformations carry the rounding of
      // the deck's world coordinates (about 1e-15 m) on top.
      ASSERT_LE(rise[j], closure + 1e-13) << "step " << step << " spring " << springs[j].name;
      if (closure > 0.0) tightest = std::max(tightest, rise[j] / closure);
    }
  }
  // A bound of no use (far above the motion) would pass the check above too: the largest rise
  // reaches 0.44-0.48 of the bound in these cases.
  EXPECT_GT(tightest, 0.3);
}

TEST(SpringGapBound, HoldsOnRandomStepsOfADampedDeck) {
  CheckSteps(0.05, 200, 11, 0.05, 0.5, 5.0, 0.01);
}

TEST(SpringGapBound, HoldsOnAnUndampedDeckAndLongSteps) {
  CheckSteps(0.0, 100, 12, 0.05, 0.5, 5.0, 0.05);
}

TEST(SpringGapBound, HoldsUnderForcingAloneFromRest) {
  CheckSteps(0.05, 100, 13, 0.0, 0.0, 5.0, 0.02);
}

TEST(SpringGapBound, HoldsOnFreeVibrationOfLargeRotation) {
  // No input, rotation dominant: the arm's term carries the closure.
  CheckSteps(0.05, 100, 14, 0.3, 3.0, 0.0, 0.01);
}

TEST(SpringGapBound, DoesNotApplyToASpringOnABodyOrNegativeDamping) {
  const model::Model deck = testing::EccentricDeck(0.05);
  std::vector<CompliantSpring> springs = DeckSprings(deck);
  LinearFlow modal(deck.M(), deck.K(), deck.C(), deck.r());
  EXPECT_TRUE(SpringGapBound(modal.modal_flow(), springs).applies());
  // A model whose C is the negative of a classical damping (an energy source).
  LinearFlow source(deck.M(), deck.K(), -deck.C(), deck.r());
  ASSERT_TRUE(source.modal());
  EXPECT_FALSE(SpringGapBound(source.modal_flow(), springs).applies());
  // One spring against a face on a body (a deck-deck joint): its face moves with that body.
  springs.back().face.body = 0;
  EXPECT_FALSE(SpringGapBound(modal.modal_flow(), springs).applies());
}

}  // namespace
}  // namespace skewbridge::dynamics::compliant_bound_test
