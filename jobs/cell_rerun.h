#pragma once
/// @file
/// One cell of a cube run again, as the sweep ran it: the sweep's specification read back from
/// the cube (its stored text, parsed against the folder it was read from), every input file
/// checked against the checksums the cube stores (a result never outlives its inputs), the cell
/// found by its coordinates or its index, and its model, scaled excitation and run control made
/// by the sweep's own evaluator (spectra::ModelFileEvaluator::MakeCell for the model-file family,
/// spectra::SpectraEvaluator::MakeRun for subsystem and pilot-bridge), so that a run of them
/// repeats the cell's maxima bit for bit (`skewbridge run --from-cube`, docs/run-output.md).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "jobs/sweep_spec.h"
#include "solver/common/excitation.h"
#include "spectra/cell.h"
#include "spectra/grid.h"
#include "spectra/model_file_evaluator.h"
#include "spectra/point.h"
#include "spectra/study.h"

namespace skewbridge::jobs {

/// Which cell of which sweep of a cube.
struct CellChoice {
  std::string sweep;                   ///< the sweep's name; empty: the cube's only sweep
  std::string coordinates;             ///< `--cell` text ("record=NIS090.AT2,im_g=0.6"), or ""
  std::optional<std::uint64_t> index;  ///< `--cell-index`: the row-major cell index
};

/// The row-major index of the cell that `text` names: comma-separated `axis=value` pairs, one
/// for every axis of more than one coordinate (an axis of one may be given or left out). A
/// number matches the axis coordinate it equals to 1e-9 relative (a linspace coordinate need
/// not be typed to its last digit); a label matches exactly.
/// @throws InputError at field "--cell" naming the axis and its allowed values: an unknown axis,
/// a value that is no coordinate of its axis, an axis given twice or left out, a pair without '='.
std::uint64_t CellIndexOf(const spectra::CellGrid& grid, std::string_view text);

/// "record=NIS090.AT2, im_g=0.6, ...": every axis of the grid with the cell's coordinate.
/// @pre cell < grid.CellCount()
std::string CellCoordinates(const spectra::CellGrid& grid, std::uint64_t cell);

/// A cube's cell made concrete again.
struct CellRerun {
  SweepSpec spec;  ///< the sweep's specification, parsed from the cube's stored text
  /// The sweep's evaluator (owns the records the cell's excitation was made from).
  std::unique_ptr<spectra::CellEvaluator> evaluator;
  std::optional<model::Model> model;  ///< the cell's model
  /// Its compliant abutments (a model file's law = "compliant"), else empty: the joint law.
  std::optional<model::CompliantAbutments> compliant;
  std::unique_ptr<Excitation> excitation;  ///< its ground motion, scaled as the cell scales it
  model::RunControl control;               ///< its run control (method, end time, tolerances)
  const spectra::SweepRecord* record = nullptr;  ///< its record, or nullptr for a pulse
  double scale = 1.0;                            ///< the factor on the record's accelerations
  /// The record at dynamics::kStripeTraceFactor when the sweep ran the cell as a stripe of its
  /// record (dynamics::RunScaledRecord at `scale`), else nullptr (dynamics::Run).
  std::unique_ptr<Excitation> trace_excitation;
  std::uint64_t index = 0;                  ///< the cell's row-major index
  std::string coordinates;                  ///< CellCoordinates of the cell
  bool done = false;                        ///< the cube holds the cell's results
  std::int32_t status = 0;                  ///< the cube's status code of the cell
  std::string status_name;                  ///< its name in the cube's status table
  std::vector<std::string> response_names;  ///< the cube's responses, in stored order
  std::vector<double> responses;            ///< the cell's stored values, in that order
  /// The model file's text (model-file family; the cell changes values), else "".
  std::string model_text;
};

/// Prepares the re-run of one cell of `cube`: reads the sweep, parses its stored specification
/// against the folder of its stored source path, checks that the specification and every input
/// file (model, record set, records) are the ones the cube was computed from, and makes the
/// cell's model, excitation and control.
/// @throws InputError naming the cube: not a cube, no such sweep (naming those it holds), several
/// sweeps and none chosen, the multi-span family, an [ida] sweep, a changed input
/// (DescribeIdentityChange), or a bad `--cell` / `--cell-index` (naming the axis and its
/// allowed values, or the cell count); InputError from the specification's parser.
CellRerun PrepareCellRerun(const std::filesystem::path& cube, const CellChoice& choice);

}  // namespace skewbridge::jobs
