// The pilot bridge with 2 mm joint gaps: a sticking corner whose friction reaches the cone must
// start to slip instead of re-firing its stick-slip event at the same instant.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "solver/dynamics/simulate.h"
#include "solver/model/model_file.h"

namespace skewbridge::dynamics::cascade_test {
namespace {

const std::string kExamplesDir = std::string(SKEWBRIDGE_TEST_DATA_DIR) + "/../../docs/examples";

// docs/examples/pilot-bridge.toml with both gaps 2 mm; the excitation comes from the test.
model::ModelFile PilotWithSmallGaps() {
  std::ifstream in(kExamplesDir + "/pilot-bridge.toml");
  std::string text, line;
  while (std::getline(in, line)) {
    if (line.rfind("gap_m", 0) == 0) {
      line = "gap_m = { \"+x\" = 0.002, \"-x\" = 0.002 }";
    }
    text += line + "\n";
  }
  return model::ParseModelString(text, "pilot-gap2mm.toml", kExamplesDir);
}

// The pilot signal (two columns, 0.01 s), repeated `copies` times end to end.
records::SampledExcitation PilotSignal(int copies) {
  std::ifstream in(kExamplesDir + "/pilot-signal.txt");
  std::vector<double> one;
  double t = 0.0, a = 0.0;
  while (in >> t >> a) {
    one.push_back(a);
  }
  std::vector<double> ax;
  for (int k = 0; k < copies; ++k) {
    ax.insert(ax.end(), one.begin(), one.end() - 1);
  }
  ax.push_back(one.back());
  return records::SampledExcitation(0.01, std::move(ax));
}

// Energy balance relative to the input, and no frictionless impact gaining kinetic energy.
void ExpectConsistent(const RunResult& r, const model::Model& m) {
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  EXPECT_LE(std::abs(r.energy.balance_error_J), 1e-6 * r.energy.input_J);
  EXPECT_GE(r.energy.impact_J, 0.0);
  EXPECT_GE(r.energy.friction_J, 0.0);
  for (const EventRecord& e : r.events) {
    if (e.kind == EventKind::kImpact && m.contact(e.contact).friction == 0.0) {
      EXPECT_GE(e.kinetic_loss_J, -1e-9 * r.energy.input_J) << "impact at t = " << e.t_s;
    }
  }
}

TEST(DynamicsCascade, PilotBridgeWithTwoMillimetreGapsEndsOkWithBalancedEnergy) {
  const model::ModelFile file = PilotWithSmallGaps();
  const records::SampledExcitation excitation = PilotSignal(1);
  SimulationWorkspace workspace(file.model);
  const RunResult r = Simulate(file.model, excitation, file.run, workspace);
  ExpectConsistent(r, file.model);
  EXPECT_NEAR(r.end_time_s, 6.0, 1e-9);
  // stick-slip transitions at the cone are decided once (docs/theory.md §3.8), not re-fired
  EXPECT_GT(r.slip_transitions, 0);
}

TEST(DynamicsCascade, PilotBridgeUnderFortySecondRecordEndsOkWithBalancedEnergy) {
  const model::ModelFile file = PilotWithSmallGaps();
  const records::SampledExcitation excitation = PilotSignal(10);
  ASSERT_NEAR(excitation.Duration(), 40.0, 1e-9);
  SimulationWorkspace workspace(file.model);
  const RunResult r = Simulate(file.model, excitation, file.run, workspace);
  ExpectConsistent(r, file.model);
  EXPECT_NEAR(r.end_time_s, 42.0, 1e-9);
}

// The same model frictionless: Newton impacts with eps_N = 0.5 never gain kinetic energy.
TEST(DynamicsCascade, FrictionlessPilotBridgeImpactsNeverGainEnergy) {
  std::ifstream in(kExamplesDir + "/pilot-bridge.toml");
  std::string text, line;
  while (std::getline(in, line)) {
    if (line.rfind("gap_m", 0) == 0) {
      line = "gap_m = { \"+x\" = 0.002, \"-x\" = 0.002 }";
    } else if (line.rfind("mu", 0) == 0) {
      line = "mu = 0.0";
    }
    text += line + "\n";
  }
  const model::ModelFile file = model::ParseModelString(text, "pilot-frictionless", kExamplesDir);
  ASSERT_EQ(file.model.contact(0).friction, 0.0);
  const records::SampledExcitation excitation = PilotSignal(1);
  SimulationWorkspace workspace(file.model);
  const RunResult r = Simulate(file.model, excitation, file.run, workspace);
  ExpectConsistent(r, file.model);
  EXPECT_GT(r.impacts, 0);
  EXPECT_EQ(r.energy.friction_J, 0.0);
}

}  // namespace
}  // namespace skewbridge::dynamics::cascade_test
