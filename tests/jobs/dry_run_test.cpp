#include "jobs/dry_run.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "tests/jobs/test_evaluator.h"

namespace skewbridge::jobs::dry_run_test {
namespace {

using ::testing::HasSubstr;
using testing::TestEvaluator;

const char* kSpec = R"(
[sweep]
name = "dry"
family = "subsystem"
[axes]
pulse = ["cosine", "sine"]
a_deg = [10, 30, 50]
w0_over_wg = {linspace = [0.2, 4.0, 7]}
[fixed]
eta0 = 1.5
)";

// Slice i of `count` equal slices of [0, cells): [floor(i cells / count), floor((i + 1) cells /
// count)), in integers (the grids here are far below overflow).
bool InSlice(std::uint64_t cell, std::size_t i, std::uint64_t cells, std::size_t count) {
  return cell >= i * cells / count && cell < (i + 1) * cells / count;
}

TEST(DryRun, SampleHasOneCellInEachEqualSliceOfTheGrid) {
  for (const std::uint64_t cells : {9ull, 42ull, 1000ull, 123457ull}) {
    for (const std::size_t count : {1u, 3u, 8u}) {
      const std::vector<std::uint64_t> sample = SampleCells(cells, count, 7);
      ASSERT_EQ(sample.size(), count);
      for (std::size_t i = 0; i < count; ++i) {
        EXPECT_TRUE(InSlice(sample[i], i, cells, count))
            << "cell " << sample[i] << " of " << cells << ", slice " << i << " of " << count;
      }
      EXPECT_EQ(std::set<std::uint64_t>(sample.begin(), sample.end()).size(), count);
    }
  }
}

TEST(DryRun, SampleIsEveryCellOfASmallGridAndRepeatsForTheSameSeed) {
  EXPECT_EQ(SampleCells(5, 8, 1), (std::vector<std::uint64_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(SampleCells(100000, 8, 3), SampleCells(100000, 8, 3));
  EXPECT_NE(SampleCells(100000, 8, 3), SampleCells(100000, 8, 4));
}

TEST(DryRun, EstimateIsTheMeanCellTimeOverTheComputingRanks) {
  // times 1, 2, 3, 6 s: mean 3 s, sample variance (4 + 1 + 0 + 9) / 3, standard error
  // sqrt(14 / 3 / 4) = sqrt(7 / 6) s
  const std::vector<double> t = {1.0, 2.0, 3.0, 6.0};
  const DryRunEstimate e = EstimateSweepTime(100, t, 4, 64, 0.5);
  EXPECT_EQ(e.computing_ranks, 4);
  EXPECT_DOUBLE_EQ(e.mean_s, 3.0);
  EXPECT_DOUBLE_EQ(e.min_s, 1.0);
  EXPECT_DOUBLE_EQ(e.max_s, 6.0);
  EXPECT_NEAR(e.standard_error_s, std::sqrt(7.0 / 6.0), 1e-15);
  EXPECT_DOUBLE_EQ(e.total_s, 0.5 + 100.0 / 4.0 * 3.0);
  EXPECT_NEAR(e.high_s, 0.5 + 25.0 * (3.0 + 2.0 * std::sqrt(7.0 / 6.0)), 1e-12);
  // mean - 2 SE = 0.84 s is below the shortest cell timed: the low end takes that, 1 s.
  EXPECT_DOUBLE_EQ(e.low_s, 0.5 + 25.0 * 1.0);
  EXPECT_NEAR(EstimateSweepTime(100, {2.0, 3.0, 4.0, 3.0, 3.0}, 4, 64, 0.0).low_s,
              25.0 * (3.0 - 2.0 * std::sqrt(0.5 / 5.0)), 1e-12);
  // Above root_computes_up_to_ranks rank 0 only gathers.
  EXPECT_EQ(EstimateSweepTime(100, t, 65, 64, 0.0).computing_ranks, 64);
  EXPECT_EQ(EstimateSweepTime(100, t, 64, 64, 0.0).computing_ranks, 64);
  // One sample: no standard error; the range is the estimate itself.
  const DryRunEstimate one = EstimateSweepTime(10, {2.0}, 1, 64, 0.0);
  EXPECT_DOUBLE_EQ(one.total_s, 20.0);
  EXPECT_DOUBLE_EQ(one.low_s, 20.0);
  EXPECT_DOUBLE_EQ(one.high_s, 20.0);
}

TEST(DryRun, ReportCountsTheCellsTimesTheSampleAndWritesNothing) {
  const SweepSpec spec = ParseSweepSpec(kSpec, "spec.toml", ".");
  const TestEvaluator evaluator(spec, 50, 0);
  const auto before = std::distance(std::filesystem::directory_iterator("."),
                                    std::filesystem::directory_iterator());
  const std::string text = DryRunReport(spec, evaluator, 3, 5, 64, 0.25);
  EXPECT_EQ(before, std::distance(std::filesystem::directory_iterator("."),
                                  std::filesystem::directory_iterator()));
  EXPECT_THAT(text, HasSubstr("cells: 42 = pulse 2 x a_deg 3 x w0_over_wg 7\n"));
  EXPECT_THAT(text, HasSubstr("  eta0           1.5\n"));
  EXPECT_THAT(text, HasSubstr("records: none\n"));
  EXPECT_THAT(text, HasSubstr("estimate on 3 rank(s): "));
  EXPECT_THAT(text, HasSubstr("/ 3 computing rank(s)"));
  std::size_t timed = 0;
  for (std::size_t at = text.find("\n  cell "); at != std::string::npos;
       at = text.find("\n  cell ", at + 1)) {
    ++timed;
  }
  EXPECT_EQ(timed, 5u);
}

// Records scaled to stripes as ModelFileEvaluator scales them: record r (0-based) has its own
// measure r + 1 g, so the factor of stripe s is s / (r + 1); no cell is run.
class StripeEvaluator final : public CellEvaluator, public RecordScaling {
 public:
  explicit StripeEvaluator(const SweepSpec& spec) : spec_(spec) {}
  std::vector<ResponseInfo> Responses() const override { return {{"x", "1", "unused"}}; }
  CellOutcome Evaluate(std::span<const std::size_t>) const override { return {}; }
  const RecordScaling* record_scaling() const override { return this; }
  double UnscaledIntensity(std::span<const std::size_t> index) const override {
    return static_cast<double>(index[0] + 1);
  }
  CellOutcome EvaluateScaled(std::span<const std::size_t>, double) const override { return {}; }
  std::optional<spectra::CellScaling> Scaling(std::span<const std::size_t> index) const override {
    spectra::CellScaling s;
    s.t1_s = 0.5;
    s.unscaled = static_cast<double>(index[0] + 1);
    s.target = spec_.axes[1].values[index[1]];
    s.factor = s.target / s.unscaled;
    s.too_far = s.factor > spec_.im.max_scale;
    return s;
  }

 private:
  const SweepSpec& spec_;
};

// A grid of `records` records (labels r0, r1, ...) by the stripes 1 and 2 g of Sa(T1).
SweepSpec StripeSpec(std::size_t records) {
  SweepSpec spec;
  spec.source = "spec.toml";
  spec.family = "model-file";
  spec.im.measure = "Sa";
  spec.im.at_t1 = true;
  spec.im.scale = true;
  spec.im.max_scale = 0.5;
  Axis record{"record", ParameterKind::kLabel, {}, {}, "all"};
  for (std::size_t r = 0; r < records; ++r) {
    record.labels.push_back(std::to_string(r));
    record.labels.back().insert(0, 1, 'r');  // "r" + ... trips GCC 12 -Wrestrict
  }
  spec.axes = {record, Axis{"im_g", ParameterKind::kNumber, {1.0, 2.0}, {}, "list"}};
  return spec;
}

TEST(DryRun, ScaleFactorsSummarisedPerStripeAndTabledOnlyWhenAskedAboveTwentyRecords) {
  // 25 records: factors 1/(r + 1) and 2/(r + 1); the medians are those of record 12 (1/13,
  // 2/13); beyond 0.5: record 0 at 1 g (1/2 is not beyond), records 0-2 at 2 g.
  const SweepSpec spec = StripeSpec(25);
  const StripeEvaluator evaluator(spec);
  const std::string summary = ScaleFactorReport(spec, evaluator, false);
  EXPECT_THAT(summary, HasSubstr("factor = im_g / the record's own Sa(T1, xi = 0.05) [g]; "
                                 "max_scale = 0.5\n"));
  EXPECT_THAT(summary, HasSubstr("T1 = 0.5 s: 25 record(s) x 2 stripe(s), 4 of 50 beyond"));
  EXPECT_THAT(summary, HasSubstr("             1       0.04    0.07692          1          "
                                 "1 of 25\n"));
  EXPECT_THAT(summary, HasSubstr("             2       0.08     0.1538          2          "
                                 "3 of 25\n"));
  EXPECT_THAT(summary, HasSubstr("the full table of the 25 records x 2 stripes: add "
                                 "--scale-table"));
  EXPECT_THAT(summary, HasSubstr("4 of 50 cells beyond max_scale = 0.5 (largest factor 2)\n"));
  EXPECT_THAT(summary, ::testing::Not(HasSubstr("r24")));
  const std::string table = ScaleFactorReport(spec, evaluator, true);
  EXPECT_THAT(table, HasSubstr("\n    r0               1         1*         2*\n"));
  EXPECT_THAT(table, HasSubstr("\n    r1               2       0.5          1*\n"));
  EXPECT_THAT(table, HasSubstr("\n    r24             25      0.04       0.08\n"));
  EXPECT_THAT(table, ::testing::Not(HasSubstr("--scale-table")));
  // Up to 20 records the table comes anyway; an evaluator without scaling prints nothing.
  const SweepSpec small = StripeSpec(20);
  EXPECT_THAT(ScaleFactorReport(small, StripeEvaluator(small), false), HasSubstr("\n    r19 "));
  EXPECT_EQ(ScaleFactorReport(small, TestEvaluator(small, 1, 0), false), "");
}

}  // namespace
}  // namespace skewbridge::jobs::dry_run_test
