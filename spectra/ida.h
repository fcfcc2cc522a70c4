#pragma once
/// @file
/// Incremental dynamic analysis (IDA) of one cell [Vamvatsikos and Cornell 2002, EESD
/// 31:491-514]: the cell's record is scaled up through a sequence of intensities chosen by the
/// hunt-and-fill search [Vamvatsikos and Cornell 2004, Earthquake Spectra 20(2):523-553, §3],
/// and the capacity of each limit state is the lowest intensity at which it is exceeded. The
/// whole search is one cell of a sweep, run on one rank, so the sweep machinery (MPI, the
/// checkpoints, --resume, the inputs' checksums) is that of any sweep.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "spectra/cell.h"
#include "spectra/grid.h"
#include "spectra/limit_states.h"
#include "spectra/response_table.h"

namespace skewbridge::spectra {

/// What one run of the search returns: per limit state its demand and exceedance (0 or 1).
struct IdaPoint {
  bool ok = true;  ///< false: the run failed (status, text below)
  std::int32_t status = kStatusOk;
  std::string status_text;
  std::vector<double> demand;    ///< per limit state (its unit)
  std::vector<double> exceeded;  ///< per limit state: 0 or 1
};

/// The bracket of one limit state's capacity after the search.
struct IdaCapacity {
  /// The lowest intensity run at which the limit state is exceeded (g or m/s); +inf when no run
  /// up to ida.max_im exceeds it (the capacity is beyond the search).
  double im = 0.0;
  /// The highest intensity run below `im` at which it is not exceeded; 0 when none (the first
  /// run already exceeded it). For a demand increasing with the intensity the capacity lies in
  /// (below, im].
  double below = 0.0;
};

/// The trace of one record's IDA: its runs in the order they were made.
struct IdaTrace {
  std::vector<double> im;                     ///< per run: the intensity (g or m/s)
  std::vector<std::vector<double>> demand;    ///< [run][limit state]
  std::vector<std::vector<double>> exceeded;  ///< [run][limit state]: 0 or 1
  std::vector<IdaCapacity> capacity;          ///< per limit state, from every run
  std::int32_t status = kStatusOk;  ///< the first failed run's status (it ends the search)
  std::string status_text;          ///< its text
};

/// The capacity of each of `limit_states` limit states from the runs of `trace` (IdaCapacity).
std::vector<IdaCapacity> IdaCapacities(const IdaTrace& trace, std::size_t limit_states);

/// The hunt-and-fill search of one record [Vamvatsikos and Cornell 2004, §3]:
///  - hunt: runs at start, start + step, ... with the step growing by step_increase after each
///    run, until every limit state has been exceeded or the run at max_im is made;
///  - bracket and bisect: while a limit state's (below, im] is wider than tolerance, a run at
///    its middle (the widest bracket first);
///  - fill: otherwise a run halves the widest gap between consecutive intensities (0 included)
///    up to the highest capacity found, while a gap is wider than tolerance; a filling run
///    that exceeds a limit state below its capacity (a demand not monotone in the intensity)
///    lowers that capacity and opens its bracket, which is bisected again;
/// never more than max_runs runs. `run(im)` makes one run; a failed run ends the search.
/// @pre spec.enabled, limit_states >= 1
IdaTrace HuntAndFill(const IdaSpec& spec, std::size_t limit_states,
                     const std::function<IdaPoint(double)>& run);

/// The lognormal fragility of a set of capacities [Baker 2015, Earthquake Spectra 31(1):579-599,
/// eqs. 2-3]: with every capacity finite, theta = exp(mean ln IM_c) and beta = the standard
/// deviation of ln IM_c with n - 1; with some records censored (never reaching the limit state),
/// the maximum-likelihood theta and beta of right-censored lognormal data.
struct CapacityFit {
  double theta = 0.0;         ///< median capacity (g or m/s); NaN when not fitted
  double beta = 0.0;          ///< dispersion of ln IM_c; NaN when not fitted
  std::int64_t n = 0;         ///< finite capacities used
  std::int64_t censored = 0;  ///< records beyond the search (+inf capacity), censored in the fit
  std::string reason;         ///< "" or why theta and beta are NaN
  std::string note;           ///< "" or how censored records entered the fit
};

/// Fits CapacityFit to `capacities` (NaN entries are failed cells, skipped). A +inf capacity (a
/// record that never reaches the limit state) is right-censored at `censor_at` of the same
/// index (the highest intensity run, g or m/s; empty when none is censored). theta and beta
/// are NaN with the reason when fewer than 2 capacities are finite, or the censored likelihood
/// has no maximum (finite capacities all equal).
CapacityFit FitCapacities(std::span<const double> capacities,
                          std::span<const double> censor_at = {});

/// A sweep of IDA cells ([ida]): wraps the evaluator of the limit states (LimitStateEvaluator
/// over a model-file evaluator) and makes each cell one HuntAndFill over its record. Stores per
/// cell the record's own intensity, the runs made, per limit state the capacity (and the run
/// below it, the scale factor at it, and whether that exceeds [records] max_scale), and per run k <
/// max_runs its intensity, scale factor and each limit state's demand and exceedance (NaN past the
/// runs made).
class IdaEvaluator final : public CellEvaluator {
 public:
  /// @throws InputError when the inner evaluator lacks a limit state's responses.
  /// @pre inner->record_scaling() != nullptr (the sweep scales its records to an intensity)
  IdaEvaluator(std::unique_ptr<LimitStateEvaluator> inner, const CellGrid& grid);

  std::vector<ResponseInfo> Responses() const override { return table_.Infos(); }
  std::vector<std::pair<std::int32_t, std::string>> StatusNames() const override {
    return inner_->StatusNames();
  }
  const std::vector<SweepRecord>* Records() const override { return inner_->Records(); }
  std::vector<std::string> Notes() const override { return inner_->Notes(); }
  std::vector<std::string> Warnings() const override { return inner_->Warnings(); }
  const RecordScaling* record_scaling() const override { return inner_->record_scaling(); }
  CellOutcome Evaluate(std::span<const std::size_t> axis_index) const override;

 private:
  std::unique_ptr<LimitStateEvaluator> inner_;
  IdaSpec ida_;
  std::vector<LimitState> limit_states_;
  std::string im_unit_;
  double max_scale_ = 0.0;  ///< [records] max_scale (0: none)
  std::vector<std::string> demand_units_;
  std::vector<std::size_t> demand_columns_, exceeded_columns_;
  std::size_t inner_count_ = 0;  ///< the responses of the inner evaluator
  // One cell's search, as the table reads it: the record's own intensity and the runs.
  struct CellValues {
    double own = 0.0;
    const IdaTrace& trace;
  };
  ResponseTable<CellValues> table_;  ///< the stored responses, each with how it is read
};

}  // namespace skewbridge::spectra
