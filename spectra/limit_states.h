#pragma once
/// @file
/// Limit states of a sweep (docs/sweep-format.md, [limit_states]): each cell stores, after the
/// responses of its family, the engineering demand of every declared limit state and whether
/// the cell exceeded it (1) or not (0), NaN for a failed cell. The demands are taken from the
/// family's own responses, so the limit states work the same for every family that stores
/// what they need.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "spectra/cell.h"
#include "spectra/grid.h"
#include "spectra/response_table.h"

namespace skewbridge::spectra {

/// The response names of limit state `ls`: {demand, exceedance} = {"ls_<name>_demand",
/// "ls_<name>"}.
std::pair<std::string, std::string> LimitStateResponseNames(const LimitState& ls);

/// The unit of a limit state's demand ("1" for unseating, the seat demand ratio; "rad", "m", or
/// the response's unit).
std::string LimitStateDemandUnit(const LimitState& ls, std::span<const ResponseInfo> inner);

/// The words of a limit state kind, as [limit_states] keys name it: "unseating", "rotation",
/// "seat_displacement", "residual", "joint_closing", "response".
std::string LimitStateKindName(LimitStateKind kind);

/// Wraps the evaluator of a family and appends the limit states' demands and exceedances to
/// every cell's responses:
///  - unseating: demand max_i t_i / s_i, the corner travel t_i of deck i normal to its end line
///    (`travel_m_d<i>`, or `travel_m` in a single-deck family) over its seat width s_i; exceeded
///    when t_i > s_i for any deck (the stored margin_m[_d<i>] < 0 when the seats are the
///    sweep's own);
///  - rotation: max over the decks of theta_m[_d<i>] (rad), exceeded above the threshold;
///  - seat_displacement, residual: max over the decks of travel_m[_d<i>] or travel_end_m[_d<i>]
///    (m);
///  - joint_closing: the number of impacts, exceeded from 1 on;
///  - response: the response's value, exceeded above the threshold.
/// Immutable after construction, as the evaluator it wraps.
class LimitStateEvaluator final : public CellEvaluator {
 public:
  /// @throws InputError naming "limit_states.<key>" when the family does not store what a
  /// limit state needs (the corner travel, seat widths, a response of that name), or when the
  /// seat widths per support line do not match the decks.
  LimitStateEvaluator(std::unique_ptr<CellEvaluator> inner, const CellGrid& grid);

  std::vector<ResponseInfo> Responses() const override { return table_.Infos(); }
  std::vector<std::pair<std::int32_t, std::string>> StatusNames() const override {
    return inner_->StatusNames();
  }
  const std::vector<SweepRecord>* Records() const override { return inner_->Records(); }
  std::vector<std::string> Notes() const override { return inner_->Notes(); }
  std::vector<std::string> Warnings() const override { return inner_->Warnings(); }
  const RecordScaling* record_scaling() const override { return inner_->record_scaling(); }
  CellOutcome Evaluate(std::span<const std::size_t> axis_index) const override;
  std::uint64_t WorkBlock() const override { return inner_->WorkBlock(); }
  /// The cell with its record scaled by `factor` (RecordScaling::EvaluateScaled of the family),
  /// with the limit states appended: the responses of Evaluate.
  /// @pre record_scaling() != nullptr
  CellOutcome EvaluateScaled(std::span<const std::size_t> axis_index, double factor) const;

 private:
  // The columns of the inner responses one limit state reads.
  struct Plan {
    LimitState ls;
    std::vector<std::size_t> columns;  ///< per deck (or one)
    std::vector<std::size_t> margins;  ///< unseating with the sweep's seats: margin_m_d<i>
    std::vector<double> seats_m;       ///< unseating with given seats: per deck
  };
  // The demand of a limit state and whether it is exceeded (1 or 0; NaN with a NaN demand),
  // from the inner responses `v`.
  static std::pair<double, double> Assess(const Plan& plan, const std::vector<double>& v);
  // The inner outcome with every limit state's demand and exceedance appended.
  CellOutcome WithLimitStates(CellOutcome out) const;
  // The inner responses of one cell, as the table reads them.
  struct CellValues {
    const std::vector<double>& inner;
  };
  std::unique_ptr<CellEvaluator> inner_;
  std::vector<ResponseInfo> inner_responses_;
  std::vector<Plan> plans_;
  ResponseTable<CellValues> table_;  ///< the inner responses, then each limit state's two
};

}  // namespace skewbridge::spectra
