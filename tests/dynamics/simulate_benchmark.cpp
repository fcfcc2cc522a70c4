// Runs per second of the event-driven integrator, with and without contacts, and the heap
// allocations per run (a counting global operator new): a run allocates a fixed number of
// blocks for its results, independent of its number of steps.
#include <benchmark/benchmark.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <numbers>
#include <random>

#include "records/excitations.h"
#include "solver/dynamics/simulate.h"
#include "solver/model/builders.h"
#include "solver/model/model_file.h"

// The replacement pair below is malloc/free on both sides; GCC cannot see that through new.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) {
    return p;
  }
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace skewbridge::dynamics {
namespace {

constexpr double kPi = std::numbers::pi;

model::Model Subsystem(double gap_m) {
  model::DeckSpec spec;
  spec.mass_kg = 1.0e5;
  spec.geometry = {30.0, model::WidthFromEta0(2.0, 30.0 * kPi / 180.0, 30.0), 30.0 * kPi / 180.0};
  spec.w0x_radps = spec.w0y_radps = spec.W0_radps = kPi;
  spec.gap_plus_m = gap_m;
  spec.restitution = 0.5;
  spec.friction = 0.2;
  return model::BuildDeckModel(spec);
}

void Run(benchmark::State& state, const model::Model& m, const Excitation& ex,
         const model::RunControl& control) {
  SimulationWorkspace ws(m);
  RunResult r = Simulate(m, ex, control, ws);  // warm the propagator cache
  long runs = 0;
  const long before = g_allocations.load();
  for (auto _ : state) {
    r = Simulate(m, ex, control, ws);
    benchmark::DoNotOptimize(r.max_abs_q.data());
    ++runs;
  }
  const long allocations = g_allocations.load() - before;
  state.counters["runs_per_s"] =
      benchmark::Counter(static_cast<double>(runs), benchmark::Counter::kIsRate);
  state.counters["allocs_per_run"] = static_cast<double>(allocations) / static_cast<double>(runs);
  state.counters["steps_per_run"] = static_cast<double>(r.free_steps + r.rk_steps + r.rk_rejected);
  state.counters["impacts"] = static_cast<double>(r.impacts);
  state.counters["ok"] = r.status == RunStatus::kOk ? 1.0 : 0.0;
}

void BM_SubsystemCosinePulse(benchmark::State& state) {
  const model::Model m = Subsystem(state.range(0) ? 0.5 * 5.0 / (4.0 * kPi * kPi) : 1e3);
  const records::PulseExcitation pulse(records::PulseShape::kCosine, 5.0, 2.0 * kPi);
  model::RunControl control;
  control.end_time_s = 3.0;
  Run(state, m, pulse, control);
}
BENCHMARK(BM_SubsystemCosinePulse)->Arg(1)->Arg(0)->ArgName("contacts");

void BM_PilotBridgeRecord(benchmark::State& state) {
  const model::ModelFile file = model::ParseModelFile(std::string(SKEWBRIDGE_TEST_DATA_DIR) +
                                                      "/../../docs/examples/pilot-bridge.toml");
  model::DeckSpec spec = file.deck;
  if (state.range(0)) {
    spec.gap_plus_m = spec.gap_minus_m = 0.002;
  } else {
    spec.gap_plus_m = spec.gap_minus_m = 1e3;
  }
  const model::Model m = model::BuildDeckModel(spec);
  // A record-like signal: seeded white noise through a 2 Hz resonator, 40 s at 0.01 s, PGA 3 m/s^2.
  std::mt19937 rng(12345);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<double> a(4001);
  double x = 0.0, v = 0.0, peak = 0.0;
  const double w = 4.0 * kPi, dt = 0.01;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double envelope = std::sin(kPi * static_cast<double>(i) / 4000.0);
    v += dt * (-w * w * x - 2.0 * 0.3 * w * v + 30.0 * noise(rng));
    x += dt * v;
    a[i] = envelope * w * w * x;
    peak = std::max(peak, std::abs(a[i]));
  }
  for (double& ai : a) ai *= 3.0 / peak;
  const records::SampledExcitation record(dt, a);
  model::RunControl control;
  control.end_time_s = 40.0;
  Run(state, m, record, control);
}
BENCHMARK(BM_PilotBridgeRecord)->Arg(1)->Arg(0)->ArgName("contacts")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace skewbridge::dynamics
