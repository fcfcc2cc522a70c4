// Speed of the ground-motion tools: reading, measures, spectrum and synthesis of one record.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <vector>

#include "records/ground_motion.h"
#include "records/measures.h"
#include "records/synthetic.h"

namespace skewbridge::records {
namespace {

const std::filesystem::path kRecord =
    std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) / "records" / "RSN763_LOMAP_GIL067.AT2";

void BM_ReadAt2(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(ReadRecord(kRecord));
  state.SetItemsProcessed(state.iterations() * 7999);
}
BENCHMARK(BM_ReadAt2);

void BM_ComputeMeasures(benchmark::State& state) {
  const GroundMotion motion = ReadRecord(kRecord);
  for (auto _ : state) benchmark::DoNotOptimize(ComputeMeasures(motion));
}
BENCHMARK(BM_ComputeMeasures);

void BM_PseudoAccelerationSpectrum100Periods(benchmark::State& state) {
  const GroundMotion motion = ReadRecord(kRecord);
  std::vector<double> periods;
  for (int i = 1; i <= 100; ++i) periods.push_back(0.04 * i);
  for (auto _ : state) {
    benchmark::DoNotOptimize(PseudoAccelerationSpectrum(motion.acc_mps2, motion.dt_s, periods));
  }
}
BENCHMARK(BM_PseudoAccelerationSpectrum100Periods);

void BM_SynthesizeRecord30s(benchmark::State& state) {
  const SynthOptions options;
  int index = 0;
  for (auto _ : state) benchmark::DoNotOptimize(SynthesizeRecord(options, index++));
}
BENCHMARK(BM_SynthesizeRecord30s);

}  // namespace
}  // namespace skewbridge::records
