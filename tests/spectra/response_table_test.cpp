// The responses of an evaluator as one table (spectra/response_table.h): names and values in one
// order, a failed cell's run values NaN without calling their rules, its input values kept; and
// the check every cell's count passes (spectra/cell.h, CheckResponseCount).

#include "spectra/response_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace skewbridge::spectra::response_table_test {
namespace {

struct Cell {
  double x_m = 0.0;
  double gap_m = 0.0;
  mutable int reads_of_x = 0;
};

ResponseTable<Cell> Table() {
  ResponseTable<Cell> t;
  t.Add({"x_m", "m", "maximum |x|"}, [](const Cell& c) {
    ++c.reads_of_x;
    return c.x_m;
  });
  t.AddAlways({"delta", "m", "the gap"}, [](const Cell& c) { return c.gap_m; });
  t.Add({"x_over_delta", "1", "x_m / delta"}, [](const Cell& c) { return c.x_m / c.gap_m; });
  return t;
}

TEST(ResponseTable, NamesAndValuesComeInOneOrder) {
  const ResponseTable<Cell> t = Table();
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t.Infos()[0].name, "x_m");
  EXPECT_EQ(t.Infos()[1].name, "delta");
  EXPECT_EQ(t.Infos()[2].name, "x_over_delta");
  EXPECT_EQ(t.Infos()[2].unit, "1");
  const Cell cell{0.3, 0.1};
  const std::vector<double> v = t.Values(cell, true);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0], 0.3);
  EXPECT_EQ(v[1], 0.1);
  EXPECT_EQ(v[2], 0.3 / 0.1);
}

TEST(ResponseTable, AFailedCellHasEveryValueTheRunsOnesNaN) {
  const ResponseTable<Cell> t = Table();
  const Cell cell{0.3, 0.1};
  const std::vector<double> v = t.Values(cell, false);
  ASSERT_EQ(v.size(), t.size());
  EXPECT_TRUE(std::isnan(v[0]));
  EXPECT_EQ(v[1], 0.1);  // what the cell was given
  EXPECT_TRUE(std::isnan(v[2]));
  EXPECT_EQ(cell.reads_of_x, 0);  // a failed run's values are not read
}

TEST(ResponseCount, AnotherCountBecomesAnInternalErrorWithoutValues) {
  CellOutcome ok;
  ok.responses = {1.0, 2.0, 3.0};
  EXPECT_TRUE(CheckResponseCount(ok, 3));
  EXPECT_EQ(ok.status, kStatusOk);
  EXPECT_EQ(ok.responses.size(), 3u);

  CellOutcome shorter;
  shorter.responses = {1.0, 2.0};
  EXPECT_FALSE(CheckResponseCount(shorter, 3));
  EXPECT_EQ(shorter.status, kStatusResponseCount);
  EXPECT_EQ(shorter.status_text,
            "internal error: the evaluator returned 2 responses for the 3 it declares");
  EXPECT_TRUE(shorter.responses.empty());

  // A failed cell is checked the same: its values are NaN, never missing.
  CellOutcome failed_longer;
  failed_longer.status = 1;
  failed_longer.status_text = "ray";
  failed_longer.responses = {1.0, 2.0, 3.0, 4.0};
  EXPECT_FALSE(CheckResponseCount(failed_longer, 3));
  EXPECT_EQ(failed_longer.status, kStatusResponseCount);
  EXPECT_EQ(failed_longer.status_text,
            "internal error: the evaluator returned 4 responses for the 3 it declares");

  // A decorator's check of an inner evaluator's error keeps the inner message.
  EXPECT_FALSE(CheckResponseCount(shorter, 5));
  EXPECT_EQ(shorter.status_text,
            "internal error: the evaluator returned 2 responses for the 3 it declares");
}

}  // namespace
}  // namespace skewbridge::spectra::response_table_test
