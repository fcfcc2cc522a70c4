// The sweep runner on one process: the cube equals a direct evaluation bit for bit, failures
// are data, an interrupted sweep resumes computing only its missing cells, and unusable output
// files are refused before any work.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "jobs/h5/cube_file.h"
#include "jobs/sweep_runner.h"
#include "solver/common/error.h"
#include "tests/jobs/test_evaluator.h"

namespace skewbridge::jobs::sweep_runner_test {
namespace {

using ::testing::HasSubstr;
using testing::StoppingEvaluator;
using testing::TestEvaluator;

const char* kSpec = R"(
[sweep]
name = "runner"
family = "subsystem"
[axes]
pulse = ["cosine", "sine"]
a_deg = [10, 30, 50]
w0_over_wg = {linspace = [0.2, 4.0, 7]}
[fixed]
eta0 = 1.5
xi = 0.05
)";

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

class SweepRunnerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("sb_runner_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    options_.out = dir_ / "cube.h5";
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  SweepReport Run(const SweepSpec& spec, const CellEvaluator& evaluator) {
    auto transport = MakeInProcessTransport();
    return RunSweep(spec, evaluator, *transport, options_);
  }

  // Every done cell of `data` equals the direct evaluation, bit for bit.
  void ExpectMatchesDirect(const SweepSpec& spec, const CubeData& data, bool all_done) {
    const TestEvaluator direct(spec, 50, 0);
    for (std::uint64_t c = 0; c < spec.CellCount(); ++c) {
      if (!data.done[c]) {
        EXPECT_FALSE(all_done) << "cell " << c;
        continue;
      }
      if (TestEvaluator::Throws(c)) {
        EXPECT_EQ(data.status[c], kStatusException);
        EXPECT_TRUE(std::isnan(data.responses[0][c]));
        continue;
      }
      const CellOutcome o = direct.Evaluate(spec.AxisIndex(c));
      EXPECT_EQ(data.status[c], o.status) << "cell " << c;
      for (std::size_t r = 0; r < o.responses.size(); ++r) {
        EXPECT_TRUE(SameBits(data.responses[r][c], o.responses[r])) << "cell " << c;
      }
      EXPECT_EQ(data.steps[c], o.stats.steps);
      EXPECT_EQ(data.events[c], o.stats.events);
    }
  }

  std::filesystem::path dir_;
  SweepOptions options_;
};

TEST_F(SweepRunnerTest, CubeEqualsDirectEvaluationAndRecordsFailures) {
  const SweepSpec spec = ParseSweepSpec(kSpec, "spec.toml", ".");
  const TestEvaluator evaluator(spec, 50, 0);
  const SweepReport report = Run(spec, evaluator);
  EXPECT_TRUE(report.complete);
  EXPECT_EQ(report.cells_computed, 42u);
  EXPECT_TRUE(std::filesystem::exists(options_.out));
  EXPECT_FALSE(std::filesystem::exists(PartialPath(options_.out)));
  std::vector<std::string> names;
  const CubeData data = h5::ReadCubeData(options_.out, "runner", &names);
  EXPECT_EQ(names, (std::vector<std::string>{"x_peak", "theta_peak", "cell_echo"}));
  ExpectMatchesDirect(spec, data, true);
  std::uint64_t ray = 0;
  std::uint64_t thrown = 0;
  for (std::uint64_t c = 0; c < 42; ++c) {
    ray += TestEvaluator::Fails(c);
    thrown += TestEvaluator::Throws(c);
  }
  ASSERT_GT(ray + thrown, 0u) << "the test grid should contain failing cells";
  EXPECT_EQ(report.cells_failed, ray + thrown);
  const auto summary = h5::SummarizeCube(options_.out);
  ASSERT_EQ(summary.size(), 1u);
  EXPECT_TRUE(summary[0].complete);
  EXPECT_EQ(summary[0].done, 42u);
  EXPECT_EQ(summary[0].done_by_status.at("ok"), 42u - ray - thrown);
  EXPECT_EQ(summary[0].done_by_status.at("exception"), thrown);
  for (const auto& [name, count] : summary[0].done_by_status) {
    if (name == "ok") {
      EXPECT_EQ(summary[0].status_examples.count(name), 0u);
    } else {  // one message per failure status, from the evaluator
      EXPECT_THAT(summary[0].status_examples.at(name), HasSubstr("test evaluator: injected"));
    }
  }
  EXPECT_EQ(summary[0].axes.at(0).labels, (std::vector<std::string>{"cosine", "sine"}));
  EXPECT_EQ(summary[0].axes.at(2).values.back(), 4.0);
}

// An evaluator that returns one response too few on cells 3 and 8, and one too many on cell 5.
class MiscountingEvaluator final : public CellEvaluator {
 public:
  explicit MiscountingEvaluator(const CellEvaluator& inner) : inner_(inner) {}
  std::vector<ResponseInfo> Responses() const override { return inner_.Responses(); }
  std::vector<std::pair<std::int32_t, std::string>> StatusNames() const override {
    return inner_.StatusNames();
  }
  CellOutcome Evaluate(std::span<const std::size_t> index) const override {
    CellOutcome out = inner_.Evaluate(index);
    const std::uint64_t cell = static_cast<std::uint64_t>(out.responses.back());  // cell_echo
    if (cell == 3 || cell == 8) out.responses.pop_back();
    if (cell == 5) out.responses.push_back(1.0);
    return out;
  }

 private:
  const CellEvaluator& inner_;
};

TEST_F(SweepRunnerTest, ACellWithAnotherResponseCountIsAnInternalErrorNotPadded) {
  const SweepSpec spec = ParseSweepSpec(kSpec, "spec.toml", ".");
  const TestEvaluator evaluator(spec, 50, 0);
  const MiscountingEvaluator miscounting(evaluator);
  // The cells the test needs as ok cells of the test evaluator.
  for (const std::uint64_t c : {3u, 5u, 8u}) {
    ASSERT_FALSE(TestEvaluator::Throws(c) || TestEvaluator::Fails(c)) << c;
  }
  const SweepReport report = Run(spec, miscounting);
  EXPECT_TRUE(report.complete);
  EXPECT_EQ(report.failed_by_status.at("response-count"), 3u);
  std::vector<std::string> names;
  const CubeData data = h5::ReadCubeData(options_.out, "runner", &names);
  for (std::uint64_t c = 0; c < spec.CellCount(); ++c) {
    if (c != 3 && c != 5 && c != 8) {
      EXPECT_NE(data.status[c], kStatusResponseCount) << c;
      continue;
    }
    EXPECT_EQ(data.status[c], kStatusResponseCount) << c;
    for (std::size_t r = 0; r < data.responses.size(); ++r) {
      EXPECT_TRUE(std::isnan(data.responses[r][c])) << "cell " << c << " response " << r;
    }
  }
  const auto summary = h5::SummarizeCube(options_.out);
  ASSERT_EQ(summary.size(), 1u);
  EXPECT_EQ(summary[0].done_by_status.at("response-count"), 3u);
  // The lowest such cell's message.
  EXPECT_EQ(summary[0].status_examples.at("response-count"),
            "cell 3: internal error: the evaluator returned 2 responses for the 3 it declares");
}

TEST_F(SweepRunnerTest, InterruptedSweepResumesComputingOnlyMissingCells) {
  const SweepSpec spec = ParseSweepSpec(kSpec, "spec.toml", ".");
  const TestEvaluator evaluator(spec, 50, 0);
  volatile std::sig_atomic_t flag = 0;
  const StoppingEvaluator stopping(evaluator, 20, &flag);
  options_.stop = &flag;
  options_.checkpoint_cells = 6;
  const SweepReport first = Run(spec, stopping);
  EXPECT_TRUE(first.interrupted);
  EXPECT_FALSE(first.complete);
  EXPECT_EQ(first.cells_computed, 20u);
  ASSERT_TRUE(std::filesystem::exists(PartialPath(options_.out)));
  EXPECT_FALSE(std::filesystem::exists(options_.out));
  const CubeData partial = h5::ReadCubeData(PartialPath(options_.out), "runner", nullptr);
  std::uint64_t done_before = 0;
  for (std::uint8_t d : partial.done) {
    done_before += d;
  }
  EXPECT_EQ(done_before, 20u);  // the stop request checkpoints what was computed
  ExpectMatchesDirect(spec, partial, false);
  EXPECT_EQ(h5::SummarizeCube(PartialPath(options_.out))[0].complete, false);

  flag = 0;
  options_.resume = true;
  const SweepReport second = Run(spec, evaluator);
  EXPECT_TRUE(second.complete);
  EXPECT_EQ(second.run, 2);
  EXPECT_EQ(second.cells_computed, 42u - done_before);
  const CubeData final_data = h5::ReadCubeData(options_.out, "runner", nullptr);
  ExpectMatchesDirect(spec, final_data, true);
  for (std::uint64_t c = 0; c < 42; ++c) {
    EXPECT_EQ(final_data.run[c], partial.done[c] ? 1 : 2) << "cell " << c;
  }
  // Resuming a complete cube has nothing to do.
  const SweepReport third = Run(spec, evaluator);
  EXPECT_TRUE(third.already_complete);
}

// Checkpoints due after every cell are written after every cell when they may take all of
// rank 0's time (share 1), and deferred when they may take only a thousandth of it (a
// checkpoint of at least tens of microseconds, two fsyncs, then defers the next by tens of
// milliseconds or more, longer than the 42 cells of 1 ms); the cube is the same.
TEST_F(SweepRunnerTest, CheckpointsTakeAtMostTheirShareOfRankZero) {
  const SweepSpec spec = ParseSweepSpec(kSpec, "spec.toml", ".");
  const TestEvaluator evaluator(spec, 50, 1.0);  // 1 ms per cell
  options_.max_chunk = 1;  // results stored cell by cell, each making a checkpoint due
  options_.checkpoint_cells = 1;
  options_.force = true;
  options_.checkpoint_share = 1.0;
  const SweepReport every = Run(spec, evaluator);
  EXPECT_TRUE(every.complete);
  EXPECT_EQ(every.checkpoints, 42u) << "one per cell";
  EXPECT_EQ(every.cells_checkpointed, 42u);
  options_.checkpoint_share = 1e-3;
  const SweepReport deferred = Run(spec, evaluator);
  EXPECT_TRUE(deferred.complete);
  EXPECT_LE(deferred.checkpoints, 2u);
  EXPECT_GE(deferred.checkpoints, 1u) << "the first is due after the first cell";
  ExpectMatchesDirect(spec, h5::ReadCubeData(options_.out, "runner", nullptr), true);
}

TEST_F(SweepRunnerTest, ResumeWithADifferentSpecificationIsRefused) {
  const SweepSpec spec = ParseSweepSpec(kSpec, "spec.toml", ".");
  const TestEvaluator evaluator(spec, 50, 0);
  volatile std::sig_atomic_t flag = 0;
  const StoppingEvaluator stopping(evaluator, 5, &flag);
  options_.stop = &flag;
  Run(spec, stopping);
  ASSERT_TRUE(std::filesystem::exists(PartialPath(options_.out)));
  std::string other_text = kSpec;
  other_text.replace(other_text.find("xi = 0.05"), 9, "xi = 0.02");
  const SweepSpec other = ParseSweepSpec(other_text, "other.toml", ".");
  options_.stop = nullptr;
  options_.resume = true;
  try {
    Run(other, evaluator);
    FAIL() << "resume with another specification was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("cube.h5.partial: cannot resume: other.toml: key fixed.xi "
                                    "differs from the specification the cube was computed "
                                    "with (cube: 0.05; now: 0.02)"));
  }
}

// The test evaluator of a newer program version: one response more, same specification hash.
class EvaluatorWithBand final : public CellEvaluator {
 public:
  explicit EvaluatorWithBand(const CellEvaluator& inner) : inner_(inner) {}
  std::vector<ResponseInfo> Responses() const override {
    std::vector<ResponseInfo> out = inner_.Responses();
    out.push_back({"band", "1", "a response the older version did not write"});
    return out;
  }
  std::vector<std::pair<std::int32_t, std::string>> StatusNames() const override {
    return inner_.StatusNames();
  }
  CellOutcome Evaluate(std::span<const std::size_t> index) const override {
    ++evaluations_;
    CellOutcome out = inner_.Evaluate(index);
    out.responses.push_back(0.0);
    return out;
  }
  int evaluations() const { return evaluations_; }

 private:
  const CellEvaluator& inner_;
  mutable int evaluations_ = 0;
};

std::string FileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST_F(SweepRunnerTest, ResumeOfACheckpointWithoutAnEvaluatorResponseIsRefusedUntouched) {
  const SweepSpec spec = ParseSweepSpec(kSpec, "spec.toml", ".");
  const TestEvaluator older(spec, 1, 0);
  volatile std::sig_atomic_t flag = 0;
  const StoppingEvaluator stopping(older, 5, &flag);
  options_.stop = &flag;
  Run(spec, stopping);
  const std::filesystem::path partial = PartialPath(options_.out);
  ASSERT_TRUE(std::filesystem::exists(partial));
  const std::string before = FileBytes(partial);

  const EvaluatorWithBand newer(older);
  options_.stop = nullptr;
  options_.resume = true;
  try {
    Run(spec, newer);
    FAIL() << "a checkpoint without responses/band was resumed";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(partial.string() + ": cannot resume: it has no dataset "
                                                       "sweeps/runner/responses/band"));
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line";
  }
  EXPECT_EQ(newer.evaluations(), 0) << "cells evaluated before the refusal";
  EXPECT_FALSE(std::filesystem::exists(options_.out));
  EXPECT_TRUE(FileBytes(partial) == before) << "the refused checkpoint was modified";

  // The same checkpoint still resumes with the evaluator that wrote it.
  EXPECT_TRUE(Run(spec, older).complete);
}

TEST_F(SweepRunnerTest, ExistingOutputIsRefusedWithoutResumeOrForce) {
  const SweepSpec spec = ParseSweepSpec(kSpec, "spec.toml", ".");
  const TestEvaluator evaluator(spec, 1, 0);
  Run(spec, evaluator);
  EXPECT_THROW(
      {
        try {
          Run(spec, evaluator);
        } catch (const InputError& e) {
          EXPECT_THAT(e.what(), HasSubstr("cube.h5: already exists; use --resume"));
          throw;
        }
      },
      InputError);
  options_.force = true;
  EXPECT_TRUE(Run(spec, evaluator).complete);
}

TEST_F(SweepRunnerTest, UnknownRequestedResponseIsRefusedBeforeAnyWork) {
  std::string text = kSpec;
  text.replace(text.find("family"), 6, "responses = [\"x_peak\", \"y_peak\"]\nfamily");
  const SweepSpec spec = ParseSweepSpec(text, "spec.toml", ".");
  const TestEvaluator evaluator(spec, 1, 0);
  try {
    Run(spec, evaluator);
    FAIL() << "unknown response accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("sweep.responses: unknown response 'y_peak'; allowed: "
                                    "x_peak, theta_peak, cell_echo"));
  }
  EXPECT_FALSE(std::filesystem::exists(PartialPath(options_.out)));
}

TEST_F(SweepRunnerTest, RequestedResponsesAreStoredInTheirOrder) {
  std::string text = kSpec;
  text.replace(text.find("family"), 6, "responses = [\"cell_echo\", \"x_peak\"]\nfamily");
  const SweepSpec spec = ParseSweepSpec(text, "spec.toml", ".");
  const TestEvaluator evaluator(spec, 1, 0);
  ASSERT_TRUE(Run(spec, evaluator).complete);
  std::vector<std::string> names;
  const CubeData data = h5::ReadCubeData(options_.out, "runner", &names);
  EXPECT_EQ(names, (std::vector<std::string>{"cell_echo", "x_peak"}));
  for (std::uint64_t c = 0; c < 42; ++c) {
    if (!TestEvaluator::Throws(c)) {
      EXPECT_EQ(data.responses[0][c], static_cast<double>(c));
    }
  }
}

// A checkpoint writes runs of consecutive cells as boxes of the N-D datasets: every listed
// cell, and no other, reaches the file, whatever the runs cross (rows, planes, short gaps).
TEST(CheckpointFile, WritesExactlyTheListedCellsInRunsAndAlone) {
  const SweepSpec spec = ParseSweepSpec(R"(
[sweep]
name = "boxes"
family = "subsystem"
[axes]
pulse = ["cosine", "sine"]
a_deg = {linspace = [0, 60, 5]}
Pi_delta = [0.5, 1.0, 2.0]
w0_over_wg = {linspace = [0.2, 4.0, 7]}
)",
                                        "spec.toml", ".");
  const TestEvaluator evaluator(spec, 0, 0);
  const CubeLayout layout = MakeCubeLayout(evaluator, {}, "spec.toml");
  const std::uint64_t cells = spec.CellCount();  // 2 * 5 * 3 * 7 = 210
  CubeData data;
  data.Reset(cells, layout.responses.size());
  for (std::uint64_t c = 0; c < cells; ++c) {
    data.Store(c, static_cast<std::int32_t>(c % 3), {0.5 * static_cast<double>(c), 1.0, 2.0},
               CellStats{static_cast<std::int64_t>(c), 7, 0.0}, 1);
  }
  // A run inside one row, runs across rows, planes and the whole first block, single cells
  // and runs shorter than a box, all in one call.
  std::vector<std::uint64_t> listed;
  for (std::uint64_t c = 2; c < 6; ++c) listed.push_back(c);      // short run
  for (std::uint64_t c = 9; c < 12; ++c) listed.push_back(c);     // short run
  listed.push_back(20);                                           // alone
  for (std::uint64_t c = 23; c < 131; ++c) listed.push_back(c);   // rows and planes
  for (std::uint64_t c = 140; c < 149; ++c) listed.push_back(c);  // one row and a bit
  for (std::uint64_t c = 150; c < 210; ++c) listed.push_back(c);  // to the end
  const auto dir = std::filesystem::temp_directory_path() / "sb_checkpoint_boxes";
  std::filesystem::create_directories(dir);
  const auto path = dir / "boxes.h5.partial";
  {
    h5::CheckpointFile file = h5::CheckpointFile::Create(path, spec, layout);
    for (std::uint64_t c : listed) data.done[c] = 1;
    file.Write(data, listed);
    file.Close();
  }
  const CubeData back = h5::ReadCubeData(path, "boxes", nullptr);
  std::vector<bool> is_listed(cells, false);
  for (std::uint64_t c : listed) is_listed[c] = true;
  for (std::uint64_t c = 0; c < cells; ++c) {
    if (is_listed[c]) {
      EXPECT_EQ(back.done[c], 1) << c;
      EXPECT_EQ(back.responses[0][c], 0.5 * static_cast<double>(c)) << c;
      EXPECT_EQ(back.status[c], static_cast<std::int32_t>(c % 3)) << c;
      EXPECT_EQ(back.events[c], static_cast<std::int64_t>(c)) << c;
    } else {
      EXPECT_EQ(back.done[c], 0) << c;
      EXPECT_TRUE(std::isnan(back.responses[0][c])) << c;
      EXPECT_EQ(back.status[c], kStatusNotDone) << c;
    }
  }
  std::filesystem::remove_all(dir);
}

// The final cube's chunks filtered outside HDF5 (FilterFinalChunk, as the idle ranks do) and
// written as stored bytes are, chunk for chunk, the bytes HDF5's own shuffle + deflate +
// Fletcher-32 pipeline stores (edge chunks with their fill included), and they read back
// through the checksum; a chunk whose deflate stream changed under its checksum fails the read.
TEST(FinalCube, FarmedChunksAreTheBytesHdf5StoresAndTheirChecksumsVerify) {
  const SweepSpec spec = ParseSweepSpec(R"(
[sweep]
name = "farm"
family = "subsystem"
[axes]
pulse = ["cosine", "sine"]
a_deg = {linspace = [0, 60, 11]}
w0_over_wg = {linspace = [0.2, 4.0, 1000]}
)",
                                        "spec.toml", ".");
  const TestEvaluator evaluator(spec, 0, 0);
  const CubeLayout layout = MakeCubeLayout(evaluator, {}, "spec.toml");
  const std::uint64_t cells = spec.CellCount();  // 2 x 11 x 1000: chunks of 8 rows, an edge of 3
  CubeData data;
  data.Reset(cells, layout.responses.size());
  for (std::uint64_t c = 0; c < cells; ++c) {
    if (c % 7 == 3 || TestEvaluator::Throws(c)) continue;  // not done: fill values stay
    const CellOutcome o = evaluator.Evaluate(spec.AxisIndex(c));
    data.Store(c, o.status, o.responses,
               CellStats{o.stats.events, o.stats.steps, 1e-6 * static_cast<double>(c)}, 2);
    data.done[c] = 1;
  }
  const auto dir = std::filesystem::temp_directory_path() / "sb_final_farm";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::size_t jobs = 0;
  const h5::ChunkFarm local = [&](std::size_t count, const auto& job, const auto& done) {
    for (std::size_t i = 0; i < count; ++i, ++jobs) {
      const std::vector<char> stored = h5::RunChunkJob(job(i));
      done(i, stored);
    }
  };
  h5::WriteFinalCube(dir / "hdf5.h5", spec, layout, data, 2, "2026-01-01T00:00:00Z");
  h5::WriteFinalCube(dir / "farm.h5", spec, layout, data, 2, "2026-01-01T00:00:00Z", {}, nullptr,
                     &local);
  std::vector<std::string> names;
  const CubeData back = h5::ReadCubeData(dir / "farm.h5", "farm", &names);  // checksums on
  std::vector<std::string> datasets = {"status",       "done",        "stats/run",
                                       "stats/events", "stats/steps", "stats/wall_s"};
  for (const std::string& r : names) datasets.push_back("responses/" + r);
  EXPECT_EQ(jobs, datasets.size() * 2 * 2) << "2 x 2 chunks per dataset";
  for (const std::string& name : datasets) {
    const auto ours = h5::ReadStoredChunks(dir / "farm.h5", "farm", name);
    const auto theirs = h5::ReadStoredChunks(dir / "hdf5.h5", "farm", name);
    ASSERT_EQ(ours.size(), 4u) << name;
    EXPECT_TRUE(ours == theirs) << name << ": stored bytes differ from HDF5's pipeline";
  }
  for (std::size_t r = 0; r < names.size(); ++r) {
    EXPECT_EQ(std::memcmp(back.responses[r].data(), data.responses[r].data(), cells * 8), 0);
  }
  EXPECT_EQ(std::memcmp(back.status.data(), data.status.data(), cells * 4), 0);
  EXPECT_EQ(std::memcmp(back.done.data(), data.done.data(), cells), 0);
  EXPECT_EQ(std::memcmp(back.wall_s.data(), data.wall_s.data(), cells * 8), 0);

  // One byte of a deflate stream changed after its checksum was computed: the read must fail.
  const h5::ChunkFarm damaging = [&](std::size_t count, const auto& job, const auto& done) {
    for (std::size_t i = 0; i < count; ++i) {
      std::vector<char> stored = h5::RunChunkJob(job(i));
      if (i == 0) stored[stored.size() / 2] ^= 0x10;
      done(i, stored);
    }
  };
  h5::WriteFinalCube(dir / "bad.h5", spec, layout, data, 2, "2026-01-01T00:00:00Z", {}, nullptr,
                     &damaging);
  try {
    (void)h5::ReadCubeData(dir / "bad.h5", "farm", nullptr);
    ADD_FAILURE() << "a damaged chunk was read";
  } catch (const h5::H5Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("checksum"));
  }
  std::filesystem::remove_all(dir);
}

// A claim runs on to the first multiple of the block at or after begin + count, cut at the end.
TEST(InProcessClaims, ClaimsRunOnToTheBlockEnd) {
  auto transport = MakeInProcessTransport();
  PendingCells pending;
  for (std::uint64_t c = 0; c < 1000; ++c) pending.Append(c);
  transport->BroadcastPending(pending);
  using Range = std::pair<std::uint64_t, std::uint64_t>;
  EXPECT_EQ(transport->Claim(1, 1), Range(0, 1));
  EXPECT_EQ(transport->Claim(5, 300), Range(1, 300));
  EXPECT_EQ(transport->Claim(300, 300), Range(300, 600));
  EXPECT_EQ(transport->Claim(301, 300), Range(600, 1000));
  EXPECT_EQ(transport->Claim(1, 300), Range(1000, 1000));
  EXPECT_EQ(BlockEnd(0, 300), 0u);
  EXPECT_EQ(BlockEnd(301, 300), 600u);
  EXPECT_EQ(BlockEnd(7, 1), 7u);
}

// The pending list as runs answers every position like the plain list of cells it replaces,
// and travels as (first cell, length) pairs.
TEST(PendingCells, RunsGiveTheCellOfEveryPositionAndSurviveTheirFlatForm) {
  std::vector<std::uint64_t> plain;
  for (std::uint64_t c = 0; c < 5000; ++c) {
    if (testing::Mix(c) % 7 != 0 || c % 100 < 40) plain.push_back(c);  // gaps, and long runs
  }
  PendingCells runs;
  for (std::uint64_t c : plain) runs.Append(c);
  ASSERT_EQ(runs.size(), plain.size());
  EXPECT_LT(runs.Runs(), plain.size() / 3);
  const PendingCells copy = PendingCells::FromFlat(runs.Flatten());
  for (std::uint64_t pos = 0; pos < plain.size(); ++pos) {
    ASSERT_EQ(runs[pos], plain[pos]) << pos;
    ASSERT_EQ(copy[pos], plain[pos]) << pos;
  }
  EXPECT_EQ(copy.Runs(), runs.Runs());
  PendingCells fresh;
  for (std::uint64_t c = 0; c < 1000000; ++c) fresh.Append(c);
  EXPECT_EQ(fresh.Runs(), 1U);  // a fresh sweep: 16 bytes for any number of cells
  EXPECT_EQ(fresh[999999], 999999U);
  EXPECT_THROW(PendingCells::FromFlat({5, 2, 6, 1}), std::runtime_error);  // overlapping runs
  EXPECT_THROW(PendingCells::FromFlat({5}), std::runtime_error);
}

TEST(ResultBatches, PackAndUnpackRoundTripColumnsAndFailureNotes) {
  ResultBatch in;
  in.Reset(40, 43, 2);
  in.status = {0, 1, kStatusException};
  in.events = {3, 4, 5};
  in.steps = {400, 500, 600};
  in.wall_s = {0.25, 0.5, 0.75};
  in.values = {1.5, -2.0, 3.0, 4.0, -5.5, 6.0};  // response-major: [r * 3 + i]
  in.failures = {{1, 1, 41, "ray"}, {kStatusException, 1, 123456789012ULL, "boom"}};
  const std::vector<char> bytes = PackBatch(in);
  const BatchView out = UnpackBatch(bytes);
  EXPECT_EQ(out.begin, 40u);
  EXPECT_EQ(out.end, 43u);
  EXPECT_EQ(out.responses, 2u);
  for (std::size_t i = 0; i < 3; ++i) {
    std::int32_t status = 0;
    std::int64_t steps = 0;
    std::memcpy(&status, out.status + 4 * i, 4);
    std::memcpy(&steps, out.steps + 8 * i, 8);
    EXPECT_EQ(status, in.status[i]);
    EXPECT_EQ(steps, in.steps[i]);
  }
  for (std::size_t k = 0; k < 6; ++k) {
    double v = 0.0;
    std::memcpy(&v, out.values + 8 * k, 8);
    EXPECT_TRUE(SameBits(v, in.values[k])) << k;
  }
  ASSERT_EQ(out.failures.size(), 2u);
  EXPECT_EQ(out.failures[1].lowest_cell, 123456789012ULL);
  EXPECT_EQ(out.failures[0].text, "ray");
  EXPECT_THROW(UnpackBatch(std::span<const char>(bytes.data(), bytes.size() - 3)),
               std::runtime_error);
  std::vector<char> foreign = bytes;
  foreign[0] ^= 1;
  EXPECT_THROW(UnpackBatch(foreign), std::runtime_error);
}

TEST(ResultBatches, TruncateKeepsTheFirstCellsOfEveryResponse) {
  ResultBatch b;
  b.Reset(0, 4, 2);
  b.values = {0, 1, 2, 3, 10, 11, 12, 13};
  b.Truncate(2);
  EXPECT_EQ(b.Size(), 2u);
  EXPECT_EQ(b.values, (std::vector<double>{0, 1, 10, 11}));
  EXPECT_EQ(b.status.size(), 2u);
}

}  // namespace
}  // namespace skewbridge::jobs::sweep_runner_test
