#pragma once
/// @file
/// The in-memory image of a sweep cube on the writing rank: one array per dataset, indexed by
/// the row-major linear cell index (docs/hdf5-layout.md).

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "jobs/cell.h"
#include "jobs/sweep_spec.h"

namespace skewbridge::jobs {

/// What a cube stores besides the axes: the responses and the table of status names.
struct CubeLayout {
  std::vector<ResponseInfo> responses;
  /// For each stored response, its position in CellEvaluator::Responses().
  std::vector<std::size_t> source_index;
  /// The number of CellEvaluator::Responses(): every outcome holds that many values.
  std::size_t evaluator_responses = 0;
  /// Every status code that may appear, with its name (reserved codes included).
  std::vector<std::pair<std::int32_t, std::string>> status_names;
  /// The integrators the cells run with: the cube stores each one's policy (SweepMethods).
  std::vector<model::Method> methods = {model::Method::kEventDriven};
  /// The policies the evaluator's runs use (CellEvaluator::policies): the cube stores, for each
  /// of `methods`, that one.
  dynamics::RunPolicies policies;
};

/// The layout for an evaluator: its responses (all, or those named in `requested`, in that
/// order) and the reserved (exception, not_done, response-count, ok) plus evaluator status
/// names.
/// @throws InputError("sweep.responses: unknown response ...") naming the allowed ones.
CubeLayout MakeCubeLayout(const CellEvaluator& evaluator, const std::vector<std::string>& requested,
                          const std::string& source);

/// The integrators a sweep's cells run with, each once: the labels of its `method` (axis or
/// fixed value), else the model file's run.method for the model-file family, else the
/// event-driven integrator.
/// @throws InputError for a method label or a model file the evaluator would refuse too.
std::vector<model::Method> SweepMethods(const SweepSpec& spec);

/// The per-cell arrays of a cube.
struct CubeData {
  std::vector<std::vector<double>> responses;  ///< [response][cell]; NaN when not computed.
  std::vector<std::int32_t> status;            ///< kStatusNotDone until computed.
  std::vector<std::uint8_t> done;              ///< 1 once the cell's data is in the file.
  std::vector<std::int32_t> run;               ///< The run (1, 2, ... on resume) that computed it.
  std::vector<std::int64_t> events;            ///< CellStats::events.
  std::vector<std::int64_t> steps;             ///< CellStats::steps.
  std::vector<double> wall_s;                  ///< CellStats::wall_s [s].

  /// Sizes every array for `cells` cells and `responses` responses, with the fill values.
  void Reset(std::uint64_t cells, std::size_t response_count);
  /// Number of cells.
  std::uint64_t Cells() const { return status.size(); }
  /// Stores one outcome, values already in layout order (missing values stay NaN).
  /// @pre cell < Cells()
  void Store(std::uint64_t cell, std::int32_t status_code, const std::vector<double>& values,
             const CellStats& stats, std::int32_t run_number);
};

}  // namespace skewbridge::jobs
