// Runs per second of the event-driven integrator, with and without contacts, and the heap
// allocations per run (counting malloc): a run allocates a fixed number of blocks for its
// results, independent of its number of steps.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>

#include "records/incidence.h"
#include "solver/dynamics/compliant_run.h"
#include "solver/dynamics/run.h"
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

// A record cell against a pair cell of the same length (docs/theory.md §2), cold as a sweep runs
// it: the excitation made from the components (records::PairExcitation), a new workspace, the run.
// Arg 0: one record along x (one column, as every record cell without incidence_deg); 1: one
// record along 30 deg (two columns); 2: the pair (H1, 0) at 30 deg, the same run as 1 through the
// pair's path; 3: the pair (H1, H2) at 30 deg, H2 a second signal of another seed. The cost
// ratio of a pair cell is 3 against 0 (different motions, so different impacts and steps: see
// the counters) and 2 against 1 (the same motion: the plumbing alone).
void BM_PilotBridgeCellComponents(benchmark::State& state) {
  const model::Model bridge = bench::PilotBridge(true, bench::kPilotStudyGap_m);
  records::GroundMotion h1, h2, zero;
  h1.file = "h1";
  h1.dt_s = 0.01;
  h1.acc_mps2 = bench::RecordLikeSignal(12345);
  h2 = h1;
  h2.file = "h2";
  h2.acc_mps2 = bench::RecordLikeSignal(54321);
  zero = h1;
  zero.file = "zero";
  std::fill(zero.acc_mps2.begin(), zero.acc_mps2.end(), 0.0);
  model::RunControl control;
  control.end_time_s = 40.0;
  control.energy_ledger = false;
  const long which = state.range(0);
  RunResult r;
  long runs = 0;
  for (auto _ : state) {
    const records::SampledExcitation ex =
        which == 0   ? records::ToExcitation(h1)
        : which == 1 ? records::ToExcitation(h1, records::DirectionAt(30.0))
        : which == 2 ? records::PairExcitation(h1, zero, 30.0)
                     : records::PairExcitation(h1, h2, 30.0);
    const model::Model cell = bridge;
    r = dynamics::Run(cell, ex, control);
    benchmark::DoNotOptimize(r.max_abs_q.data());
    ++runs;
  }
  state.counters["runs_per_s"] =
      benchmark::Counter(static_cast<double>(runs), benchmark::Counter::kIsRate);
  state.counters["steps_per_run"] = static_cast<double>(r.free_steps + r.rk_steps + r.rk_rejected);
  state.counters["events"] = static_cast<double>(r.events.size());
  state.counters["impacts"] = static_cast<double>(r.impacts);
  state.counters["ok"] = r.status == RunStatus::kOk ? 1.0 : 0.0;
}
BENCHMARK(BM_PilotBridgeCellComponents)
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Arg(3)
    ->ArgName("components")
    ->Unit(benchmark::kMillisecond);

// One record cell of the pilot bridge at the study's gap under each joint law, as a sweep cell
// runs it (the model copied, no ledger): 0 the rigid law (eps_N = 0.5, mu = 0.3, dynamics::Run),
// 1 the compliant law (Wilson and Elgamal's backfill, K_max = K_ur = 20 300 kN/m/m, R_f = 0.7,
// F_ult = 326 kN/m over the backwall W / cos a, 5 springs per wall; SimulateCompliant).
void BM_PilotBridgeCellLaw(benchmark::State& state) {
  const model::Model rigid = bench::PilotBridge(true, bench::kPilotStudyGap_m);
  const model::DeckGeometry& g = rigid.body(0).geometry;
  const double wall_m = g.width_m / std::cos(g.skew_rad);
  const joint::HyperbolicGap wall{20.3e6 * wall_m, 20.3e6 * wall_m, 0.7, 326e3 * wall_m, 0.0};
  std::vector<CompliantSpring> springs = WallSprings(rigid, 0, 1, wall, 5, "+x");
  const std::vector<CompliantSpring> minus = WallSprings(rigid, 2, 3, wall, 5, "-x");
  springs.insert(springs.end(), minus.begin(), minus.end());
  const model::Model linear = WithoutContacts(rigid);
  const records::SampledExcitation ex(0.01, bench::RecordLikeSignal());
  model::RunControl control;
  control.end_time_s = 40.0;
  control.energy_ledger = false;
  RunResult r;
  for (auto _ : state) {
    if (state.range(0) == 0) {
      const model::Model cell = rigid;
      r = dynamics::Run(cell, ex, control);
    } else {
      const model::Model cell = linear;
      r = SimulateCompliant(cell, springs, ex, control).run;
    }
    benchmark::DoNotOptimize(r.max_abs_q.data());
  }
  state.counters["steps_per_run"] = static_cast<double>(r.free_steps + r.rk_steps + r.rk_rejected);
  state.counters["rk_steps"] = static_cast<double>(r.rk_steps);
  state.counters["impacts"] = static_cast<double>(r.impacts);
  state.counters["ok"] = r.status == RunStatus::kOk ? 1.0 : 0.0;
}
BENCHMARK(BM_PilotBridgeCellLaw)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("compliant")
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace skewbridge::dynamics
