// Runs per second of the event-driven integrator, with and without contacts, and the heap
// allocations per run (a counting global operator new): a run allocates a fixed number of
// blocks for its results, independent of its number of steps.
#include <benchmark/benchmark.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "solver/dynamics/simulate.h"
#include "tests/dynamics/benchmark_cases.h"

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
  const bench::Case c = bench::SubsystemCosinePulse(state.range(0) != 0);
  Run(state, c.model, *c.excitation, c.control);
}
BENCHMARK(BM_SubsystemCosinePulse)->Arg(1)->Arg(0)->ArgName("contacts");

void BM_PilotBridgeRecord(benchmark::State& state) {
  const bench::Case c = bench::PilotBridgeRecord(state.range(0) != 0);
  Run(state, c.model, *c.excitation, c.control);
}
BENCHMARK(BM_PilotBridgeRecord)->Arg(1)->Arg(0)->ArgName("contacts")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace skewbridge::dynamics
