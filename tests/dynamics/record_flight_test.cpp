// A deck's record flight (Integrator::DeckRecordSteps: the state, the piece, the plan's cache, the
// maxima and the counts in locals, the gap floors' drifts from the transition's lanes) against the
// general flight loop, which a run takes while an observer sees its free steps: every result's
// bits (maxima and their times, the end state, the corner travel, the counts, the events), for the
// pilot bridge without contacts and at two gaps, under records along x and at an angle (y samples
// too), with and without history samples; and its tests in lanes (the coordinates' maxima, the
// corners' reach) against the scalar functions they stand for, on drawn and tied values.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <string>

#include "records/excitations.h"
#include "records/incidence.h"
#include "solver/dynamics/coordinate_maxima.h"
#include "solver/dynamics/corner_travel.h"
#include "solver/dynamics/simulate.h"
#include "tests/dynamics/benchmark_cases.h"
#include "tests/dynamics/run_bits.h"

namespace skewbridge::dynamics::record_flight_test {
namespace {

using testing::PassThrough;

TEST(RecordFlight, ADecksStepsAreTheBitsOfTheGeneralLoop) {
  for (const double gap_m : {0.0, bench::kPilotStudyGap_m, bench::kPilotStressGap_m}) {
    const model::Model model = bench::PilotBridge(gap_m > 0.0, gap_m);
    for (const double angle_deg : {0.0, 30.0}) {
      for (const unsigned seed : {12345u, 7u}) {
        for (const double output_s : {0.0, 0.05}) {
          SCOPED_TRACE("gap " + std::to_string(gap_m) + " m, angle " + std::to_string(angle_deg) +
                       " deg, seed " + std::to_string(seed) + ", output " +
                       std::to_string(output_s) + " s");
          records::GroundMotion motion;
          motion.dt_s = 0.01;
          motion.acc_mps2 = bench::RecordLikeSignal(seed);
          const Eigen::Vector2d direction =
              angle_deg == 0.0 ? Eigen::Vector2d::UnitX() : records::DirectionAt(angle_deg);
          const records::SampledExcitation excitation =
              records::ScaledExcitation(motion, 1.0, direction);
          ASSERT_EQ(excitation.Samples().ay_mps2 != nullptr, angle_deg != 0.0);
          model::RunControl control;
          control.end_time_s = 20.0;
          control.energy_ledger = false;  // the record flight's condition
          control.output_interval_s = output_s;
          SimulationWorkspace ws(model);
          const RunResult deck = Simulate(model, excitation, control, ws);
          PassThrough seen;
          SimulationWorkspace ws_general(model);
          const RunResult general = Simulate(model, excitation, control, ws_general, {}, {}, &seen);
          testing::ExpectSameRunBits(deck, general);
          ASSERT_EQ(deck.histories.t_s.size(), general.histories.t_s.size());
          // The general loop took the steps up to the first event (every step without contacts).
          EXPECT_GT(seen.steps, gap_m > 0.0 ? 10 : deck.free_steps - 10);
          EXPECT_GT(deck.free_steps, 1000);
          if (gap_m == bench::kPilotStressGap_m) {
            EXPECT_GT(deck.impacts, 0);
          }
        }
      }
    }
  }
}

// A value from a small pool (so that ends, maxima and products tie, and signed zeros meet) or
// drawn over decades.
double Draw(std::mt19937_64& rng) {
  static constexpr double kPool[] = {0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 1e-300, -1e-300, 2.0};
  std::uniform_int_distribution<int> pick(0, 12);
  const int k = pick(rng);
  if (k < 9) {
    return kPool[k];
  }
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> decade(-6, 2);
  return mantissa(rng) * std::pow(10.0, decade(rng));
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(RecordFlight, LaneMaximaAreTheScalarMaxima) {
  std::mt19937_64 rng(2011);
  long searched = 0, raised = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    double q0[3], u0[3], q1[3], u1[3], max_scalar[3], time_scalar[3];
    CoordinateLanes x0[3], x1[3];
    for (int i = 0; i < 3; ++i) {
      q0[i] = Draw(rng);
      u0[i] = Draw(rng);
      q1[i] = Draw(rng);
      u1[i] = Draw(rng);
      max_scalar[i] = std::abs(Draw(rng));
      time_scalar[i] = -1.0;
      x0[i] = CoordinateLanes{q0[i], u0[i]};
      x1[i] = CoordinateLanes{q1[i], u1[i]};
    }
    double max_lanes[3], time_lanes[3];
    std::memcpy(max_lanes, max_scalar, sizeof max_lanes);
    std::memcpy(time_lanes, time_scalar, sizeof time_lanes);
    const double t1 = 3.0, h = Draw(rng) == 0.0 ? 0.0 : 0.01;
    const bool scalar = RaiseMaximaAtEnd(3, q0, u0, t1, q1, u1, h, max_scalar, time_scalar);
    double bound[3] = {-1.0, -1.0, -1.0};
    const int each = RaiseMaximaAtEnd3Each(x0, x1, t1, h, max_lanes, time_lanes, bound);
    ASSERT_EQ(each != 0, scalar) << "trial " << trial;
    for (int i = 0; i < 3; ++i) {
      ASSERT_TRUE(SameBits(max_lanes[i], max_scalar[i])) << "trial " << trial << ", q" << i;
      ASSERT_TRUE(SameBits(time_lanes[i], time_scalar[i])) << "trial " << trial << ", q" << i;
      raised += time_scalar[i] == t1;
      // Coordinate i on its own: RaiseMaximaAtEnd's search test with the raised maximum, and
      // the cheap hull's peak as it writes it.
      const double hull = std::max(std::abs(q0[i]), std::abs(q1[i])) +
                          0.5 * h * std::max(std::abs(u0[i]), std::abs(u1[i]));
      const bool searches = u0[i] * u1[i] < 0.0 && hull > max_scalar[i];
      ASSERT_EQ((each >> i) & 1, searches ? 1 : 0) << "trial " << trial << ", q" << i;
      if (searches) {
        ASSERT_TRUE(SameBits(bound[i], hull)) << "trial " << trial << ", q" << i;
      }
    }
    searched += scalar;
  }
  // Both outcomes of every test were met.
  EXPECT_GT(searched, 1000);
  EXPECT_LT(searched, 199000);
  EXPECT_GT(raised, 1000);
}

TEST(RecordFlight, LaneReachIsTheScalarReach) {
  const model::Model model = bench::PilotBridge(true, bench::kPilotStudyGap_m);
  const CornerTravelTracker travel(model);
  ASSERT_EQ(travel.decks(), 1);
  const CornerTravelTracker::ReachConstants constants = travel.reach_constants(0);
  std::mt19937_64 rng(62);
  long may = 0;
  for (int trial = 0; trial < 100000; ++trial) {
    double x[2][3], v[2][3];
    CornerTravelTracker::ReachLanes lanes[2][3];
    double reach[2], speed[2];
    CornerTravelTracker::ReachLanes end[2];
    for (int e = 0; e < 2; ++e) {
      for (int i = 0; i < 3; ++i) {
        x[e][i] = 0.01 * Draw(rng);
        v[e][i] = 0.1 * Draw(rng);
        lanes[e][i] = CornerTravelTracker::ReachLanes{x[e][i], v[e][i]};
      }
      travel.EndReach(0, x[e], v[e], reach[e], speed[e]);
      end[e] = CornerTravelTracker::EndReach(constants, lanes[e]);
      ASSERT_TRUE(SameBits(end[e][0], reach[e])) << "trial " << trial;
      ASSERT_TRUE(SameBits(end[e][1], speed[e])) << "trial " << trial;
    }
    const double best = std::abs(0.02 * Draw(rng)), h = 0.01;
    const bool scalar =
        CornerTravelTracker::MayReach(reach[0], speed[0], reach[1], speed[1], h, best);
    ASSERT_EQ(CornerTravelTracker::MayReach(end[0], end[1], h, best), scalar) << "trial " << trial;
    // The deck's test from the states at the step's ends (Scan's).
    ASSERT_EQ(travel.MayReach(0, x[0], v[0], x[1], v[1], h, best), scalar) << "trial " << trial;
    may += scalar;
  }
  EXPECT_GT(may, 1000);
  EXPECT_LT(may, 99000);
}

TEST(RecordFlight, TheCornersAtAStepsEndAreScansAndDeferWhereScanSearches) {
  const model::Model model = bench::PilotBridge(true, bench::kPilotStudyGap_m);
  CornerTravelTracker in_loop(model), scan(model);
  Eigen::VectorXd best_scan = Eigen::VectorXd::Zero(1);
  in_loop.Start(Eigen::VectorXd::Zero(3), best_scan);
  scan.Start(Eigen::VectorXd::Zero(3), best_scan);
  double best_in_loop = best_scan[0];
  std::mt19937_64 rng(1971);
  std::normal_distribution<double> draw(0.0, 1.0);
  // A walk of states (a step's end starts the next step), so that the kept end is reused.
  std::array<double, 6> s0 = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  long plain = 0, deferring = 0;
  for (int step = 0; step < 20000; ++step) {
    // An oscillation whose amplitude grows and shrinks, with noise: peaks inside steps that
    // raise the maximum (a search) and ends that raise it alone.
    const double h = 0.01, t = (step + 1) * h, w = 18.0;
    const double a = 0.01 * (1.0 + 0.5 * std::sin(0.05 * t)) + 1e-5 * draw(rng);
    std::array<double, 6> s1;
    for (int i = 0; i < 3; ++i) {
      const double scale = i == 2 ? 1e-3 : (i == 1 ? 0.3 : 1.0), phase = 0.7 * i;
      s1[i] = scale * a * std::sin(w * t + phase);
      s1[3 + i] = scale * a * w * std::cos(w * t + phase);
    }
    const double before = best_in_loop;
    // The loop asks only when the reach test passes (Scan skips the deck otherwise).
    if (!in_loop.MayReach(0, s0.data(), s0.data() + 3, s1.data(), s1.data() + 3, h, best_in_loop)) {
      s0 = s1;
      continue;
    }
    double bound[4];
    const int deferred = in_loop.ScanEnd(0, s0, s1, h, best_in_loop, bound);
    // Scan over the same step: its searches find a travel of 0 (the state of zeros), so it
    // raises the maximum by the step's end alone, and it searches only when ScanEnd defers.
    const Eigen::Map<const Eigen::VectorXd> q0(s0.data(), 3), u0(s0.data() + 3, 3),
        q1(s1.data(), 3), u1(s1.data() + 3, 3);
    bool searched = false;
    scan.Scan(
        0.0, q0, u0, h, q1, u1, 1e-12,
        [&](double, int) {
          searched = true;
          return 0.0;
        },
        best_scan,
        [](int, double, double, double, double, double, double, double, double) {
          return std::numeric_limits<double>::infinity();
        });
    ASSERT_EQ(searched, deferred != 0) << "step " << step;
    ASSERT_TRUE(SameBits(best_in_loop, best_scan[0])) << "step " << step;
    ASSERT_GE(best_in_loop, before) << "step " << step;
    if (deferred == 0) {
      ++plain;
    } else {
      ++deferring;
      // Each deferred corner's cheap peak lies above the raised maximum.
      for (int k = 0; k < 4; ++k) {
        if ((deferred & (1 << k)) == 0) continue;
        ASSERT_GT(bound[k], best_in_loop) << "step " << step << ", corner " << k;
      }
    }
    s0 = s1;
  }
  EXPECT_GT(plain, 100);
  EXPECT_GT(deferring, 100);
}

}  // namespace
}  // namespace skewbridge::dynamics::record_flight_test
