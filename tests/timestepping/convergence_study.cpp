// Convergence of the Moreau-Jean scheme to the event-driven result (docs/validation.md, section
// "Time-stepping against event-driven"): for each canonical subsystem case and the pilot bridge,
// the error of the maxima and of the displacement history against h = 1e-3 s halved six times,
// with the observed order, the time per run at equal accuracy (maxima within 1 %), and the
// event-driven run against the contact-free linear run of the same model.
// Run by hand: build/ts/tests/timestepping/timestepping_convergence [--markdown]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "solver/dynamics/simulate.h"
#include "solver/dynamics/time_stepping.h"
#include "solver/model/builders.h"
#include "tests/timestepping/cases.h"

namespace {

using namespace skewbridge;
using Clock = std::chrono::steady_clock;

// Seconds per run, the median-free mean of enough repetitions to last about 0.3 s.
template <class Run>
double SecondsPerRun(Run&& run) {
  int repetitions = 0;
  const Clock::time_point start = Clock::now();
  double elapsed = 0.0;
  do {
    run();
    ++repetitions;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  } while (elapsed < 0.3);
  return elapsed / repetitions;
}

void Study(timestepping_test::Case& c) {
  const model::Model& m = c.file.model;
  const double rho = timestepping_test::Rho(m);
  model::RunControl control = c.file.run;
  control.relative_tolerance = 1e-11;
  control.absolute_tolerance = 1e-13;
  dynamics::SimulationWorkspace ed_ws(m);
  const dynamics::RunResult reference = dynamics::Simulate(m, *c.excitation, control, ed_ws);
  std::printf(
      "\n### %s (event-driven: %s, %ld impacts, max |x| %.4e m, |y| %.4e m, |theta| %.4e rad)\n\n",
      c.name.c_str(), dynamics::ToString(reference.status), reference.impacts,
      reference.max_abs_q[0], reference.max_abs_q[1], reference.max_abs_q[2]);
  std::printf(
      "| h (s) | maxima error | order | envelope [h, 2h) | history error | order | impacts |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  dynamics::TimeSteppingWorkspace ts_ws(m);
  double previous_max = NAN, previous_hist = NAN;
  double h_equal = NAN;
  for (int j = 0; j <= 6; ++j) {
    model::RunControl ts_control = control;
    ts_control.time_step_s = 1e-3 / std::pow(2.0, j);
    const dynamics::RunResult r =
        dynamics::SimulateTimeStepping(m, *c.excitation, ts_control, ts_ws);
    const double e_max = timestepping_test::MaximaError(reference, r, rho);
    const double e_hist = timestepping_test::HistoryError(reference, r, rho);
    // The worst maxima error over h 2^(j/4), j = 0..3: the first-order envelope that the
    // grid's phase against the impact instants hides at a single h.
    double envelope = e_max;
    for (int b = 1; b < 4; ++b) {
      model::RunControl band = ts_control;
      band.time_step_s = ts_control.time_step_s * std::exp2(0.25 * b);
      envelope = std::max(
          envelope,
          timestepping_test::MaximaError(
              reference, dynamics::SimulateTimeStepping(m, *c.excitation, band, ts_ws), rho));
    }
    std::printf(
        "| %.4g | %.3e | %s | %.3e | %.3e | %s | %ld |\n", ts_control.time_step_s, e_max,
        j == 0 ? "" : std::to_string(std::log2(previous_max / e_max)).substr(0, 5).c_str(),
        envelope, e_hist,
        j == 0 ? "" : std::to_string(std::log2(previous_hist / e_hist)).substr(0, 5).c_str(),
        r.impacts);
    previous_max = e_max;
    previous_hist = e_hist;
  }
  // Equal accuracy: the largest h = 1.6e-2 s / 2^j whose every step in [h, 2h) keeps the maxima
  // within 1 % of the converged (tight event-driven) value.
  for (int j = 0; j < 12 && std::isnan(h_equal); ++j) {
    double worst = 0.0;
    for (int b = 0; b < 4; ++b) {
      model::RunControl band = c.file.run;
      band.time_step_s = 1.6e-2 / std::exp2(j) * std::exp2(0.25 * b);
      const dynamics::RunResult r = dynamics::SimulateTimeStepping(m, *c.excitation, band, ts_ws);
      worst = r.status == dynamics::RunStatus::kOk
                  ? std::max(worst, timestepping_test::MaximaError(reference, r, rho))
                  : 1.0;
    }
    if (worst < 0.01) {
      h_equal = 1.6e-2 / std::exp2(j);
    }
  }
  const dynamics::RunResult ed_default = dynamics::Simulate(m, *c.excitation, c.file.run, ed_ws);
  std::printf("\nEvent-driven at the default tolerances: maxima error %.2e\n",
              timestepping_test::MaximaError(reference, ed_default, rho));
  const double t_ed =
      SecondsPerRun([&] { dynamics::Simulate(m, *c.excitation, c.file.run, ed_ws); });
  // The same model with gaps too wide to close: the exact linear flow alone, the floor of the
  // event-driven integrator's cost.
  model::DeckSpec free_spec = c.file.deck;
  free_spec.gap_plus_m = free_spec.gap_minus_m = 1e3;
  const model::Model free_model = model::BuildDeckModel(free_spec);
  dynamics::SimulationWorkspace free_ws(free_model);
  const double t_free =
      SecondsPerRun([&] { dynamics::Simulate(free_model, *c.excitation, c.file.run, free_ws); });
  std::printf(
      "\nContact-free run of the same model (gaps 1 km): %.3e s per run; event-driven with "
      "contacts / contact-free = %.1f\n",
      t_free, t_ed / t_free);
  if (!std::isnan(h_equal)) {
    model::RunControl ts_control = c.file.run;
    ts_control.time_step_s = h_equal;
    const double t_ts =
        SecondsPerRun([&] { dynamics::SimulateTimeStepping(m, *c.excitation, ts_control, ts_ws); });
    std::printf(
        "\nEqual accuracy (maxima within 1 %%): time-stepping h = %.4g s takes %.3e s per run, "
        "event-driven (default tolerances) %.3e s: ratio time-stepping / event-driven = %.1f\n",
        h_equal, t_ts, t_ed, t_ts / t_ed);
  } else {
    std::printf(
        "\nNo step down to 1.6e-5 s reaches 1 %% on the maxima; event-driven %.3e s per run\n",
        t_ed);
  }
}

}  // namespace

int main() {
  for (timestepping_test::Case& c : timestepping_test::CanonicalCases()) {
    Study(c);
  }
  timestepping_test::Case pilot = timestepping_test::PilotCase(1.0);
  Study(pilot);
  timestepping_test::Case strong = timestepping_test::PilotCase(3.0);
  Study(strong);
  return 0;
}
