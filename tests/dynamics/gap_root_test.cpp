/// FirstGapRoot (solver/dynamics/event_location.h) on analytic gap functions, each against its
/// closed-form first root [docs/theory.md §3.12].

#include "solver/dynamics/event_location.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace skewbridge::dynamics {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kGapTol = 1e-12;  // m
constexpr double kVTol = 1e-10;    // m/s

// g(t) = c0 + c1 t + c2 t^2 / 2 (a contact under constant acceleration): gap and rate.
struct Parabola {
  double c0, c1, c2;
  double g(double t) const { return c0 + c1 * t + 0.5 * c2 * t * t; }
  double rate(double t) const { return c1 + c2 * t; }
  // Its first root after t0 (the smaller root above t0), or +inf.
  double FirstRoot(double t0) const {
    if (c2 == 0.0) {
      const double r = -c0 / c1;
      return r > t0 ? r : kInf;
    }
    const double d = c1 * c1 - 2.0 * c2 * c0;
    if (d < 0.0) {
      return kInf;
    }
    const double r1 = (-c1 - std::sqrt(d)) / c2, r2 = (-c1 + std::sqrt(d)) / c2;
    const double lo = std::min(r1, r2), hi = std::max(r1, r2);
    return lo > t0 ? lo : (hi > t0 ? hi : kInf);
  }
};

double Root(const Parabola& p, double t0, double t1, const EventPolicy& policy = {}) {
  return FirstGapRoot(
      t0, t1, p.g(t0), p.rate(t0), p.g(t1), p.rate(t1), [&](double t) { return p.g(t); },
      [&](double t) { return p.rate(t); }, kGapTol, kVTol, policy);
}

TEST(GapRoot, FindsTheFirstClosureOfAnalyticGaps) {
  struct Row {
    Parabola p;
    double t0, t1;
    const char* why;
  };
  const Row rows[] = {
      {{1e-3, -0.1, 0.0}, 0.0, 0.02, "constant approach: closes at 0.01 s"},
      {{1e-3, -0.1, 2.0}, 0.0, 0.02, "decelerating approach that still closes"},
      {{1e-3, -0.1, 4.0}, 0.0, 0.05, "a dip: closes and reopens inside the step (ends open)"},
      {{1.551, -0.05, -3.0}, 1.0, 1.02, "accelerating approach in a later step"},
  };
  for (const Row& r : rows) {
    const double expected = r.p.FirstRoot(r.t0);
    ASSERT_LT(expected, r.t1) << r.why;
    const double t = Root(r.p, r.t0, r.t1);
    EXPECT_NEAR(t, expected, 1e-12) << r.why;
    EXPECT_LE(r.p.g(t), 0.0) << r.why << ": the impact must see a closed gap";
  }
}

TEST(GapRoot, NoRootWhereTheGapStaysOpen) {
  struct Row {
    Parabola p;
    double t0, t1;
    const char* why;
  };
  const Row rows[] = {
      {{1e-3, 0.1, 0.0}, 0.0, 0.02, "separating"},
      {{1e-3, -0.01, 0.0}, 0.0, 0.02, "approaching, but not within the step"},
      {{1e-3, -0.1, 20.0}, 0.0, 0.02, "a dip whose minimum stays above zero"},
  };
  for (const Row& r : rows) {
    EXPECT_EQ(Root(r.p, r.t0, r.t1), kInf) << r.why;
  }
}

TEST(GapRoot, AContactThatJustOpenedClosesWhereItsSeparationTurns) {
  // Opened at t0 = 0 with a small separating speed and a pressing acceleration: it flies
  // g = v t - a t^2 / 2 and returns at 2 v / a.
  const Parabola p{0.0, 1e-3, -10.0};
  const double t = Root(p, 0.0, 0.001);
  EXPECT_NEAR(t, 2e-4, 1e-12);
  // Resting in touch (gap, rate and acceleration zero): no impact.
  const Parabola q{0.0, 0.0, 0.0};
  EXPECT_EQ(Root(q, 0.0, 0.001), kInf) << "resting in touch: no impact";
}

TEST(GapRoot, TouchProbesFindTheReturnOfAContactOpenedWithZeroRate) {
  // Opened at t0 = 0 with gap and rate zero (the contact problem's answer) and a separating
  // acceleration of 1 m/s^2 that reverses at 1000 m/s^3: g = t^2 / 2 - 1000 t^3 / 6, rate
  // t - 500 t^2, positive on (0, 2 ms), the gap largest at 2 ms and closing again at 3 ms. The
  // step [0, 4 ms] ends closed and approaching; only a probe inside (0, 2 ms) sees the
  // separation (t0 + 4 ms / 4 = 1 ms here), from which the gap's maximum and then its root are
  // bracketed. Without probes the step's start is taken as the impact: t0.
  const double jerk = 1000.0, t0 = 0.0, t1 = 4e-3;
  const auto g = [&](double t) { return 0.5 * t * t - jerk * t * t * t / 6.0; };
  const auto rate = [&](double t) { return t - 0.5 * jerk * t * t; };
  ASSERT_EQ(g(t0), 0.0);
  ASSERT_EQ(rate(t0), 0.0);
  ASSERT_LT(g(t1), 0.0);
  ASSERT_LT(rate(t1), 0.0);
  const double expected = 3.0 / jerk;  // t^2 / 2 = jerk t^3 / 6
  const double t = FirstGapRoot(t0, t1, g(t0), rate(t0), g(t1), rate(t1), g, rate, kGapTol, kVTol,
                                EventPolicy{});
  EXPECT_NEAR(t, expected, 1e-12);
  EXPECT_LE(g(t), 0.0) << "the impact must see a closed gap";
  EventPolicy no_probes;
  no_probes.touch_probes = 0;
  EXPECT_EQ(
      FirstGapRoot(t0, t1, g(t0), rate(t0), g(t1), rate(t1), g, rate, kGapTol, kVTol, no_probes),
      t0);
}

TEST(GapRoot, AMinimumAtTheStepStartIsNotAnImpact) {
  // A gap that the decision at t0 has just left open, whose dense output dips 8e-17 m below
  // zero (rounding) 1.5e-13 s after t0, inside the start-of-step band of two event-time
  // brackets (2e-13 s): no impact there, which would repeat the decision at the same instant.
  // Without the band the dip is taken for an impact before its minimum.
  const double t0 = 1.0, t1 = 1.001, tm = t0 + 1.5e-13, c = 1e10, depth = 8e-17;
  const auto g = [&](double t) { return -depth + 0.5 * c * (t - tm) * (t - tm); };
  const auto rate = [&](double t) { return c * (t - tm); };
  ASSERT_GT(g(t0), 0.0);
  EXPECT_EQ(FirstGapRoot(t0, t1, g(t0), rate(t0), g(t1), rate(t1), g, rate, kGapTol, kVTol,
                         EventPolicy{}),
            kInf);
  EventPolicy no_band;
  no_band.start_minimum_band = 0.0;
  const double t =
      FirstGapRoot(t0, t1, g(t0), rate(t0), g(t1), rate(t1), g, rate, kGapTol, kVTol, no_band);
  EXPECT_GT(t, t0);
  EXPECT_LE(t, tm);
}

}  // namespace
}  // namespace skewbridge::dynamics
