#pragma once
/// @file
/// The responses an evaluator stores, each beside the rule that reads its value from what a
/// cell computed: one table gives both the names (CellEvaluator::Responses) and the values
/// (CellOutcome::responses), in one order, so that the two cannot drift apart (a name added
/// without its value, or a value pushed in the wrong place). A cell's values are the table's
/// rows read in order, so their count is the table's size whatever the cell's status.

#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "spectra/cell.h"

namespace skewbridge::spectra {

/// The responses of an evaluator, read from a `Cell` (the evaluator's own view of what one
/// cell computed: its run, its inputs, its derived values).
template <typename Cell>
class ResponseTable {
 public:
  /// Reads one response's value from a cell.
  using Read = std::function<double(const Cell&)>;

  /// Appends a response of the solver run: NaN when the cell failed (its maxima, counts,
  /// margins).
  void Add(ResponseInfo info, Read read) { Append(std::move(info), std::move(read), true); }
  /// Appends a response stored whatever the cell's status (its excitation's scales, gaps,
  /// record measures: what it was given, not what it computed).
  void AddAlways(ResponseInfo info, Read read) { Append(std::move(info), std::move(read), false); }

  /// The responses, in the order of the values.
  const std::vector<ResponseInfo>& Infos() const { return infos_; }
  /// The number of responses.
  std::size_t size() const { return infos_.size(); }

  /// One value per response, in order: read(cell), or NaN for a response of the run when the
  /// cell failed (`run_ok` false; its rule is then not called).
  std::vector<double> Values(const Cell& cell, bool run_ok) const {
    std::vector<double> values;
    values.reserve(rows_.size());
    for (const Row& row : rows_) {
      values.push_back(run_ok || !row.nan_when_failed ? row.read(cell)
                                                      : std::numeric_limits<double>::quiet_NaN());
    }
    return values;
  }

 private:
  struct Row {
    Read read;
    bool nan_when_failed = true;
  };
  void Append(ResponseInfo info, Read read, bool nan_when_failed) {
    infos_.push_back(std::move(info));
    rows_.push_back({std::move(read), nan_when_failed});
  }
  std::vector<ResponseInfo> infos_;
  std::vector<Row> rows_;
};

}  // namespace skewbridge::spectra
