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

namespace skewbridge::jobs {
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
    EXPECT_THAT(e.what(), HasSubstr("cube.h5.partial: cannot resume: it was written by a "
                                    "different sweep specification (hash " +
                                    spec.Hash()));
    EXPECT_THAT(e.what(), HasSubstr("other.toml has " + other.Hash()));
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

TEST(CellRecords, PackAndUnpackRoundTrip) {
  std::vector<CellRecord> in(2);
  in[0] = {7, 1, {3, 400, 0.25}, {1.5, -2.0}, "ray"};
  in[1] = {123456789012ULL, kStatusException, {0, 0, 0.0}, {}, ""};
  const std::vector<char> bytes = PackRecords(in, true);
  std::vector<CellRecord> out;
  EXPECT_TRUE(UnpackRecords(bytes, out));
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[1].cell, 123456789012ULL);
  EXPECT_EQ(out[0].values, in[0].values);
  EXPECT_EQ(out[0].stats.steps, 400);
  EXPECT_EQ(out[1].status, kStatusException);
  EXPECT_EQ(out[0].text, "ray");
  EXPECT_THROW(UnpackRecords(std::span<const char>(bytes.data(), bytes.size() - 3), out),
               std::runtime_error);
}

}  // namespace
}  // namespace skewbridge::jobs
