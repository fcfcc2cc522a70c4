// Events inside one exact free step are found, never stepped over [docs/theory.md §3]: a free deck
// (K = C = 0, so the whole 1 s excitation piece is a single step) moves towards the +x abutment
// while the ground pushes it back. Its gap g(t) = g0 - v t + a t^2 / 2 dips below zero and is
// positive again at both ends of the step (times cos a, the face's obliquity); the impact must be
// located at the closed-form root, and a dip that stays above zero must give no event.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "records/excitations.h"
#include "solver/dynamics/simulate.h"
#include "tests/contact/test_models.h"

namespace skewbridge::dynamics::event_location_test {
namespace {

constexpr double kSkew = 30.0 * std::numbers::pi / 180.0;

// a = 30 deg, eta0 = 0.8: both corners of the +x end at gap g0 cos a (delta = g0), closing
// together while the deck translates along x.
RunResult Graze(double g0, double v_mps, double a_mps2) {
  const model::Model m =
      contact::testing::FreeDeck(30.0, 0.8, 20.0, g0, 0.5, 0.0, model::AbutmentSet::kPlusX, 1.0);
  InitialState initial;
  initial.q = Eigen::Vector3d::Zero();
  initial.u = Eigen::Vector3d(v_mps, 0.0, 0.0);
  // The relative acceleration is -a_g along x: a_g > 0 pulls the deck back from the face.
  const records::SampledExcitation push(1.0, {a_mps2, a_mps2});
  model::RunControl control;
  control.end_time_s = 1.0;
  SimulationWorkspace ws(m);
  return Simulate(m, push, control, ws, initial);
}

TEST(Simulate, GrazingDipInsideOneFreeStepIsLocatedAtTheClosedFormRoot) {
  const double v = 0.1, a = 4.9;
  // g_min = (g0 - v^2 / (2 a)) cos a = -0.87e-6 m at t = v / a = 0.0204 s; at t = 1 s the gap
  // is 2 m.
  const double g0 = v * v / (2.0 * a) - 1e-6;
  const RunResult r = Graze(g0, v, a);
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  EXPECT_EQ(r.free_steps, 2);  // up to the impact, then the rest of the piece
  ASSERT_GE(r.events.size(), 1u);
  const double t_root = (v - std::sqrt(v * v - 2.0 * a * g0)) / a;
  EXPECT_EQ(r.events.front().kind, EventKind::kImpact);
  EXPECT_NEAR(r.events.front().t_s, t_root, 1e-12);
  // Approach speed at the root: (v - a t) cos a.
  EXPECT_NEAR(-r.events.front().gamma_N_before_mps, (v - a * t_root) * std::cos(kSkew), 1e-9);
  EXPECT_EQ(r.impacts, 1);
}

TEST(Simulate, DipThatStaysAboveZeroGivesNoEvent) {
  const double v = 0.1, a = 4.9;
  const RunResult r = Graze(v * v / (2.0 * a) + 1e-6, v, a);  // g_min = +0.87e-6 m
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  EXPECT_EQ(r.impacts, 0);
  EXPECT_TRUE(r.events.empty());
  // Maxima inside the step: x peaks at v^2 / (2 a) when the velocity crosses zero.
  EXPECT_NEAR(r.max_abs_q[0], 0.5 * a * 1.0 - v, 1e-12);  // |x(1)| = a/2 - v beats the peak
}

}  // namespace
}  // namespace skewbridge::dynamics::event_location_test
