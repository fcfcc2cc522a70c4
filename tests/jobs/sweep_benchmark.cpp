// Cost of the sweep machinery itself, per cell: the runner with a trivial evaluator on one
// process (evaluation bookkeeping, checkpoint file, final compressed cube) and the packing of
// results for the trip to rank 0. Cross-rank overhead: see docs/hdf5-layout.md and the report
// commands (mpiexec -n 4 sweep_test_driver ... --work 0).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "jobs/sweep_runner.h"
#include "tests/jobs/test_evaluator.h"

namespace skewbridge::jobs {
namespace {

SweepSpec Spec(std::int64_t cells_per_row) {
  const std::string text =
      "[sweep]\nname = \"bench\"\nfamily = \"subsystem\"\n[axes]\n"
      "a_deg = {linspace = [5, 60, 10]}\n"
      "w0_over_wg = {logspace = [0.1, 10.0, " +
      std::to_string(cells_per_row) + "]}\n";
  return ParseSweepSpec(text, "bench.toml", ".");
}

void BM_InProcessSweepPerCell(benchmark::State& state) {
  const SweepSpec spec = Spec(state.range(0));
  const testing::TestEvaluator evaluator(spec, 0, 0);
  SweepOptions options;
  options.out = std::filesystem::temp_directory_path() / "sb_sweep_benchmark.h5";
  options.force = true;
  options.checkpoint_cells = 1000;
  for (auto _ : state) {
    auto transport = MakeInProcessTransport();
    benchmark::DoNotOptimize(RunSweep(spec, evaluator, *transport, options));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(spec.CellCount()));
  std::filesystem::remove(options.out);
}
BENCHMARK(BM_InProcessSweepPerCell)->Arg(100)->Arg(10000)->Unit(benchmark::kMillisecond);

// One chunk's results: packing on the computing rank, unpacking (no copy) on rank 0.
void BM_PackUnpackBatch(benchmark::State& state) {
  ResultBatch batch;
  batch.Reset(0, static_cast<std::uint64_t>(state.range(0)), 3);
  for (auto _ : state) {
    const std::vector<char> bytes = PackBatch(batch);
    benchmark::DoNotOptimize(UnpackBatch(bytes).values);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_PackUnpackBatch)->Arg(64)->Arg(65536);

}  // namespace
}  // namespace skewbridge::jobs
