#pragma once
/// @file
/// The "multi-span" sweep family (docs/sweep-format.md, docs/multispan.md): N identical skew
/// spans in a row between two abutments (model::BuildMultiSpanBridge), every gap (both abutments,
/// every joint) delta = Pi_delta a_g / w_g^2, each deck on its own bearings (w0 along x and y,
/// W0 in torsion, damping ratio xi), under a one-cycle pulse along x. The number of spans is a
/// parameter (`spans`, an axis or fixed). Responses are stored per deck with a suffix _d<i>
/// for i up to the largest span count of the sweep; a cell with fewer spans stores NaN for the
/// decks it does not have (docs/hdf5-layout.md, multi-span responses). With limit states each
/// deck also stores its rotation in rad and its corner travels (the exact largest travel the
/// integrator tracks, model::CornerTravelAt at the end, model::CornerTravelBound from the maxima),
/// which spectra::LimitStateEvaluator reads.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "solver/dynamics/run_result.h"
#include "solver/model/model.h"
#include "spectra/cell.h"
#include "spectra/grid.h"
#include "spectra/response_table.h"
#include "spectra/shared_runs.h"
#include "spectra/solver_status.h"

namespace skewbridge::spectra {

/// Evaluates the cells of a multi-span sweep. Evaluate is a pure function of the cell index:
/// cells that differ only in the seat width share one dynamic run (SharedRuns), so a cell's
/// responses are the bits its own run would give whatever the order of evaluation.
class MultiSpanEvaluator final : public CellEvaluator {
 public:
  /// Checks every cell's parameters before any work.
  /// @throws InputError naming the key for a parameter this family does not take (record,
  /// L_over_Le with delta_over_L, ...) or an impossible combination (eta0 with a = 0).
  explicit MultiSpanEvaluator(const CellGrid& spec);

  std::vector<ResponseInfo> Responses() const override { return table_.Infos(); }
  std::vector<std::pair<std::int32_t, std::string>> StatusNames() const override;
  CellOutcome Evaluate(std::span<const std::size_t> axis_index) const override;

 private:
  CellGrid spec_;
  int max_spans_ = 1;  ///< the largest span count over the cells: the number of deck suffixes
  /// The sweep declares limit states: theta_m, travel_m, travel_end_m (and margin_m with
  /// seat_over_L) are stored per deck.
  bool travel_ = false;
  /// What one cell computed, as its responses read it (multispan_evaluator.cpp).
  struct CellValues;
  ResponseTable<CellValues> table_;  ///< the stored responses, each with how it is read
  void MakeResponseTable();
  /// A cell's model and run, for the cells that differ from it only in the seat width.
  struct SeatRun {
    std::optional<model::Model> model;
    dynamics::RunResult run;
  };
  mutable SharedRuns<SeatRun> shared_;  ///< the last runs (spectra/shared_runs.h)
  /// The model and run of the cell at `axis_index` (its seat width enters neither).
  SeatRun RunOf(std::span<const std::size_t> axis_index) const;
};

}  // namespace skewbridge::spectra
