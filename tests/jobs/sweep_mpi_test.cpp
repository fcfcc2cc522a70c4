// The sweep runner over MPI (launched by ctest with mpiexec -n 2 and -n 3): every cell is
// computed exactly once across the ranks, rank 0 computes too, and the gathered cube equals
// the serial evaluation bit for bit.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "jobs/h5/cube_file.h"
#include "jobs/mpi/mpi_transport.h"
#include "jobs/sweep_runner.h"
#include "solver/common/error.h"
#include "tests/jobs/test_evaluator.h"

namespace skewbridge::jobs::sweep_mpi_test {
namespace {

const char* kSpec = R"(
[sweep]
name = "mpi"
family = "subsystem"
[axes]
pulse = ["cosine", "sine"]
a_deg = [5, 20, 35, 50, 65]
w0_over_wg = {logspace = [0.1, 10.0, 24]}
[fixed]
eta0 = 2.0
)";

int WorldSize() {
  int size = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

TEST(MpiSweep, EveryCellComputedOnceAndCubeEqualsSerialEvaluation) {
  const SweepSpec spec = ParseSweepSpec(kSpec, "spec.toml", ".");
  const testing::TestEvaluator evaluator(spec, 300, 0);
  // 20 ms per cell on the other ranks (the same results): they cannot take all 240 cells
  // while rank 0 opens the cube, however busy the machine.
  const testing::TestEvaluator slow(spec, 300, 20.0);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  SweepOptions options;
  options.out = std::filesystem::temp_directory_path() /
                ("sb_mpi_test_" + std::to_string(WorldSize()) + ".h5");
  options.force = true;
  options.checkpoint_cells = 17;
  options.max_chunk = 8;
  auto transport = MakeMpiTransport();
  const SweepReport report = RunSweep(spec, rank == 0 ? evaluator : slow, *transport, options);

  const std::uint64_t mine = report.cells_this_rank;
  std::uint64_t sum = 0;
  std::uint64_t least = 0;
  MPI_Allreduce(&mine, &sum, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(&mine, &least, 1, MPI_UINT64_T, MPI_MIN, MPI_COMM_WORLD);
  EXPECT_EQ(sum, spec.CellCount());  // with Store's check that no cell arrives twice
  if (transport->Rank() != 0) {
    return;
  }
  EXPECT_GT(mine, 0u) << "rank 0 must compute, not only coordinate";
  EXPECT_TRUE(report.complete);
  EXPECT_EQ(report.cells_computed, spec.CellCount());
  const CubeData data = h5::ReadCubeData(options.out, "mpi", nullptr);
  for (std::uint64_t c = 0; c < spec.CellCount(); ++c) {
    ASSERT_EQ(data.done[c], 1) << "cell " << c;
    EXPECT_EQ(data.run[c], 1);
    if (testing::TestEvaluator::Throws(c)) {
      EXPECT_EQ(data.status[c], kStatusException);
      continue;
    }
    const CellOutcome o = evaluator.Evaluate(spec.AxisIndex(c));
    EXPECT_EQ(data.status[c], o.status);
    for (std::size_t r = 0; r < o.responses.size(); ++r) {
      EXPECT_EQ(std::memcmp(&data.responses[r][c], &o.responses[r], sizeof(double)), 0)
          << "cell " << c << " response " << r;
    }
  }
  std::filesystem::remove(options.out);
}

// Claims that run on to a block's end, racing on every rank: together they hand out every
// position once, in order, and each ends at a multiple of the block or at the list's end.
TEST(MpiClaims, ClaimsToBlockEndsPartitionThePendingListAtBlockBoundaries) {
  auto transport = MakeMpiTransport();
  PendingCells pending;
  constexpr std::uint64_t kCells = 10007, kBlock = 60;
  for (std::uint64_t c = 0; c < kCells; ++c) pending.Append(c);
  transport->BroadcastPending(pending);
  std::vector<std::uint64_t> mine;  // begin, end pairs
  const std::uint64_t counts[] = {1, 7, 59, 60, 61, 130};
  for (std::size_t k = 0;; ++k) {
    const auto [begin, end] = transport->Claim(counts[k % 6], kBlock);
    if (begin >= end) break;
    mine.push_back(begin);
    mine.push_back(end);
  }
  int size = WorldSize(), rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const int n = static_cast<int>(mine.size());
  std::vector<int> counts_of(static_cast<std::size_t>(size)), at(static_cast<std::size_t>(size));
  MPI_Gather(&n, 1, MPI_INT, counts_of.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  int total = 0;
  for (int r = 0; r < size; ++r) {
    at[static_cast<std::size_t>(r)] = total;
    total += counts_of[static_cast<std::size_t>(r)];
  }
  std::vector<std::uint64_t> all(static_cast<std::size_t>(total));
  MPI_Gatherv(mine.data(), n, MPI_UINT64_T, all.data(), counts_of.data(), at.data(), MPI_UINT64_T,
              0, MPI_COMM_WORLD);
  if (rank != 0) return;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> claims;
  for (std::size_t i = 0; i + 1 < all.size(); i += 2) claims.emplace_back(all[i], all[i + 1]);
  std::sort(claims.begin(), claims.end());
  std::uint64_t next = 0;
  for (const auto& [begin, end] : claims) {
    EXPECT_EQ(begin, next) << "a gap or an overlap before " << begin;
    EXPECT_TRUE(end % kBlock == 0 || end == kCells) << "a claim ends at " << end;
    EXPECT_GE(end - begin, 1u);
    next = end;
  }
  EXPECT_EQ(next, kCells);
  EXPECT_GE(claims.size(), kCells / (2 * kBlock));  // more than a few large claims
}

// The final cube's chunk farm on 2 and 3 ranks, where rank 0 runs jobs too: every job's result
// reaches rank 0 exactly once and is the work's result for that job whichever rank ran it; a
// throwing `done` ends the farm on every rank, rethrown on rank 0 alone, and leaves no message
// behind (a second farm on the same transport gets its own results).
std::vector<char> FarmJob(std::size_t i) {
  std::vector<char> bytes(100 + (i * 977) % 70000);  // above and below MPI's eager limits
  for (std::size_t k = 0; k < bytes.size(); ++k) bytes[k] = static_cast<char>((i * 31 + k) % 251);
  return bytes;
}

std::vector<char> FarmWork(std::span<const char> in) {
  std::vector<char> out(in.rbegin(), in.rend());  // the job reversed, then its length mod 256
  out.push_back(static_cast<char>(in.size() % 256));
  return out;
}

TEST(MpiFarm, EveryJobsResultReachesRankZeroOnceAndAThrowingDoneEndsItOnEveryRank) {
  auto transport = MakeMpiTransport();
  const bool root = transport->Rank() == 0;
  constexpr std::size_t kJobs = 300;
  std::map<std::size_t, int> seen;
  std::size_t wrong = 0;
  auto check = [&](std::size_t i, std::span<const char> result) {
    ++seen[i];
    const std::vector<char> expected = FarmWork(FarmJob(i));
    if (!std::equal(result.begin(), result.end(), expected.begin(), expected.end())) ++wrong;
  };
  if (root) {
    transport->Farm(kJobs, FarmJob, FarmWork, check);
    EXPECT_EQ(seen.size(), kJobs);
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](const auto& e) { return e.second == 1; }));
    EXPECT_EQ(wrong, 0u);
  } else {
    transport->Farm(0, {}, FarmWork, {});
  }

  std::size_t calls = 0;
  const auto failing = [&](std::size_t, std::span<const char>) {
    if (++calls == 7) throw std::runtime_error("disk full");
  };
  if (root) {
    EXPECT_THROW(transport->Farm(kJobs, FarmJob, FarmWork, failing), std::runtime_error);
    EXPECT_EQ(calls, 7u);  // no result handed on after the failure
  } else {
    EXPECT_NO_THROW(transport->Farm(0, {}, FarmWork, {}));
  }

  seen.clear();
  wrong = 0;
  if (root) {
    transport->Farm(20, FarmJob, FarmWork, check);
    EXPECT_EQ(seen.size(), 20u);
    EXPECT_EQ(wrong, 0u);
  } else {
    transport->Farm(0, {}, FarmWork, {});
  }
}

TEST(MpiSweep, RankZeroOnlyGathersAboveTheThresholdAndTheCubeIsUnchanged) {
  const SweepSpec spec = ParseSweepSpec(kSpec, "spec.toml", ".");
  const testing::TestEvaluator evaluator(spec, 100, 0);
  SweepOptions options;
  options.out = std::filesystem::temp_directory_path() /
                ("sb_mpi_gather_" + std::to_string(WorldSize()) + ".h5");
  options.force = true;
  options.root_computes_up_to_ranks = 1;
  auto transport = MakeMpiTransport();
  const SweepReport report = RunSweep(spec, evaluator, *transport, options);
  const std::uint64_t mine = report.cells_this_rank;
  std::uint64_t sum = 0;
  MPI_Allreduce(&mine, &sum, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  EXPECT_EQ(sum, spec.CellCount());
  if (transport->Rank() != 0) {
    return;
  }
  EXPECT_EQ(mine, 0u);
  EXPECT_TRUE(report.complete);
  const CubeData data = h5::ReadCubeData(options.out, "mpi", nullptr);
  for (std::uint64_t c = 0; c < spec.CellCount(); ++c) {
    ASSERT_EQ(data.done[c], 1);
    if (!testing::TestEvaluator::Throws(c)) {
      const CellOutcome o = evaluator.Evaluate(spec.AxisIndex(c));
      EXPECT_EQ(std::memcmp(&data.responses[0][c], &o.responses[0], sizeof(double)), 0);
    }
  }
  std::filesystem::remove(options.out);
}

TEST(MpiSweep, StopOnRankZeroAloneCheckpointsEveryComputedCellAndResumes) {
  const SweepSpec spec = ParseSweepSpec(kSpec, "spec.toml", ".");
  // 2 ms per cell: the other ranks cannot finish the 240 cells while rank 0 does its 3.
  const testing::TestEvaluator evaluator(spec, 100, 2.0);
  volatile std::sig_atomic_t flag = 0;  // per process: only rank 0's evaluator sets it
  const testing::StoppingEvaluator stopping(evaluator, 3, &flag);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  SweepOptions options;
  options.out = std::filesystem::temp_directory_path() /
                ("sb_mpi_stop_" + std::to_string(WorldSize()) + ".h5");
  options.force = true;
  options.stop = &flag;
  options.max_chunk = 4;
  std::uint64_t computed_everywhere = 0;
  {
    auto transport = MakeMpiTransport();
    const SweepReport first =
        RunSweep(spec, rank == 0 ? static_cast<const CellEvaluator&>(stopping) : evaluator,
                 *transport, options);
    const std::uint64_t mine = first.cells_this_rank;
    MPI_Allreduce(&mine, &computed_everywhere, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    if (rank == 0) {
      EXPECT_TRUE(first.interrupted);
      EXPECT_FALSE(first.complete);
      // Everything any rank computed before it heard of the stop reached the file.
      EXPECT_EQ(first.cells_done, computed_everywhere);
      EXPECT_LT(first.cells_done, spec.CellCount());
    }
  }
  options.force = false;
  options.resume = true;
  flag = 0;
  auto transport = MakeMpiTransport();
  const SweepReport second = RunSweep(spec, evaluator, *transport, options);
  if (rank != 0) {
    return;
  }
  EXPECT_TRUE(second.complete);
  EXPECT_EQ(second.cells_computed, spec.CellCount() - computed_everywhere);
  const CubeData data = h5::ReadCubeData(options.out, "mpi", nullptr);
  std::uint64_t first_run = 0;
  for (std::uint64_t c = 0; c < spec.CellCount(); ++c) {
    first_run += data.run[c] == 1;
    if (!testing::TestEvaluator::Throws(c)) {
      const CellOutcome o = evaluator.Evaluate(spec.AxisIndex(c));
      EXPECT_EQ(std::memcmp(&data.responses[1][c], &o.responses[1], sizeof(double)), 0);
    }
  }
  EXPECT_EQ(first_run, computed_everywhere);
  std::filesystem::remove(options.out);
}

// Ranks > 0 compute while rank 0 creates the checkpoint file; a creation that fails (a folder
// where no file can be made, even by root) ends every rank with the same error, naming the
// checkpoint file, leaves no file behind, and leaves no message in flight: a sweep on a new
// transport then runs to a complete cube.
TEST(MpiSweep, AFailedCheckpointCreationEndsEveryRankWithItsErrorAndNoFile) {
  const SweepSpec spec = ParseSweepSpec(kSpec, "spec.toml", ".");
  const testing::TestEvaluator evaluator(spec, 100, 0);
  const testing::TestEvaluator slow(spec, 100, 5.0);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  SweepOptions options;
  options.out = "/proc/sb_mpi_no_file_" + std::to_string(WorldSize()) + ".h5";
  options.max_chunk = 4;
  std::string error;
  {
    auto transport = MakeMpiTransport();
    try {
      RunSweep(spec, rank == 0 ? evaluator : slow, *transport, options);
    } catch (const InputError& e) {
      error = e.what();
    }
    transport.reset();
  }
  EXPECT_NE(error.find(options.out.string() + ".partial: create: "), std::string::npos) << error;
  std::error_code ec;
  EXPECT_FALSE(std::filesystem::exists(options.out, ec));
  EXPECT_FALSE(std::filesystem::exists(PartialPath(options.out), ec));
  // Every rank holds the same line (rank 0's, broadcast).
  std::uint64_t length = error.size();
  std::uint64_t longest = 0;
  MPI_Allreduce(&length, &longest, 1, MPI_UINT64_T, MPI_MAX, MPI_COMM_WORLD);
  EXPECT_EQ(length, longest);

  options.out = std::filesystem::temp_directory_path() /
                ("sb_mpi_after_failure_" + std::to_string(WorldSize()) + ".h5");
  options.force = true;
  auto transport = MakeMpiTransport();
  const SweepReport report = RunSweep(spec, rank == 0 ? evaluator : slow, *transport, options);
  if (rank == 0) {
    EXPECT_TRUE(report.complete);
    EXPECT_EQ(report.cells_done, spec.CellCount());
    std::filesystem::remove(options.out);
  }
}

}  // namespace
}  // namespace skewbridge::jobs::sweep_mpi_test
