/// The predicates that end an accumulation of impacts (solver/dynamics/impact_history.h), each
/// on a table of histories against the mechanics it encodes [docs/theory.md §3.4-§3.6].

#include "solver/dynamics/impact_history.h"

#include <gtest/gtest.h>

#include <limits>

namespace skewbridge::dynamics::impact_history_test {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// A model with a shortest period of 0.1 s, gap tolerance 1e-12 m, v_acc 1e-6 m/s.
constexpr AccumulationScales kScales{0.1, 1e-12, 1e-6};

TEST(ImpactHistory, AccumulatingIsTheSecondImpactOfAGeometricSequence) {
  const EventPolicy policy;
  // The previous impact of this contact at t = 1 s, 0.01 m/s, and it was the last impact
  // instant of the run (sequence 5).
  const ImpactHistory h{1.0, 0.01, 5, 1.0};
  struct Row {
    long sequence;
    double t_s, approach_mps;
    bool expected;
    const char* why;
  };
  const Row rows[] = {
      {5, 1.0005, 0.005, true, "eps_N = 0.5 after 0.5 % of a period"},
      {5, 1.0005, 0.009, true, "ratio 0.9 is still a sequence"},
      {5, 1.0005, 0.0095, false, "ratio 0.95: too close to elastic"},
      {5, 1.0011, 0.005, false, "flight 1.1 % of a period: the loads change over it"},
      {5, 1.0010, 0.005, true, "flight exactly 1 % of a period"},
      {6, 1.0005, 0.005, false, "another impact came between the two"},
      {5, 1.0, 0.005, false, "no flight"},
  };
  for (const Row& r : rows) {
    EXPECT_EQ(Accumulating(h, r.sequence, r.t_s, r.approach_mps, kScales, policy), r.expected)
        << r.why;
  }
  EXPECT_FALSE(Accumulating(ImpactHistory{}, 0, 1.0, 0.005, kScales, policy)) << "no impact yet";
  EventPolicy off;
  off.zeno_extrapolation = false;
  EXPECT_FALSE(Accumulating(h, 5, 1.0005, 0.005, kScales, off)) << "rule switched off";
}

TEST(ImpactHistory, SettlingInsideTheTouchBandOrByRockingSlowly) {
  const EventPolicy policy;
  struct Row {
    ImpactHistory h;
    long sequence;
    double t_s, approach_mps;
    bool expected;
    const char* why;
  };
  const Row rows[] = {
      // Touch band: rise approach x flight / 4 against gap_tol = 1e-12 m.
      {{-kInf, 0.0, -1, 2.0}, 9, 2.0 + 4e-6, 0.9e-6, true, "rose 0.9e-12 m: never left the band"},
      {{-kInf, 0.0, -1, 2.0}, 9, 2.0 + 4e-6, 2e-6, false, "rose 2e-12 m: a resolved flight"},
      {{-kInf, 0.0, -1, 2.0}, 9, 2.0, 1e-6, false, "no flight yet"},
      // Slow rocking: its last impact was the instant before the other corner's (sequence - 1).
      {{3.0, 1e-4, 8, -kInf}, 9, 3.0005, 0.99e-4, true, "rocking at 99 v_acc, flight 0.5 % period"},
      {{3.0, 1e-4, 8, -kInf}, 9, 3.0005, 1.01e-4, false, "faster than 100 v_acc"},
      {{3.0, 1e-4, 7, -kInf}, 9, 3.0005, 1e-5, false, "not the impact just before"},
      {{3.0, 1e-4, 8, -kInf}, 9, 3.002, 1e-5, false, "flight 2 % of a period"},
  };
  for (const Row& r : rows) {
    EXPECT_EQ(Settling(r.h, r.sequence, r.t_s, r.approach_mps, kScales, policy), r.expected)
        << r.why;
  }
  EventPolicy no_band;
  no_band.settle_in_touch_band = false;
  EXPECT_FALSE(Settling(rows[0].h, 9, rows[0].t_s, rows[0].approach_mps, kScales, no_band));
  EventPolicy no_rocking;
  no_rocking.slow_rocking = false;
  EXPECT_FALSE(Settling(rows[3].h, 9, rows[3].t_s, rows[3].approach_mps, kScales, no_rocking));
}

TEST(ImpactHistory, BounceClosesWhenItsPredictedFlightIsShort) {
  // A rebound at gamma_N returns after 2 gamma_N / a under a pressing acceleration -a; closed at
  // once below 1e-3 of the shortest period (1e-4 s here).
  const EventPolicy policy;
  struct Row {
    double approach_mps, leave_mps, accel_mps2;
    bool expected;
    const char* why;
  };
  const Row rows[] = {
      {0.01, 0.005, -200.0, true, "returns after 5e-5 s"},
      {0.01, 0.005, -100.0, true, "returns after exactly 1e-4 s"},
      {0.01, 0.005, -50.0, false, "returns after 2e-4 s"},
      {0.01, 0.005, 10.0, false, "the loads pull it away: no return"},
      {0.01, 0.0095, -1e4, false, "restitution 0.95: too elastic for an accumulation"},
      {1e-6, 5e-7, -1e4, false, "an approach at v_acc is a plastic closure, not a bounce"},
  };
  for (const Row& r : rows) {
    int evaluations = 0;
    const auto accel = [&]() {
      ++evaluations;
      return r.accel_mps2;
    };
    EXPECT_EQ(BounceClosesAtOnce(r.approach_mps, r.leave_mps, accel, kScales, policy), r.expected)
        << r.why;
    EXPECT_LE(evaluations, 1);
  }
  // The acceleration is not evaluated when speeds alone decide.
  int evaluations = 0;
  BounceClosesAtOnce(
      0.01, 0.0095,
      [&]() {
        ++evaluations;
        return -1.0;
      },
      kScales, policy);
  EXPECT_EQ(evaluations, 0);
  EventPolicy off;
  off.bounce_at_once = false;
  EXPECT_FALSE(BounceClosesAtOnce(
      0.01, 0.005, [] { return -200.0; }, kScales, off));
}

}  // namespace
}  // namespace skewbridge::dynamics::impact_history_test
