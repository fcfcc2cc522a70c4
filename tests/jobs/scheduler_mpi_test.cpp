// The scheduler on 8 oversubscribed ranks with cheap cells, rank 0 only gathering as it does
// above SweepOptions::root_computes_up_to_ranks: every cell is computed exactly once, results
// travel as one message per claimed chunk (not per cell), and the cube equals the serial run's
// bit for bit whatever the chunking, its chunks deflated by the other ranks stored as the very
// bytes HDF5 writes in the serial run. Speed is measured by scheduler_benchmark, not here.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "jobs/h5/cube_file.h"
#include "jobs/mpi/mpi_transport.h"
#include "jobs/sweep_runner.h"
#include "tests/jobs/test_evaluator.h"

namespace skewbridge::jobs::scheduler_mpi_test {
namespace {

// 2 x 40 x 1000 = 80 000 cells.
const char* kSpec = R"(
[sweep]
name = "scheduler"
family = "subsystem"
[axes]
pulse = ["cosine", "sine"]
a_deg = {linspace = [1, 80, 40]}
w0_over_wg = {logspace = [0.1, 10.0, 1000]}
[fixed]
eta0 = 2.0
)";

int Rank() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

std::uint64_t Sum(std::uint64_t mine) {
  std::uint64_t sum = 0;
  MPI_Allreduce(&mine, &sum, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  return sum;
}

template <typename T>
bool SameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// The datasets that must not depend on the ranks or the chunking (wall_s is a timing).
void ExpectSameCube(const CubeData& a, const CubeData& b) {
  ASSERT_EQ(a.responses.size(), b.responses.size());
  for (std::size_t r = 0; r < a.responses.size(); ++r) {
    EXPECT_TRUE(SameBytes(a.responses[r], b.responses[r])) << "response " << r;
  }
  EXPECT_TRUE(SameBytes(a.status, b.status));
  EXPECT_TRUE(SameBytes(a.events, b.events));
  EXPECT_TRUE(SameBytes(a.steps, b.steps));
  EXPECT_TRUE(SameBytes(a.done, b.done));
  EXPECT_TRUE(SameBytes(a.run, b.run));
}

class Scheduler8 : public ::testing::TestWithParam<std::pair<std::uint64_t, double>> {};

TEST_P(Scheduler8, EveryCellOnceOneMessagePerChunkAndTheSerialCube) {
  ASSERT_EQ(
      [] {
        int size = 0;
        MPI_Comm_size(MPI_COMM_WORLD, &size);
        return size;
      }(),
      8);
  const SweepSpec spec = ParseSweepSpec(kSpec, "spec.toml", ".");
  const testing::TestEvaluator evaluator(spec, 0, 0);
  const auto dir = std::filesystem::temp_directory_path();
  const std::string tag = std::to_string(GetParam().first);
  SweepOptions serial;
  serial.out = dir / ("sb_sched_serial_" + tag + ".h5");
  serial.force = true;
  if (Rank() == 0) {
    auto alone = MakeInProcessTransport();
    ASSERT_TRUE(RunSweep(spec, evaluator, *alone, serial).complete);
  }
  MPI_Barrier(MPI_COMM_WORLD);

  SweepOptions options;
  options.out = dir / ("sb_sched_mpi_" + tag + ".h5");
  options.force = true;
  options.root_computes_up_to_ranks = 1;
  options.max_chunk = GetParam().first;
  options.chunk_seconds = GetParam().second;
  options.checkpoint_cells = 9000;  // checkpoints of many chunks while cells arrive
  auto transport = MakeMpiTransport();
  const SweepReport report = RunSweep(spec, evaluator, *transport, options);

  EXPECT_EQ(Sum(report.cells_this_rank), spec.CellCount());
  const std::uint64_t chunks = Sum(report.chunks_this_rank);
  if (Rank() != 0) {
    EXPECT_LE(report.chunks_this_rank, report.cells_this_rank);
    return;
  }
  EXPECT_EQ(report.cells_this_rank, 0u) << "rank 0 only gathers";
  EXPECT_TRUE(report.complete);
  EXPECT_EQ(report.cells_computed, spec.CellCount());
  EXPECT_EQ(report.messages_received, chunks) << "one message per chunk";
  EXPECT_LT(report.messages_received, spec.CellCount() / 4) << "results travel in batches";
  // Reported, not asserted (speed belongs to scheduler_benchmark): rank 0's rate while busy.
  RecordProperty("rank0_cells_per_cpu_s",
                 std::to_string(static_cast<double>(report.cells_computed) /
                                std::max(report.receive_busy_s, 1e-9)));
  std::printf("rank 0: %llu messages, %.3g cells per CPU second while receiving\n",
              static_cast<unsigned long long>(report.messages_received),
              static_cast<double>(report.cells_computed) / std::max(report.receive_busy_s, 1e-9));
  std::vector<std::string> names;
  const CubeData parallel = h5::ReadCubeData(options.out, "scheduler", &names);  // checksums on
  const CubeData alone = h5::ReadCubeData(serial.out, "scheduler", nullptr);
  ExpectSameCube(parallel, alone);
  // The final cube's chunks were deflated by the 7 other ranks and written as stored bytes;
  // the serial run filtered them through HDF5. Every chunk is the same bytes, checksum
  // included (wall_s, a timing, excepted).
  std::vector<std::string> datasets = {"status", "done", "stats/run", "stats/events",
                                       "stats/steps"};
  for (const std::string& r : names) datasets.push_back("responses/" + r);
  for (const std::string& name : datasets) {
    const auto farmed = h5::ReadStoredChunks(options.out, "scheduler", name);
    const auto hdf5 = h5::ReadStoredChunks(serial.out, "scheduler", name);
    EXPECT_EQ(farmed.size(), 10u) << name << ": 2 x 5 chunks of 8 rows";
    EXPECT_TRUE(farmed == hdf5) << name;
  }
  // And both equal the evaluator itself (the serial run is not its own oracle).
  for (std::uint64_t c = 0; c < spec.CellCount(); c += 97) {
    if (testing::TestEvaluator::Throws(c)) {
      EXPECT_EQ(parallel.status[c], kStatusException);
      continue;
    }
    const CellOutcome o = evaluator.Evaluate(spec.AxisIndex(c));
    EXPECT_EQ(std::memcmp(&parallel.responses[0][c], &o.responses[0], sizeof(double)), 0) << c;
    EXPECT_EQ(parallel.responses[2][c], static_cast<double>(c));
  }
  std::filesystem::remove(options.out);
  std::filesystem::remove(serial.out);
}

// From collective_final_from_ranks on, every rank writes its own cells into the final cube with
// parallel HDF5's filtered collective writes (rank 0 its own, as it computes cells too here):
// the cube is the serial run's, value for value and stored byte for stored byte, complete,
// and it reads back through its checksums.
TEST(Scheduler8Collective, EveryRankWritesItsCellsAndTheCubeIsTheSerialOne) {
  const SweepSpec spec = ParseSweepSpec(kSpec, "spec.toml", ".");
  const testing::TestEvaluator evaluator(spec, 0, 0);
  const auto dir = std::filesystem::temp_directory_path();
  SweepOptions serial;
  serial.out = dir / "sb_sched_serial_collective.h5";
  serial.force = true;
  if (Rank() == 0) {
    auto alone = MakeInProcessTransport();
    ASSERT_TRUE(RunSweep(spec, evaluator, *alone, serial).complete);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  SweepOptions options;
  options.out = dir / "sb_sched_collective.h5";
  options.force = true;
  options.max_chunk = 700;  // many chunks per rank: scattered cells, edge boxes in every row
  options.checkpoint_cells = 9000;
  options.collective_final_from_ranks = 2;
  auto transport = MakeMpiTransport();
  const SweepReport report = RunSweep(spec, evaluator, *transport, options);
  EXPECT_EQ(Sum(report.cells_this_rank), spec.CellCount());
  if (Rank() != 0) {
    return;
  }
  EXPECT_GT(report.cells_this_rank, 0u) << "rank 0 computes (and writes) cells too";
  EXPECT_TRUE(report.complete);
  EXPECT_FALSE(std::filesystem::exists(PartialPath(options.out)));
  EXPECT_FALSE(std::filesystem::exists(options.out.string() + ".tmp"));
  ASSERT_EQ(h5::SummarizeCube(options.out).size(), 1u);
  EXPECT_TRUE(h5::SummarizeCube(options.out)[0].complete);
  std::vector<std::string> names;
  const CubeData parallel = h5::ReadCubeData(options.out, "scheduler", &names);  // checksums on
  const CubeData alone = h5::ReadCubeData(serial.out, "scheduler", nullptr);
  ExpectSameCube(parallel, alone);
  std::vector<std::string> datasets = {"status", "done", "stats/run", "stats/events",
                                       "stats/steps"};
  for (const std::string& r : names) datasets.push_back("responses/" + r);
  for (const std::string& name : datasets) {
    EXPECT_TRUE(h5::ReadStoredChunks(options.out, "scheduler", name) ==
                h5::ReadStoredChunks(serial.out, "scheduler", name))
        << name;
  }
  std::filesystem::remove(options.out);
  std::filesystem::remove(serial.out);
}

// A resumed sweep written collectively: rank 0 writes the cells of the first run (computed
// alone, interrupted after 30 000 cells) beside its own of the second, the others theirs; the
// cube is the serial one, and stats/run tells the runs apart.
TEST(Scheduler8Collective, AResumedCubeHoldsBothRunsCells) {
  const SweepSpec spec = ParseSweepSpec(kSpec, "spec.toml", ".");
  const testing::TestEvaluator evaluator(spec, 0, 0);
  const auto dir = std::filesystem::temp_directory_path();
  SweepOptions serial;
  serial.out = dir / "sb_sched_serial_resumed.h5";
  serial.force = true;
  SweepOptions options;
  options.out = dir / "sb_sched_collective_resumed.h5";
  options.force = true;
  options.checkpoint_cells = 5000;
  options.collective_final_from_ranks = 2;
  if (Rank() == 0) {
    auto alone = MakeInProcessTransport();
    ASSERT_TRUE(RunSweep(spec, evaluator, *alone, serial).complete);
    volatile std::sig_atomic_t flag = 0;
    const testing::StoppingEvaluator stopping(evaluator, 30000, &flag);
    SweepOptions first = options;
    first.stop = &flag;
    auto again = MakeInProcessTransport();
    ASSERT_TRUE(RunSweep(spec, stopping, *again, first).interrupted);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  options.force = false;
  options.resume = true;
  options.max_chunk = 700;
  auto transport = MakeMpiTransport();
  const SweepReport report = RunSweep(spec, evaluator, *transport, options);
  if (Rank() != 0) {
    return;
  }
  EXPECT_TRUE(report.complete);
  EXPECT_EQ(report.run, 2);
  EXPECT_EQ(report.cells_computed, spec.CellCount() - 30000);
  const CubeData resumed = h5::ReadCubeData(options.out, "scheduler", nullptr);
  const CubeData alone = h5::ReadCubeData(serial.out, "scheduler", nullptr);
  for (std::size_t r = 0; r < alone.responses.size(); ++r) {
    EXPECT_TRUE(SameBytes(resumed.responses[r], alone.responses[r])) << "response " << r;
  }
  EXPECT_TRUE(SameBytes(resumed.status, alone.status));
  EXPECT_TRUE(SameBytes(resumed.events, alone.events));
  EXPECT_TRUE(SameBytes(resumed.done, alone.done));
  const auto first_run = static_cast<std::uint64_t>(
      std::count(resumed.run.begin(), resumed.run.end(), std::int32_t{1}));
  EXPECT_EQ(first_run, 30000u);
  EXPECT_EQ(std::count(resumed.run.begin(), resumed.run.end(), std::int32_t{2}),
            static_cast<std::ptrdiff_t>(spec.CellCount() - 30000));
  std::filesystem::remove(options.out);
  std::filesystem::remove(serial.out);
}

// Tiny chunks (a message every 1 to 5 cells) and large ones (time-capped, up to 65536 cells).
INSTANTIATE_TEST_SUITE_P(Chunking, Scheduler8,
                         ::testing::Values(std::make_pair(std::uint64_t{5}, 0.05),
                                           std::make_pair(std::uint64_t{65536}, 0.01)));

}  // namespace
}  // namespace skewbridge::jobs::scheduler_mpi_test
