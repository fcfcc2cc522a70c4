// A deck's record flight (Integrator::DeckRecordSteps: the state, the piece, the plan's cache, the
// maxima and the counts in locals, the gap floors' drifts from the transition's lanes) against the
// general flight loop, which a run takes while an observer sees its free steps: every result's
// bits (maxima and their times, the end state, the corner travel, the counts, the events), for the
// pilot bridge without contacts and at two gaps, under records along x and at an angle (y samples
// too), with and without history samples.

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "records/excitations.h"
#include "records/incidence.h"
#include "solver/dynamics/simulate.h"
#include "tests/dynamics/benchmark_cases.h"
#include "tests/dynamics/run_bits.h"

namespace skewbridge::dynamics::record_flight_test {
namespace {

// Sees every free step up to the first event and lets the run go on: the run then takes the
// general flight loop, whose steps are RecordFlight's operations one member at a time.
class PassThrough final : public FreeStepObserver {
 public:
  bool Step(double, const Eigen::Ref<const Eigen::VectorXd>&, double, double,
            const Eigen::Ref<const Eigen::VectorXd>&, const RunResult&) override {
    ++steps;
    return true;
  }
  long steps = 0;
};

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

}  // namespace
}  // namespace skewbridge::dynamics::record_flight_test
