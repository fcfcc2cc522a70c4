/// FirstGapRoot and ImpactSuspected (solver/dynamics/event_location.h) on analytic gap
/// functions, each against its closed-form first root or minimum [docs/theory.md §3.12].

#include "solver/dynamics/event_location.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

namespace skewbridge::dynamics::gap_root_test {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kGapTol = 1e-12;  // m
constexpr double kVTol = 1e-10;    // m/s

// g(t) = c0 + c1 t + c2 t^2 / 2 (a contact under constant acceleration): gap and rate.
struct Parabola {
  double c0, c1, c2;
  double g0() const { return c0; }
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

// --- Impact suspicion [§3.12] -----------------------------------------------------------------

// Whether a step is searched for an impact, from the gap's values and rates at its ends, on
// parabolas (a constant normal acceleration) over a step [0, tau]: a gap that ends closed, or
// dips by more than the free step's margin allows, is suspected; one that dips far less is not
// (the free step's saving); the constrained step's kEveryDip suspects every dip; a gap that does
// not dip and ends open never is.
TEST(ImpactSuspicion, SuspectsTheStepsWhoseGapMayClose) {
  const double tau = 0.01;  // s
  const double margin = EventPolicy{}.dip_margin;
  struct Row {
    Parabola p;
    bool free_step;         // suspected with the free step's margin
    bool constrained_step;  // suspected with kEveryDip
    const char* why;
  };
  const Row rows[] = {
      {{1e-4, -0.02, 0.0}, true, true, "constant approach that closes at 5 ms"},
      {{1e-5, -0.02, 4.0}, true, true, "a dip that closes and reopens inside the step"},
      {{1e-4, -0.02, 4.0},
       true,
       true,
       "a dip that stays open, within the margin of the bound (1e-4 <= 2 x 0.02 x 0.01 / 2)"},
      {{1e-2, -0.02, 4.0}, false, true, "a dip far above the face (min g 0.995 cm)"},
      {{1e-4, 0.02, 1.0}, false, false, "separating"},
      {{1e-4, -0.005, 0.0}, false, false, "approaching, still open at the step's end"},
  };
  for (const Row& r : rows) {
    const Parabola& p = r.p;
    EXPECT_EQ(ImpactSuspected(p.g(0), p.rate(0), p.g(tau), p.rate(tau), tau, margin), r.free_step)
        << r.why;
    EXPECT_EQ(ImpactSuspected(p.g(0), p.rate(0), p.g(tau), p.rate(tau), tau, kEveryDip),
              r.constrained_step)
        << r.why;
  }
}

// The bound behind the free step's test: a gap whose normal acceleration keeps its sign over the
// step (gamma_N increasing) lies at most max(-gN0, gN1) tau / 2 below min(g0, g1), so no root is
// missed even without the margin (dip_margin = 1). Checked on 20 000 seeded gaps that dip, each
// placed so that its minimum (in closed form) lies near zero:
// - parabolas, gamma_N from -a to +b at a constant acceleration (a + b) / tau, minimum
//   g0 - a^2 tau / (2 (a + b)): they come within half the bound;
// - hyperbolas g_min + sqrt(c^2 + k^2 (t - t_m)^2) - c with c << k tau, a sharp turn of the rate
//   from about -k to +k at t_m: they reach the bound, so a test at half of it misses roots.
TEST(ImpactSuspicion, MissesNoRootOfAGapWhoseAccelerationKeepsItsSign) {
  std::mt19937_64 rng(30);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double tau = 0.01;
  int closing = 0, missed_at_half = 0;
  const auto check = [&](const auto& g, const auto& rate, double g_min, const std::string& what) {
    if (!(g_min <= 0.0)) {
      return;
    }
    ++closing;
    EXPECT_TRUE(ImpactSuspected(g(0.0), rate(0.0), g(tau), rate(tau), tau, 1.0)) << what;
    missed_at_half += ImpactSuspected(g(0.0), rate(0.0), g(tau), rate(tau), tau, 0.5) ? 0 : 1;
  };
  for (int i = 0; i < 10000; ++i) {
    const double a = 0.5 * (1.0 - unit(rng)), b = 0.5 * (1.0 - unit(rng));  // (0, 0.5] m/s
    const double depth = a * a * tau / (2.0 * (a + b));  // of the minimum below g0 (m)
    const Parabola p{depth * (0.5 + unit(rng)), -a, (a + b) / tau};
    check([&](double t) { return p.g(t); }, [&](double t) { return p.rate(t); }, p.g0() - depth,
          "parabola a " + std::to_string(a) + " b " + std::to_string(b));
  }
  const int parabolas_missed_at_half = missed_at_half;
  for (int i = 0; i < 10000; ++i) {
    const double k = 0.5 * (1.0 - unit(rng)), t_m = tau * (0.05 + 0.9 * unit(rng));
    const double c = 1e-3 * k * tau * unit(rng);
    const double g_min = (unit(rng) - 0.5) * 0.5 * k * tau;
    const auto g = [&](double t) {
      return g_min + std::sqrt(c * c + k * k * (t - t_m) * (t - t_m)) - c;
    };
    const auto rate = [&](double t) {
      return k * k * (t - t_m) / std::sqrt(c * c + k * k * (t - t_m) * (t - t_m));
    };
    check(g, rate, g_min, "hyperbola k " + std::to_string(k) + " t_m " + std::to_string(t_m));
  }
  EXPECT_GT(closing, 8000);
  EXPECT_EQ(parabolas_missed_at_half, 0) << "a parabola comes within half the bound";
  EXPECT_GT(missed_at_half, 1000) << "the bound is reached: half of it misses roots";
}

}  // namespace
}  // namespace skewbridge::dynamics::gap_root_test
