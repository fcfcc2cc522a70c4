#pragma once
/// @file
/// `skewbridge sweep --dry-run SPEC`: what a sweep would compute and about how long it would
/// take, without writing anything: the grid and its cell count, the records and their scale
/// factors, and a time estimate extrapolated from a few cells computed here.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "jobs/cell.h"
#include "jobs/sweep_spec.h"

namespace skewbridge::jobs {

/// The cells a dry run times: `count` linear indices (sorted, distinct) spread over the grid,
/// one drawn at random (seeded, so the same specification gives the same sample) from each of
/// `count` equal slices of the row-major cell list, so that every part of the grid is
/// represented and no regular stride can alias with an axis. All cells when count >= cells.
/// @pre cells >= 1
std::vector<std::uint64_t> SampleCells(std::uint64_t cells, std::size_t count, std::uint64_t seed);

/// The time estimate of a dry run, from the sampled cells' times.
struct DryRunEstimate {
  std::uint64_t cells = 0;      ///< Cells of the grid.
  std::size_t sampled = 0;      ///< Cells timed.
  double mean_s = 0.0;          ///< Mean time of a sampled cell [s].
  double min_s = 0.0;           ///< Shortest sampled cell [s].
  double max_s = 0.0;           ///< Longest sampled cell [s].
  double standard_error_s = 0;  ///< Standard error of mean_s (0 with one sample) [s].
  int ranks = 1;                ///< Ranks of the run estimated.
  int computing_ranks = 1;      ///< Ranks that compute cells (rank 0 too up to 64 ranks).
  double setup_s = 0.0;         ///< Evaluator set-up measured here (models, records) [s].
  double total_s = 0.0;         ///< setup_s + cells mean_s / computing_ranks [s].
  double low_s = 0.0;           ///< total_s with mean_s - 2 standard errors (at least min_s).
  double high_s = 0.0;          ///< total_s with mean_s + 2 standard errors.
};

/// Extrapolates the sampled times (seconds per cell) to the whole grid on `ranks` ranks: the
/// cells are shared evenly by the computing ranks (every rank up to
/// `root_computes_up_to_ranks`, all but rank 0 above), each taking the sample's mean.
/// @pre !times_s.empty(), ranks >= 1
DryRunEstimate EstimateSweepTime(std::uint64_t cells, const std::vector<double>& times_s, int ranks,
                                 int root_computes_up_to_ranks, double setup_s);

/// Records up to which the dry run prints the full record x stripe table of scale factors
/// (above it, the per-stripe summary only, unless asked for the table).
inline constexpr std::size_t kScaleTableRecords = 20;

/// The scale factors of a sweep whose records are scaled to stripes ([records] scale_to), as
/// `sweep --dry-run` prints them, from CellEvaluator::Scaling of every cell (no run): for each
/// group of cells whose records have the same own measures (one group per T1 when another
/// axis changes it), one line per stripe with the minimum, median and maximum factor over the
/// records and how many exceed max_scale; then, with `full_table` or up to kScaleTableRecords
/// records, a table of every record (rows: its label and own measure) by every stripe
/// (columns: its factor, '*' beyond max_scale); and the count of cells beyond max_scale.
/// Empty when the evaluator scales no record.
std::string ScaleFactorReport(const SweepSpec& spec, const CellEvaluator& evaluator,
                              bool full_table);

/// Runs the dry run of `spec` with its evaluator: times `sample_cells` cells (SampleCells,
/// seeded by the specification's hash) and returns the text printed by `sweep --dry-run`
/// (grid, fixed values, records, their scale factors (ScaleFactorReport, the full table with
/// `full_scale_table`), responses, the sampled cells and the estimate on `ranks` ranks with how
/// it was made). Writes no file.
/// @pre ranks >= 1, sample_cells >= 1
std::string DryRunReport(const SweepSpec& spec, const CellEvaluator& evaluator, int ranks,
                         std::size_t sample_cells, int root_computes_up_to_ranks, double setup_s,
                         bool full_scale_table = false);

}  // namespace skewbridge::jobs
