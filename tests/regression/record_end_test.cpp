/// @file
/// A sampled record whose end time (n - 1) dt, divided by dt, rounds below n - 1 (13548 x 0.005:
/// 67.74 / 0.005 = 13547.999..., 12063 x 0.0029, and with dt = 0.005 already 30 samples; four
/// records of jobs/specs/real/pilot-study-shared.toml, RSN288_ITALY_A-BRZ000, CHV1-20140203E,
/// LXR1-20140203E and LXR1-20140203N). SampledExcitation::PieceAt(t) must return the rest piece
/// for any t at or past the end time itself, not the last ramp [(n - 2) dt, (n - 1) dt) that
/// floor(t / dt) = n - 2 points to: with that ramp the integrator's next stop is t itself, and it
/// takes zero-length steps until max_steps (docs/validation.md, "Records whose last sample rounds
/// down").

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "records/excitations.h"
#include "solver/dynamics/simulate.h"
#include "solver/model/builders.h"
#include "spectra/point.h"

namespace skewbridge::record_end_test {
namespace {

/// n samples of a_g sin(w t) at interval dt (m/s^2).
std::vector<double> SineSamples(int n, double dt_s, double a_mps2, double w_radps) {
  std::vector<double> a(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k)
    a[static_cast<std::size_t>(k)] = a_mps2 * std::sin(w_radps * k * dt_s);
  return a;
}

/// True when floor((n - 1) dt / dt) < n - 1 in double arithmetic: the record end whose piece
/// lookup goes wrong.
bool EndRoundsDown(int n, double dt_s) {
  const double end_s = static_cast<double>(n - 1) * dt_s;
  return std::floor(end_s / dt_s) < static_cast<double>(n - 1);
}

TEST(RecordEnd, TheSampleCountsOfTheStepLimitRecordsRoundDownAtTheEnd) {
  // The four records of the step-limit cells, and a 30-sample record at 0.005 s, are of the
  // kind; their neighbours (and the 35 records that ran) are not.
  EXPECT_TRUE(EndRoundsDown(13549, 0.005));   // CHV1-20140203E, LXR1-20140203E/N
  EXPECT_TRUE(EndRoundsDown(12064, 0.0029));  // RSN288_ITALY_A-BRZ000
  EXPECT_TRUE(EndRoundsDown(30, 0.005));
  EXPECT_FALSE(EndRoundsDown(31, 0.005));
  EXPECT_FALSE(EndRoundsDown(5372, 0.01));   // RSN6_IMPVALL.I_I-ELC180, status ok
  EXPECT_FALSE(EndRoundsDown(8773, 0.005));  // RSN1084_NORTHR_SCS052, status ok
}

TEST(RecordEnd, PieceAtTheLastSampleIsTheRestPiece) {
  // After the last sample the ground is at rest: the piece at t = (n - 1) dt must start there
  // and never end, whatever the rounding of (n - 1) dt / dt.
  for (const auto& [n, dt_s] : {std::pair{30, 0.005}, {13549, 0.005}, {12064, 0.0029}}) {
    SCOPED_TRACE(::testing::Message() << "n = " << n << ", dt = " << dt_s);
    const records::SampledExcitation excitation(dt_s, SineSamples(n, dt_s, 1.0, 5.0));
    const double end_s = excitation.Duration();
    const ExcitationPiece piece = excitation.PieceAt(end_s);
    EXPECT_GT(piece.t_end, end_s) << "a piece that ends where it is asked for stalls the run";
    EXPECT_EQ(piece.t_end, std::numeric_limits<double>::infinity());
    EXPECT_EQ(excitation.At(end_s + 1.0), Eigen::Vector2d::Zero());
  }
}

/// The pilot bridge of the study at Pi_delta = 0.5 under a 30-sample record, run as
/// spectra::EvaluatePoint runs a cell (same tolerances and end time) but with a budget of
/// 100 000 steps instead of 10 million.
dynamics::RunResult RunPilotBridge(int n) {
  const double dt_s = 0.005;
  const double w_g_radps = 5.0;
  const double a_g_mps2 = 1.0;
  spectra::PointParameters p;
  p.family = spectra::Family::kPilotBridge;
  p.Pi_delta = 0.5;
  p.mu = 0.3;
  const spectra::DimensionalPoint point = spectra::ToDimensional(p, {a_g_mps2, w_g_radps});
  const model::Model model = model::BuildDeckModel(point.deck, "pilot");
  const records::SampledExcitation excitation(dt_s, SineSamples(n, dt_s, a_g_mps2, w_g_radps));
  model::RunControl control;
  control.absolute_tolerance = 1e-11 * point.persistency_m;
  control.end_time_s = excitation.Duration() + 2.0 * 2.0 * std::numbers::pi / w_g_radps;
  control.max_steps = 100000;
  dynamics::SimulationWorkspace workspace(model);
  return dynamics::Simulate(model, excitation, control, workspace);
}

TEST(RecordEnd, PilotBridgeRunsPastTheEndOfARecordWhoseEndRoundsDown) {
  // n = 31 always ended cleanly; n = 30 stalled at t = 29 dt = 0.145 s with zero-length exact
  // steps until the budget ran out (status step-limit, no event). Both must reach the end
  // time with about one exact step per sample interval plus the free vibration after it, so
  // their step counts differ by about one sample's worth.
  const dynamics::RunResult reference = RunPilotBridge(31);
  ASSERT_EQ(reference.status, dynamics::RunStatus::kOk) << reference.message;
  const dynamics::RunResult run = RunPilotBridge(30);
  EXPECT_EQ(run.status, dynamics::RunStatus::kOk) << run.message;
  EXPECT_DOUBLE_EQ(run.end_time_s, 29 * 0.005 + 4.0 * std::numbers::pi / 5.0);
  EXPECT_EQ(run.impacts, 0);  // |x| << delta: the deck never reaches the abutments
  EXPECT_LE(std::abs(run.free_steps - reference.free_steps), 3);
}

}  // namespace
}  // namespace skewbridge::record_end_test
