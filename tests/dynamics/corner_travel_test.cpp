// The largest corner travel normal to the end line (RunResult::max_travel_m) against a dense
// recomputation from the run's own histories (model::CornerTravelAt at every sample, 0.1 ms
// apart), over runs of the single-abutment subsystem, the pilot bridge under a record and a
// three-span bridge, for both integrators; against model::CornerTravelBound from the maxima; and
// equal to that bound where the motion is longitudinal only.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "solver/dynamics/corner_travel.h"
#include "solver/dynamics/simulate.h"
#include "solver/dynamics/time_stepping.h"
#include "solver/model/builders.h"
#include "solver/model/deck.h"
#include "solver/model/multispan.h"
#include "tests/dynamics/benchmark_cases.h"

namespace skewbridge::dynamics::corner_travel_test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
constexpr double kOutput_s = 1e-4;  // the dense recomputation's sampling interval

// What the dense recomputation gives for deck d of a run with histories.
struct Dense {
  double travel_m = 0.0;      // max over the samples of CornerTravelAt
  double max_rate_mps = 0.0;  // max over the samples of a bound of |d f_k / dt| for every corner
};

Dense DenseTravel(const model::Model& model, const RunResult& r, int d) {
  const model::DeckGeometry& g = model.body(d).geometry;
  double radius = 0.0;
  for (int k = 1; k <= 4; ++k) radius = std::max(radius, model::Corner(g, k).norm());
  const Histories& h = r.histories;
  const int n = h.n_dof;
  Dense out;
  for (std::size_t s = 0; s < h.t_s.size(); ++s) {
    const double* q = &h.q[s * static_cast<std::size_t>(n) + 3 * static_cast<std::size_t>(d)];
    const double* u = &h.u[s * static_cast<std::size_t>(n) + 3 * static_cast<std::size_t>(d)];
    out.travel_m = std::max(out.travel_m, model::CornerTravelAt(g, {q[0], q[1], q[2]}));
    out.max_rate_mps =
        std::max(out.max_rate_mps, std::abs(u[0]) + std::abs(u[1]) + radius * std::abs(u[2]));
  }
  return out;
}

struct Tally {
  int runs = 0, impacts = 0;
  double largest_gap_over_tol = 0.0;  // max of (tracked - dense) / (max rate x interval)
};

// Every deck of run r: the tracked travel is at least the dense maximum (less round-off), at most
// the dense maximum plus what the corner can travel between two samples, and at most the bound.
// `exact_grid`: the time-stepping run sampled at its own grid, whose maxima are the samples'.
void CheckRun(const model::Model& model, const RunResult& r, const std::string& what, Tally& tally,
              bool exact_grid = false) {
  ASSERT_EQ(r.status, RunStatus::kOk) << what << ": " << r.message;
  ASSERT_EQ(r.max_travel_m.size(), model.n_bodies()) << what;
  ++tally.runs;
  tally.impacts += static_cast<int>(r.impacts);
  for (int d = 0; d < model.n_bodies(); ++d) {
    const Dense dense = DenseTravel(model, r, d);
    const double tracked = r.max_travel_m[d];
    const double roundoff = 1e-12 * std::max(dense.travel_m, 1e-3);
    const double bound =
        model::CornerTravelBound(model.body(d).geometry, r.max_abs_q.segment<3>(3 * d));
    const std::string at = what + ", deck " + std::to_string(d);
    EXPECT_GT(dense.travel_m, 0.0) << at;
    EXPECT_GE(tracked, dense.travel_m - roundoff) << at;
    EXPECT_LE(tracked, bound + roundoff) << at;
    if (exact_grid) {
      EXPECT_NEAR(tracked, dense.travel_m, roundoff) << at;
    } else {
      // Between samples kOutput_s apart a corner moves at most its largest rate times half the
      // interval from the nearer sample (a few per cent more allowed for the rate between samples).
      const double tol = 0.6 * dense.max_rate_mps * kOutput_s;
      EXPECT_LE(tracked, dense.travel_m + tol + roundoff) << at;
      tally.largest_gap_over_tol =
          std::max(tally.largest_gap_over_tol, (tracked - dense.travel_m) / tol);
    }
  }
}

model::DeckSpec Subsystem(double skew_deg, double gap_m) {
  model::DeckSpec spec;
  spec.mass_kg = 1.0e5;
  // eta0 = 1.5 (W = 8.7 to 10 m here); at zero skew, where eta0 = 0, a width of 10 m.
  const double width_m = skew_deg > 0.0 ? model::WidthFromEta0(1.5, skew_deg * kDeg, 30.0) : 10.0;
  spec.geometry = {30.0, width_m, skew_deg * kDeg};
  spec.w0x_radps = spec.w0y_radps = spec.W0_radps = kPi;
  spec.gap_plus_m = gap_m;
  spec.restitution = 0.5;
  spec.friction = 0.2;
  return spec;
}

TEST(CornerTravel, AReassignedTrackerGivesTheTravelsOfAFreshOne) {
  // Trackers assigned in turn to decks whose geometry repeats and changes (and to a three-span
  // bridge) against a tracker built for each model after one of another geometry: the same
  // travel maxima, bit for bit, at states of every deck turned both ways.
  std::vector<model::Model> models;
  for (const double skew_deg : {20.0, 20.0, 45.0, 20.0}) {
    for (const double w0 : {4.0, 5.0}) {
      model::DeckSpec d;
      d.mass_kg = 1.0e6;
      d.geometry = {30.0, 12.0, skew_deg * kDeg};
      d.w0x_radps = d.w0y_radps = d.W0_radps = w0;
      d.gap_plus_m = d.gap_minus_m = 0.01;
      models.push_back(model::BuildDeckModel(d, "deck"));
    }
  }
  model::MultiSpanSpec b;
  b.n_spans = 3;
  b.span_lengths_m = {30.0};
  b.width_m = 12.0;
  b.skew_rad = 20.0 * kDeg;
  b.mass_per_length_kgpm = 3.0e4;
  b.w0x_radps = b.w0y_radps = 6.0;
  b.W0_radps = 8.0;
  b.abutment_gap_m = 0.01;
  b.joint_gap_m = 0.005;
  models.insert(models.begin() + 3, model::BuildMultiSpanBridge(b, "spans"));
  model::DeckSpec other;
  other.mass_kg = 1.0e6;
  other.geometry = {17.0, 5.0, 33.0 * kDeg};
  other.w0x_radps = other.w0y_radps = other.W0_radps = 3.0;
  const model::Model evict = model::BuildDeckModel(other, "other");
  CornerTravelTracker reused;
  for (std::size_t i = 0; i < models.size(); ++i) {
    SCOPED_TRACE(i);
    const model::Model& m = models[i];
    reused.Assign(m);
    const CornerTravelTracker away(evict);
    const CornerTravelTracker fresh(m);
    ASSERT_EQ(reused.decks(), fresh.decks());
    for (const double sign : {1.0, -1.0}) {
      Eigen::VectorXd q(m.n_dof());
      for (int j = 0; j < m.n_dof(); ++j) q[j] = sign * (0.01 + 0.003 * j);
      Eigen::VectorXd a = Eigen::VectorXd::Zero(fresh.decks());
      Eigen::VectorXd e = a;
      reused.Update(q, a);
      fresh.Update(q, e);
      for (int d = 0; d < fresh.decks(); ++d) {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(a[d]), std::bit_cast<std::uint64_t>(e[d])) << d;
        EXPECT_GT(a[d], 0.0);
      }
    }
  }
}

TEST(CornerTravel, SubsystemRunsMatchTheDenseMaximumOfTheirHistories) {
  Tally tally;
  for (double skew_deg : {15.0, 35.0, 55.0}) {
    for (records::PulseShape shape : {records::PulseShape::kCosine, records::PulseShape::kSine}) {
      for (double pi_delta : {0.2, 0.6, 1e4}) {
        const double a_g = 5.0, w_g = 2.0 * kPi;
        const model::Model model =
            model::BuildDeckModel(Subsystem(skew_deg, pi_delta * a_g / (w_g * w_g)));
        const records::PulseExcitation pulse(shape, a_g, w_g);
        model::RunControl control;
        control.end_time_s = 3.0;
        control.output_interval_s = kOutput_s;
        SimulationWorkspace ws(model);
        const RunResult r = Simulate(model, pulse, control, ws);
        CheckRun(model, r,
                 "a = " + std::to_string(skew_deg) + ", Pi_delta = " + std::to_string(pi_delta),
                 tally);
      }
    }
  }
  EXPECT_EQ(tally.runs, 18);
  EXPECT_GT(tally.impacts, 18);  // most runs pound
  std::printf("18 subsystem runs, %d impacts: tracked - dense <= %.3g of the sampling tolerance\n",
              tally.impacts, tally.largest_gap_over_tol);
}

TEST(CornerTravel, PilotBridgeUnderARecordMatchesTheDenseMaximum) {
  Tally tally;
  for (double gap_m : {bench::kPilotStressGap_m, bench::kPilotStudyGap_m}) {
    bench::Case c = bench::PilotBridgeRecord(true, gap_m);
    c.control.end_time_s = 12.0;
    c.control.output_interval_s = kOutput_s;
    SimulationWorkspace ws(c.model);
    CheckRun(c.model, Simulate(c.model, *c.excitation, c.control, ws),
             "pilot, gap " + std::to_string(gap_m), tally);
  }
  EXPECT_GT(tally.impacts, 20);
  std::printf("pilot bridge: %d impacts, tracked - dense <= %.3g of the sampling tolerance\n",
              tally.impacts, tally.largest_gap_over_tol);
}

TEST(CornerTravel, ThreeSpanBridgeTracksEveryDeck) {
  model::MultiSpanSpec spec;
  spec.n_spans = 3;
  spec.span_lengths_m = {30.0, 40.0, 30.0};
  spec.width_m = 12.0;
  spec.skew_rad = 30.0 * kDeg;
  spec.mass_per_length_kgpm = 20e3;
  spec.w0x_radps = spec.w0y_radps = 10.0;
  spec.W0_radps = 12.0;
  spec.abutment_gap_m = 0.02;
  spec.joint_gap_m = 0.015;
  spec.friction = 0.2;
  const model::Model model = model::BuildMultiSpanBridge(spec);
  Tally tally;
  for (records::PulseShape shape : {records::PulseShape::kCosine, records::PulseShape::kSine}) {
    const records::PulseExcitation pulse(shape, 4.0, 2.0 * kPi);
    model::RunControl control;
    control.end_time_s = 3.0;
    control.output_interval_s = kOutput_s;
    SimulationWorkspace ws(model);
    CheckRun(model, Simulate(model, pulse, control, ws), "three spans", tally);
  }
  EXPECT_GT(tally.impacts, 2);
}

TEST(CornerTravel, TimeSteppingTracksItsGridPoints) {
  Tally tally;
  for (double skew_deg : {20.0, 45.0}) {
    const model::Model model = model::BuildDeckModel(Subsystem(skew_deg, 0.05));
    const records::PulseExcitation pulse(records::PulseShape::kCosine, 5.0, 2.0 * kPi);
    model::RunControl control;
    control.end_time_s = 3.0;
    control.time_step_s = 2e-4;
    control.output_interval_s = 2e-4;  // every grid point
    TimeSteppingWorkspace ws(model);
    CheckRun(model, SimulateTimeStepping(model, pulse, control, ws),
             "time stepping, a = " + std::to_string(skew_deg), tally, true);
  }
  EXPECT_GT(tally.impacts, 0);
}

// The run of `model` for 3 s under a cosine pulse of 5 m/s^2 at 1 Hz.
RunResult RunCosinePulse(const model::Model& model) {
  const records::PulseExcitation pulse(records::PulseShape::kCosine, 5.0, 2.0 * kPi);
  model::RunControl control;
  control.end_time_s = 3.0;
  SimulationWorkspace ws(model);
  return Simulate(model, pulse, control, ws);
}

TEST(CornerTravel, EqualsTheBoundForALongitudinalMotion) {
  // Gaps too wide to close and a diagonal support: under a pulse along x the deck moves along x
  // alone (y = theta = 0 exactly), so the travel is cos a max|x| and the bound says the same.
  for (double skew_deg : {0.0, 30.0, 60.0}) {
    const model::Model model = model::BuildDeckModel(Subsystem(skew_deg, 1e3));
    const RunResult r = RunCosinePulse(model);
    ASSERT_EQ(r.status, RunStatus::kOk);
    ASSERT_EQ(r.max_abs_q[1], 0.0);
    ASSERT_EQ(r.max_abs_q[2], 0.0);
    const double bound = model::CornerTravelBound(model.body(0).geometry, r.max_abs_q.head<3>());
    EXPECT_NEAR(r.max_travel_m[0], bound, 1e-14 * bound) << skew_deg;
    EXPECT_NEAR(r.max_travel_m[0], std::cos(skew_deg * kDeg) * r.max_abs_q[0], 1e-14 * bound);
  }
  // Zero skew with impacts on the straight abutment: the deck strikes with both corners at once
  // and does not turn; x and the travel peak together.
  const model::Model model = model::BuildDeckModel(Subsystem(0.0, 0.05));
  const RunResult r = RunCosinePulse(model);
  ASSERT_EQ(r.status, RunStatus::kOk);
  EXPECT_GT(r.impacts, 0);
  const double bound = model::CornerTravelBound(model.body(0).geometry, r.max_abs_q.head<3>());
  EXPECT_NEAR(r.max_travel_m[0], bound, 1e-12 * bound);
}

TEST(CornerTravel, ASkewDeckThatPoundsTravelsLessThanTheBound) {
  // The bound adds peaks of x, y and theta taken at their own times: where the deck pounds and
  // turns, the exact travel lies clearly below it.
  const model::Model model = model::BuildDeckModel(Subsystem(45.0, 0.05));
  const RunResult r = RunCosinePulse(model);
  ASSERT_EQ(r.status, RunStatus::kOk);
  const double bound = model::CornerTravelBound(model.body(0).geometry, r.max_abs_q.head<3>());
  EXPECT_LT(r.max_travel_m[0], 0.95 * bound);
}

// One step of a deck moving along x = X sin(w t), y = X sin(w t) / 3 and theta = e (t (h - t))^2
// over [0, h] (theta and its rate zero at both ends, exactly): the tracked travel against a
// dense maximum of model::CornerTravelAt, and the dense output's reads. A deck that does not
// turn (e = 0) has four corners on one function: one search finds its peak, the other three
// would repeat it read for read. A deck that turns inside the step (e != 0, the same ends) has
// four different peaks and needs every search.
struct StepScan {
  double travel_m = 0.0;  // the tracked travel
  double dense_m = 0.0;   // the dense maximum
  int reads = 0;          // reads of the dense output
};

StepScan ScanOneStep(const model::Model& model, double e) {
  const double h = 0.2, X = 0.1, w = 2.0 * kPi / 0.3;
  const auto state = [&](double t, int i) {
    const double p = t * (h - t), dp = h - 2.0 * t;
    switch (i) {
      case 0:
        return X * std::sin(w * t);
      case 1:
        return X * std::sin(w * t) / 3.0;
      case 2:
        return e * p * p;
      case 3:
        return X * w * std::cos(w * t);
      case 4:
        return X * w * std::cos(w * t) / 3.0;
      default:
        return 2.0 * e * p * dp;
    }
  };
  StepScan out;
  const auto component_at = [&](double t, int i) {
    ++out.reads;
    return state(t, i);
  };
  Eigen::VectorXd q0(3), u0(3), q1(3), u1(3);
  for (int i = 0; i < 3; ++i) {
    q0[i] = state(0.0, i);
    u0[i] = state(0.0, 3 + i);
    q1[i] = state(h, i);
    u1[i] = state(h, 3 + i);
  }
  CornerTravelTracker travel(model);
  Eigen::VectorXd max_travel;
  travel.Start(q0, max_travel);
  travel.Scan(0.0, q0, u0, h, q1, u1, 1e-13, component_at, max_travel);
  out.travel_m = max_travel[0];
  const model::DeckGeometry& g = model.body(0).geometry;
  for (int j = 0; j <= 200000; ++j) {
    const double t = h * j / 200000.0;
    out.dense_m =
        std::max(out.dense_m, model::CornerTravelAt(g, {state(t, 0), state(t, 1), state(t, 2)}));
  }
  return out;
}

TEST(CornerTravel, ADeckThatDoesNotTurnSearchesOneCornerOfFour) {
  const model::Model model = model::BuildDeckModel(Subsystem(30.0, 1e3));
  ASSERT_EQ(model.n_dof(), 3);
  const StepScan still = ScanOneStep(model, 0.0);
  const StepScan turning = ScanOneStep(model, 1e-4 / std::pow(0.1, 4));  // theta up to 1e-4 rad
  EXPECT_NEAR(still.travel_m, still.dense_m, 1e-9 * still.dense_m);
  EXPECT_NEAR(turning.travel_m, turning.dense_m, 1e-9 * turning.dense_m);
  EXPECT_GT(turning.travel_m, still.travel_m * (1.0 + 1e-6));  // the corners' peaks differ
  // Per search: four reads per rate evaluation and three for the travel at the root.
  EXPECT_GT(still.reads, 4 * 4);
  EXPECT_GE(turning.reads, 3 * still.reads);
}

}  // namespace
}  // namespace skewbridge::dynamics::corner_travel_test
