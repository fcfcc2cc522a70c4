// Runs one benchmark case exactly N times (after one warm-up run), so that an instruction count
// under callgrind divided by N + 1 is the cost of one run:
//   valgrind --tool=callgrind build/perf/tests/dynamics/simulate_one_run pilot 1 10
// Arguments: subsystem|pilot|pilot-study, contacts 0|1, N (pilot-study: the pilot bridge at the
// gaps of Pi_delta = 0.5), and optionally warm (the default: one workspace for every run) or cold
// (a new copy of the model and a new workspace for every run) or cell (cold and without the energy
// ledger: what a sweep cell does; a record's excitation then carries the pieces that hold its
// peak, records::FindPeakPieces, as a sweep's evaluators keep them per record, so that a run's
// scale does not walk the record). Prints the run's status, counts and maxima.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "records/excitations.h"
#include "solver/dynamics/simulate.h"
#include "tests/dynamics/benchmark_cases.h"

int main(int argc, char** argv) {
  using namespace skewbridge::dynamics;
  if (argc != 4 && argc != 5) {
    std::fprintf(stderr, "usage: %s subsystem|pilot|pilot-study 0|1 N [warm|cold|cell]\n", argv[0]);
    return 2;
  }
  const std::string mode = argc == 5 ? argv[4] : "warm";
  if (mode != "warm" && mode != "cold" && mode != "cell") {
    std::fprintf(stderr, "%s: the mode must be warm, cold or cell, not %s\n", argv[0],
                 mode.c_str());
    return 2;
  }
  const std::string which = argv[1];
  const bool contacts = std::atoi(argv[2]) != 0;
  const int n = std::atoi(argv[3]);
  bench::Case c = which == "pilot" ? bench::PilotBridgeRecord(contacts)
                  : which == "pilot-study"
                      ? bench::PilotBridgeRecord(contacts, bench::kPilotStudyGap_m)
                      : bench::SubsystemCosinePulse(contacts);
  if (mode == "cell" && which != "subsystem") {
    // The same samples (a factor of 1 leaves them as read) with their peak's pieces.
    skewbridge::records::GroundMotion motion;
    motion.dt_s = 0.01;
    motion.acc_mps2 = bench::RecordLikeSignal();
    const EventPolicy policy;
    c.excitation = std::make_unique<skewbridge::records::SampledExcitation>(
        skewbridge::records::ScaledExcitation(
            motion, 1.0, Eigen::Vector2d::UnitX(),
            std::make_shared<const skewbridge::records::PeakPieces>(
                skewbridge::records::FindPeakPieces(motion.acc_mps2, motion.dt_s,
                                                    policy.ramp_horizon_s))));
  }
  SimulationWorkspace ws(c.model);
  // The warm-up run keeps the energy ledger as the mode's runs do, so that a whole-program
  // profile of `cell` runs shows no ledger work either.
  skewbridge::model::RunControl warm_up = c.control;
  warm_up.energy_ledger = mode != "cell";
  RunResult r = Simulate(c.model, *c.excitation, warm_up, ws);
  for (int i = 0; i < n; ++i) {
    if (mode != "warm") {
      // Everything a sweep cell builds: its model and a workspace for it (modal data, caches).
      const skewbridge::model::Model model = c.model;
      SimulationWorkspace cold(model);
      skewbridge::model::RunControl control = c.control;
      control.energy_ledger = mode == "cold";
      r = Simulate(model, *c.excitation, control, cold);
    } else {
      r = Simulate(c.model, *c.excitation, c.control, ws);
    }
  }
  std::printf("%s contacts=%d: %s, free steps %ld, rk steps %ld (+%ld rejected), impacts %ld\n",
              which.c_str(), contacts ? 1 : 0, ToString(r.status), r.free_steps, r.rk_steps,
              r.rk_rejected, r.impacts);
  std::printf("max |q| = %.12e %.12e %.12e\n", r.max_abs_q[0], r.max_abs_q[1], r.max_abs_q[2]);
  return 0;
}
