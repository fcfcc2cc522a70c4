// Recording time histories only observes a run: the same run with histories at two output
// intervals (0.01 s and 0.0003 s, so samples fall inside constrained phases, between events and
// inside event searches) ends bit for bit where the run without histories ends. Every maximum and
// its time, the end state, the counts, the energy ledger and the event log are compared as bits,
// for decks that pound, slide, stick, rock and stay clamped between their abutments.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "solver/dynamics/simulate.h"
#include "solver/model/model_file.h"
#include "tests/dynamics/benchmark_cases.h"

namespace skewbridge::dynamics::recording_test {
namespace {

const std::string kExamplesDir = std::string(SKEWBRIDGE_TEST_DATA_DIR) + "/../../docs/examples";
const std::string kModelsDir = std::string(SKEWBRIDGE_TEST_DATA_DIR) + "/models";

// A model file's text with each (exact text at the start of a line, replacement) pair applied to
// the first line that starts with it.
model::ModelFile EditedModelFile(const std::string& path,
                                 const std::vector<std::pair<std::string, std::string>>& edits) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  for (const auto& [from, to] : edits) {
    const std::size_t at = text.find("\n" + from);
    EXPECT_NE(at, std::string::npos) << path << ": no line starting \"" << from << "\"";
    if (at != std::string::npos) {
      text.replace(at + 1, from.size(), to);
    }
  }
  return model::ParseModelString(text, path, kExamplesDir);
}

// A model file's model, pulse and run control as one benchmark-style case.
bench::Case FromModelFile(const model::ModelFile& file) {
  const model::ExcitationSpec& ex = file.excitation;
  const auto shape = ex.shape == model::ExcitationSpec::PulseShape::kCosine
                         ? records::PulseShape::kCosine
                         : records::PulseShape::kSine;
  bench::Case c{file.model,
                std::make_unique<records::PulseExcitation>(shape, ex.amplitude_mps2, ex.omega_radps,
                                                           ex.direction),
                file.run};
  return c;
}

// Bits of a double: equal bits are the same number, and NaN equals itself.
std::uint64_t Bits(double x) { return std::bit_cast<std::uint64_t>(x); }

// |a - b| relative to max(|a|, |b|) (0 when both are 0 or the bits agree).
double RelativeDifference(double a, double b) {
  if (Bits(a) == Bits(b)) {
    return 0.0;
  }
  const double scale = std::max(std::abs(a), std::abs(b));
  return scale > 0.0 ? std::abs(a - b) / scale : std::abs(a - b);
}

// Every difference between two runs' summaries, one line each ("" when bit-identical).
std::string Differences(const RunResult& a, const RunResult& b) {
  std::ostringstream out;
  out.precision(17);
  const auto scalar = [&](const char* name, double x, double y) {
    if (Bits(x) != Bits(y)) {
      out << name << ": " << x << " vs " << y << " (relative " << RelativeDifference(x, y) << ")\n";
    }
  };
  const auto count = [&](const char* name, long x, long y) {
    if (x != y) {
      out << name << ": " << x << " vs " << y << "\n";
    }
  };
  const auto vector = [&](const char* name, const Eigen::VectorXd& x, const Eigen::VectorXd& y) {
    if (x.size() != y.size()) {
      out << name << ": sizes " << x.size() << " vs " << y.size() << "\n";
      return;
    }
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      if (Bits(x[i]) != Bits(y[i])) {
        out << name << "[" << i << "]: " << x[i] << " vs " << y[i] << " (relative "
            << RelativeDifference(x[i], y[i]) << ")\n";
      }
    }
  };
  count("status", static_cast<long>(a.status), static_cast<long>(b.status));
  if (a.message != b.message) {
    out << "message: \"" << a.message << "\" vs \"" << b.message << "\"\n";
  }
  scalar("end_time_s", a.end_time_s, b.end_time_s);
  vector("max_abs_q", a.max_abs_q, b.max_abs_q);
  vector("time_of_max_s", a.time_of_max_s, b.time_of_max_s);
  vector("q_end", a.q_end, b.q_end);
  vector("u_end", a.u_end, b.u_end);
  count("impacts", a.impacts, b.impacts);
  count("plastic_closures", a.plastic_closures, b.plastic_closures);
  count("detachments", a.detachments, b.detachments);
  count("stick_transitions", a.stick_transitions, b.stick_transitions);
  count("slip_transitions", a.slip_transitions, b.slip_transitions);
  count("free_steps", a.free_steps, b.free_steps);
  count("rk_steps", a.rk_steps, b.rk_steps);
  count("rk_rejected", a.rk_rejected, b.rk_rejected);
  scalar("min_impact_separation_s", a.min_impact_separation_s, b.min_impact_separation_s);
  const EnergyLedger& ea = a.energy;
  const EnergyLedger& eb = b.energy;
  scalar("energy.initial_J", ea.initial_J, eb.initial_J);
  scalar("energy.input_J", ea.input_J, eb.input_J);
  scalar("energy.damping_J", ea.damping_J, eb.damping_J);
  scalar("energy.impact_J", ea.impact_J, eb.impact_J);
  scalar("energy.friction_J", ea.friction_J, eb.friction_J);
  scalar("energy.kinetic_J", ea.kinetic_J, eb.kinetic_J);
  scalar("energy.strain_J", ea.strain_J, eb.strain_J);
  scalar("energy.balance_error_J", ea.balance_error_J, eb.balance_error_J);
  count("events", static_cast<long>(a.events.size()), static_cast<long>(b.events.size()));
  for (std::size_t k = 0; k < std::min(a.events.size(), b.events.size()); ++k) {
    const EventRecord& x = a.events[k];
    const EventRecord& y = b.events[k];
    const bool same = Bits(x.t_s) == Bits(y.t_s) && x.kind == y.kind && x.contact == y.contact &&
                      Bits(x.impulse_N_Ns) == Bits(y.impulse_N_Ns) &&
                      Bits(x.impulse_T_Ns) == Bits(y.impulse_T_Ns) &&
                      Bits(x.gamma_N_before_mps) == Bits(y.gamma_N_before_mps) &&
                      Bits(x.gamma_N_after_mps) == Bits(y.gamma_N_after_mps) &&
                      Bits(x.kinetic_loss_J) == Bits(y.kinetic_loss_J);
    if (!same) {
      out << "event " << k << ": " << ToString(x.kind) << " of contact " << x.contact << " at "
          << x.t_s << " s vs " << ToString(y.kind) << " of contact " << y.contact << " at " << y.t_s
          << " s (the first differing event)\n";
      break;
    }
  }
  return out.str();
}

struct Named {
  std::string name;
  bench::Case run;
  bool constrained;  // the run has constrained phases (where a sample evaluates forces)
};

// The decks of the comparison: the pilot bridge at the study's gaps (Pi_delta = 0.5, free flight
// between impacts) and at 2 mm (319 impacts, 30 detachments, sticking and slipping corners); the
// subsystem under its pulse, with one abutment and with both at 2 mm, plastic and mu = 0.3; the
// three-span bridge as written and with plastic joints of 4 mm; and a deck clamped between its
// abutments (zero gaps, plastic, mu = 0.3: it slides along them from the first instant).
std::vector<Named> Cases() {
  std::vector<Named> cases;
  cases.push_back(
      {"pilot bridge, study gaps", bench::PilotBridgeRecord(true, bench::kPilotStudyGap_m), false});
  cases.push_back(
      {"pilot bridge, 2 mm gaps", bench::PilotBridgeRecord(true, bench::kPilotStressGap_m), true});
  cases.push_back({"subsystem", bench::SubsystemCosinePulse(true), false});
  cases.push_back({"subsystem, both abutments, plastic, mu 0.3",
                   FromModelFile(EditedModelFile(kExamplesDir + "/subsystem.toml",
                                                 {{"set = \"+x\"", "set = \"both\""},
                                                  {"gap_m = 0.03", "gap_m = 0.002"},
                                                  {"eps_N = 0.5", "eps_N = 0.0"},
                                                  {"mu = 0.0", "mu = 0.3"}})),
                   true});
  cases.push_back({"three-span",
                   FromModelFile(model::ParseModelFile(kExamplesDir + "/three-span.toml")), false});
  cases.push_back(
      {"three-span, plastic joints",
       FromModelFile(EditedModelFile(kExamplesDir + "/three-span.toml",
                                     {{"gap_m = 0.04", "gap_m = 0.004"},
                                      {"gap_m = 0.04", "gap_m = 0.004"},
                                      {"eps_N = 0.5\nmu = 0.2", "eps_N = 0.0\nmu = 0.2"},
                                      {"eps_N = 0.5\nmu = 0.2", "eps_N = 0.0\nmu = 0.2"}})),
       true});
  cases.push_back({"clamped deck",
                   FromModelFile(EditedModelFile(kModelsDir + "/one-deck-pulse.toml",
                                                 {{"gap_m = 0.03", "gap_m = 0.0"},
                                                  {"eps_N = 0.5", "eps_N = 0.0"},
                                                  {"mu = 0.0", "mu = 0.3"}})),
                   true});
  return cases;
}

TEST(Recording, HistoriesLeaveEveryResultBitIdentical) {
  for (const Named& c : Cases()) {
    SimulationWorkspace ws(c.run.model);
    model::RunControl control = c.run.control;
    control.output_interval_s = 0.0;
    const RunResult plain = Simulate(c.run.model, *c.run.excitation, control, ws);
    ASSERT_EQ(plain.status, RunStatus::kOk) << c.name << ": " << plain.message;
    // Each case pounds; those with constrained phases evaluate contact forces at their samples.
    EXPECT_GT(plain.impacts, 0) << c.name;
    EXPECT_EQ(plain.rk_steps > 0, c.constrained) << c.name;
    for (const double interval_s : {0.01, 0.0003}) {
      control.output_interval_s = interval_s;
      const RunResult recorded = Simulate(c.run.model, *c.run.excitation, control, ws);
      EXPECT_EQ(Differences(plain, recorded), "")
          << c.name << " with histories every " << interval_s << " s";
      // The histories cover the run at that interval.
      EXPECT_EQ(recorded.histories.t_s.size(),
                static_cast<std::size_t>(std::floor(plain.end_time_s / interval_s + 1e-9)) + 1)
          << c.name;
    }
  }
}

}  // namespace
}  // namespace skewbridge::dynamics::recording_test
