// Runs per second of the event-driven integrator, with and without contacts, and the heap
// allocations per run (counting malloc): a run allocates a fixed number of blocks for its
// results, independent of its number of steps.
#include <benchmark/benchmark.h>

#include <atomic>
#include <cstdlib>

#include "solver/dynamics/simulate.h"
#include "tests/dynamics/benchmark_cases.h"

// Every heap block counts, Eigen's (malloc) as well as operator new's (which calls malloc):
// malloc, calloc and realloc are interposed on glibc's own entry points.
namespace {
std::atomic<long> g_allocations{0};
}  // namespace

extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* p, std::size_t size);
void* malloc(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
void* realloc(void* p, std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(p, size);
}
}

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

// Cold: a new model and workspace for every run, and no energy ledger, which is what a sweep cell
// does (every cell is a new model, so nothing is cached from the previous one).
void RunCold(benchmark::State& state, const model::Model& m, const Excitation& ex,
             model::RunControl control) {
  control.energy_ledger = false;
  RunResult r;
  long runs = 0;
  for (auto _ : state) {
    const model::Model cell = m;
    SimulationWorkspace ws(cell);
    r = Simulate(cell, ex, control, ws);
    benchmark::DoNotOptimize(r.max_abs_q.data());
    ++runs;
  }
  state.counters["runs_per_s"] =
      benchmark::Counter(static_cast<double>(runs), benchmark::Counter::kIsRate);
  state.counters["steps_per_run"] = static_cast<double>(r.free_steps + r.rk_steps + r.rk_rejected);
  state.counters["impacts"] = static_cast<double>(r.impacts);
  state.counters["ok"] = r.status == RunStatus::kOk ? 1.0 : 0.0;
}

void BM_SubsystemCosinePulseCold(benchmark::State& state) {
  const bench::Case c = bench::SubsystemCosinePulse(state.range(0) != 0);
  RunCold(state, c.model, *c.excitation, c.control);
}
BENCHMARK(BM_SubsystemCosinePulseCold)->Arg(1)->Arg(0)->ArgName("contacts");

void BM_PilotBridgeRecordStudyGapCold(benchmark::State& state) {
  const bench::Case c = bench::PilotBridgeRecord(true, bench::kPilotStudyGap_m);
  RunCold(state, c.model, *c.excitation, c.control);
}
BENCHMARK(BM_PilotBridgeRecordStudyGapCold)->Unit(benchmark::kMillisecond);

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

// The same signal with the gaps of the pilot study's smallest Pi_delta (0.5): the with-contact
// cost at the gaps the study uses, against BM_PilotBridgeRecord/contacts:0.
void BM_PilotBridgeRecordStudyGap(benchmark::State& state) {
  const bench::Case c = bench::PilotBridgeRecord(true, bench::kPilotStudyGap_m);
  Run(state, c.model, *c.excitation, c.control);
}
BENCHMARK(BM_PilotBridgeRecordStudyGap)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace skewbridge::dynamics
