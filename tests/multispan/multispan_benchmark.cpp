// Run time per simulated second of an N-span bridge (N = 1, 2, 5, 10, 20, 50) under a one-cycle
// cosine pulse along x (a_g = 0.5 g, T = 0.6 s, 0.4 s of tail: 1 s simulated, so the reported time
// is the time per simulated second): Moreau-Jean time-stepping (h = 1e-3 s) with the dense and the
// sparse linear algebra, and the event-driven integrator. The table and the crossover are in
// docs/multispan.md.
#include <benchmark/benchmark.h>

#include <numbers>

#include "records/excitations.h"
#include "solver/dynamics/simulate.h"
#include "solver/dynamics/time_stepping.h"
#include "solver/model/multispan.h"

namespace skewbridge {
namespace {

model::Model Bridge(int n_spans) {
  model::MultiSpanSpec spec;
  spec.n_spans = n_spans;
  spec.span_lengths_m = {30.0};
  spec.width_m = 10.0;
  spec.skew_rad = 30.0 * std::numbers::pi / 180.0;
  spec.mass_per_length_kgpm = 20e3;
  spec.w0x_radps = spec.w0y_radps = 8.0;
  spec.W0_radps = 10.0;
  spec.xi = 0.05;
  spec.abutment_gap_m = 0.02;
  spec.joint_gap_m = 0.01;
  spec.restitution = 0.5;
  spec.friction = 0.2;
  return model::BuildMultiSpanBridge(spec, "benchmark");
}

records::PulseExcitation Pulse() {
  return records::PulseExcitation(records::PulseShape::kCosine, 0.5 * 9.80665,
                                  2.0 * std::numbers::pi / 0.6, Eigen::Vector2d::UnitX());
}

void TimeStepping(benchmark::State& state, const char* linear_algebra) {
  const model::Model model = Bridge(static_cast<int>(state.range(0)));
  const records::PulseExcitation pulse = Pulse();
  model::RunControl control;
  control.end_time_s = 1.0;
  control.time_step_s = 1e-3;
  control.linear_algebra = linear_algebra;
  dynamics::TimeSteppingWorkspace ws(model);
  int impacts = 0;
  for (auto _ : state) {
    const dynamics::RunResult r = dynamics::SimulateTimeStepping(model, pulse, control, ws);
    impacts = r.impacts;
    benchmark::DoNotOptimize(r.max_abs_q.data());
    if (r.status != dynamics::RunStatus::kOk) {
      state.SkipWithError(r.message.c_str());
      break;
    }
  }
  state.counters["n_dof"] = model.n_dof();
  state.counters["impacts"] = impacts;
}

void EventDriven(benchmark::State& state) {
  const model::Model model = Bridge(static_cast<int>(state.range(0)));
  const records::PulseExcitation pulse = Pulse();
  model::RunControl control;
  control.end_time_s = 1.0;
  dynamics::SimulationWorkspace ws(model);
  int impacts = 0;
  for (auto _ : state) {
    const dynamics::RunResult r = dynamics::Simulate(model, pulse, control, ws);
    impacts = r.impacts;
    benchmark::DoNotOptimize(r.max_abs_q.data());
    if (r.status != dynamics::RunStatus::kOk) {
      state.SkipWithError(r.message.c_str());
      break;
    }
  }
  state.counters["n_dof"] = model.n_dof();
  state.counters["impacts"] = impacts;
}

void TimeSteppingDense(benchmark::State& state) { TimeStepping(state, "dense"); }
void TimeSteppingSparse(benchmark::State& state) { TimeStepping(state, "sparse"); }

void SpanCounts(benchmark::internal::Benchmark* b) {
  for (int n : {1, 2, 3, 4, 5, 10, 20, 50}) {
    b->Arg(n);
  }
  b->Unit(benchmark::kMillisecond);
}

BENCHMARK(TimeSteppingDense)->Apply(SpanCounts);
BENCHMARK(TimeSteppingSparse)->Apply(SpanCounts);
BENCHMARK(EventDriven)->Apply(SpanCounts);

}  // namespace
}  // namespace skewbridge
