#pragma once
/// @file
/// The physics behind a sweep: evaluates a cell of a "subsystem" or "pilot-bridge" sweep by
/// mapping its coordinates to a spectra::PointParameters, running the deck solver under the
/// cell's pulse or record, and returning the dimensional and dimensionless maxima, the unseating
/// margin with seat_over_L and the corner travels with limit states (docs/sweep-format.md lists
/// the responses).

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "records/measures.h"
#include "spectra/cell.h"
#include "spectra/grid.h"
#include "spectra/point.h"
#include "spectra/response_table.h"
#include "spectra/shared_runs.h"
#include "spectra/solver_status.h"
#include "spectra/study.h"

namespace skewbridge::spectra {

/// Evaluates the cells of a subsystem or pilot-bridge sweep. Evaluate is a pure function of the
/// cell index: cells that differ only in the seat width share one dynamic run (SharedRuns), so a
/// cell's responses are the bits its own run would give whatever the order of evaluation.
class SpectraEvaluator final : public CellEvaluator {
 public:
  /// Reads or synthesises the records (LoadSweepRecords, if any), then checks every cell's
  /// parameters before any work.
  /// @throws InputError naming the key for a family it cannot evaluate, a parameter this family
  /// does not take, a record label missing from the set, or an impossible combination (eta0 with
  /// a = 0, delta/L with Pi_delta = 0, ...).
  explicit SpectraEvaluator(const CellGrid& spec);

  std::vector<ResponseInfo> Responses() const override { return table_.Infos(); }
  std::vector<std::pair<std::int32_t, std::string>> StatusNames() const override;
  CellOutcome Evaluate(std::span<const std::size_t> axis_index) const override;
  const std::vector<SweepRecord>* Records() const override {
    return records_.empty() ? nullptr : &records_;
  }

  /// A cell's run as Evaluate makes it: the model, control and integrator (MakePointRun), the
  /// excitation (the record as read, or the pulse of PulseScales) and the record (nullptr for a
  /// pulse). @throws InputError as ToDimensional.
  struct CellRun {
    std::optional<PointRun> run;             ///< model, control, integrator
    std::unique_ptr<Excitation> excitation;  ///< the cell's ground motion
    const SweepRecord* record = nullptr;     ///< the cell's record, or nullptr
  };
  CellRun MakeRun(std::span<const std::size_t> axis_index) const;

  /// The point parameters of a cell, and the record it uses (nullptr for a pulse).
  spectra::PointParameters Parameters(std::span<const std::size_t> axis_index,
                                      const SweepRecord** record) const;

  /// The ground motion of a cell: the record as read (or the pulse of `scales`) along x, or,
  /// with incidence_deg, along that angle from the bridge's x axis.
  std::unique_ptr<Excitation> MakeExcitation(std::span<const std::size_t> axis_index,
                                             const spectra::PointParameters& p,
                                             const SweepRecord* record,
                                             const spectra::ExcitationScales& scales) const;

 private:
  CellGrid spec_;
  spectra::Family family_;
  std::vector<SweepRecord> records_;  ///< LoadSweepRecords(spec_), read once per rank
  std::vector<double> band_edges_;    ///< BandEdges(spec_), for the response band
  bool seats_ = false;                ///< seat_over_L is given: margin_m, margin_norm are stored
  bool travel_ = false;  ///< limit states declared: travel_m, travel_end_m, travel_bound_m stored
  /// What one cell computed, as its responses read it (spectra_evaluator.cpp).
  struct CellValues;
  ResponseTable<CellValues> table_;  ///< the stored responses, each with how it is read
  /// A cell's dimensional point and run, for the cells that differ from it only in the seat width.
  struct SeatRun {
    spectra::DimensionalPoint point;
    spectra::PointResult result;
  };
  mutable SharedRuns<SeatRun> shared_;  ///< the last runs (spectra/shared_runs.h)
  /// The point and run of a cell, without its seat width.
  SeatRun RunOf(std::span<const std::size_t> axis_index) const;
  /// The pieces of a single `record` that hold the acceleration peak at the event-driven
  /// policy's ramp horizon (records::FindPeakPieces), found on the first call for that record
  /// and kept, so that a cell's run reads those pieces instead of the whole record; nullptr for
  /// a pair.
  std::shared_ptr<const records::PeakPieces> RecordPeakPieces(const SweepRecord& record) const;
  /// Per record of records_, its RecordPeakPieces once found.
  RecordPeakCache peak_pieces_;
  /// Where a numeric parameter of a cell comes from, found once in spec_ as NumberOf finds it:
  /// an axis (its value at the cell's index), a fixed value, or neither (the caller's default).
  struct NumberSource {
    int axis = -1;       ///< the axis of the key, or -1
    bool fixed = false;  ///< no axis, a fixed value
    double value = 0.0;  ///< the fixed value
  };
  /// The source of `key` in spec_.
  NumberSource SourceOf(std::string_view key) const;
  /// NumberOf(spec_, index, key, fallback, given) for the key of `source`.
  double Number(const NumberSource& source, std::span<const std::size_t> index, double fallback,
                bool* given = nullptr) const {
    if (given != nullptr) *given = source.axis >= 0 || source.fixed;
    if (source.axis >= 0) {
      const auto k = static_cast<std::size_t>(source.axis);
      return spec_.axes[k].values[index[k]];
    }
    return source.fixed ? source.value : fallback;
  }
  /// Where a label parameter of a cell comes from, found once in spec_ as LabelOf finds it: an
  /// axis (its label at the cell's index), a fixed label, or neither (the empty label).
  struct LabelSource {
    int axis = -1;      ///< the axis of the key, or -1
    std::string label;  ///< the fixed label, or empty
  };
  /// The source of label `key` in spec_.
  LabelSource LabelSourceOf(std::string_view key) const;
  /// LabelOf(spec_, index, key) for the key of `source`, without copying it.
  const std::string& Label(const LabelSource& source, std::span<const std::size_t> index) const {
    if (source.axis >= 0) {
      const auto k = static_cast<std::size_t>(source.axis);
      return spec_.axes[k].labels[index[k]];
    }
    return source.label;
  }
  /// The direction of a cell's ground motion: incidence_deg from the bridge's x axis, or x.
  Eigen::Vector2d DirectionOf(std::span<const std::size_t> axis_index) const;
  /// The sources of the parameters Parameters and MakeExcitation read, one per key; `method`
  /// says whether spec_ names the method (else every cell is event-driven).
  struct Sources {
    NumberSource w0_over_wg, Pi_delta, a_deg, eta0, W_over_L, W0_over_w0, xi, eps_N, mu,
        delta_over_L, L_over_Le, a_g_g, incidence_deg;
    LabelSource pulse, record;
    bool method = false;
  } sources_;
};

}  // namespace skewbridge::spectra
