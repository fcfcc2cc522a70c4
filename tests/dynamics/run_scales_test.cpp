/// Run scales (solver/dynamics/run_scales.h): self-similarity (a_g x k scales every velocity,
/// force and gap tolerance by k, the steps not at all), the floors of the gap tolerance and of a
/// free body, and the peak of an excitation from its pieces [docs/theory.md §3.2, §4 fact 4].

#include "solver/dynamics/run_scales.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "records/excitations.h"

namespace skewbridge::dynamics::run_scales_test {
namespace {

// A deck of 30 m with natural frequencies 2 and 40 rad/s and a 1e6 kg deck mass.
constexpr ModelScales kDeck{2.0, 40.0, 30.0, 1e6};
constexpr double kAccumulation = 1e-6;

TEST(RunScales, ScalingTheExcitationScalesEveryToleranceByK) {
  const EventPolicy policy;
  const double a_peak = 30.0, u0 = 0.0;
  const RunScales base = ComputeRunScales(a_peak, u0, kDeck, kAccumulation, policy);
  struct Row {
    double k;
    double rel;  // allowed relative difference from exact k scaling (0: the same bits)
  };
  // Powers of two scale every product exactly; other factors to a few roundings.
  for (const Row& row : {Row{2.0, 0.0}, Row{0.5, 0.0}, Row{1024.0, 0.0}, Row{3.7, 4e-16},
                         Row{0.13, 4e-16}, Row{0.013, 4e-16}, Row{250.0, 4e-16}}) {
    const RunScales s = ComputeRunScales(row.k * a_peak, row.k * u0, kDeck, kAccumulation, policy);
    const auto expect_scaled = [&](double scaled, double unscaled, const char* what) {
      EXPECT_NEAR(scaled, row.k * unscaled, row.rel * std::abs(row.k * unscaled))
          << what << " at k = " << row.k;
    };
    expect_scaled(s.v_ref_mps, base.v_ref_mps, "v_ref");
    expect_scaled(s.v_acc_mps, base.v_acc_mps, "v_acc");
    expect_scaled(s.v_tol_mps, base.v_tol_mps, "v_tol");
    expect_scaled(s.force_tol_N, base.force_tol_N, "force_tol");
    expect_scaled(s.a_detach_mps2, base.a_detach_mps2, "a_detach");
    // The gap tolerance scales between its rounding floor and the deck-size cap.
    const double floor = 64.0 * std::numeric_limits<double>::epsilon() * kDeck.length_m;
    const double cap = 1e-12 * kDeck.length_m;
    if (row.k * base.gap_tol_m > floor && row.k * base.gap_tol_m < cap) {
      expect_scaled(s.gap_tol_m, base.gap_tol_m, "gap_tol");
    }
    EXPECT_EQ(s.first_rk_step_s, base.first_rk_step_s);
    EXPECT_EQ(s.period_min_s, base.period_min_s);
    EXPECT_EQ(s.omega_ref_radps, base.omega_ref_radps);
  }
  // The values themselves: v_ref = a_peak / omega_min, each tolerance its fraction of it.
  EXPECT_EQ(base.v_ref_mps, 15.0);
  EXPECT_EQ(base.v_tol_mps, 1e-10 * 15.0);
  EXPECT_EQ(base.gap_tol_m, 1e-12 * (15.0 / 2.0));
  EXPECT_EQ(base.force_tol_N, 1e-7 * 1e6 * 15.0 * 2.0);
  EXPECT_DOUBLE_EQ(base.period_min_s, 2.0 * std::numbers::pi / 40.0);
  EXPECT_DOUBLE_EQ(base.first_rk_step_s, base.period_min_s / 20.0 / 4.0);
}

TEST(RunScales, FloorsHoldWhereScalingCannot) {
  const EventPolicy policy;
  // A tiny excitation: the gap tolerance stops at the rounding of a world-coordinate gap.
  const double floor = 64.0 * std::numeric_limits<double>::epsilon() * kDeck.length_m;
  for (double a : {1e-9, 1e-12}) {
    EXPECT_EQ(ComputeRunScales(a, 0.0, kDeck, kAccumulation, policy).gap_tol_m, floor);
  }
  // A huge one: the displacement scale is capped by the deck's size.
  EXPECT_EQ(ComputeRunScales(1e9, 0.0, kDeck, kAccumulation, policy).gap_tol_m, 1e-12 * 30.0);
  // Initial velocities above a_peak / omega set v_ref; rest and no excitation give 1 m/s.
  EXPECT_EQ(ComputeRunScales(3.0, 7.0, kDeck, kAccumulation, policy).v_ref_mps, 7.0);
  EXPECT_EQ(ComputeRunScales(0.0, 0.0, kDeck, kAccumulation, policy).v_ref_mps, 1.0);
  // A free body: omega_ref 1 rad/s, no shortest period, steps from the frequency floor.
  const RunScales free = ComputeRunScales(3.0, 0.0, {0.0, 0.0, 30.0, 1e6}, kAccumulation, policy);
  EXPECT_EQ(free.omega_ref_radps, 1.0);
  EXPECT_EQ(free.v_ref_mps, 3.0);
  EXPECT_EQ(free.period_min_s, std::numeric_limits<double>::infinity());
  EXPECT_EQ(free.omega_top_radps, 1e-3);
}

TEST(RunScales, ExcitationPeakOfAPulse) {
  // A cosine and a sine pulse of amplitude a_p: the peak is a_p.
  const records::PulseExcitation pulse(records::PulseShape::kCosine, 4.0, 2.0 * std::numbers::pi);
  EXPECT_NEAR(ExcitationPeak(pulse, 1e3), 4.0, 1e-12);
  const records::PulseExcitation sine(records::PulseShape::kSine, 2.5, std::numbers::pi);
  EXPECT_NEAR(ExcitationPeak(sine, 1e3), 2.5, 1e-12);
}

}  // namespace
}  // namespace skewbridge::dynamics::run_scales_test
