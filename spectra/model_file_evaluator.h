#pragma once
/// @file
/// The "model-file" sweep family (docs/sweep-format.md): a bridge given by a model file
/// (docs/model-format.md; one deck or several in a row), run as `skewbridge run` runs it, with
/// some of its values replaced cell by cell: the excitation (a record of the [records] set, or a
/// pulse of shape, a_g and w_g or T_g), a factor on the accelerations, the gaps (Pi_delta L_e of
/// the cell's excitation, or metres), eps_N, mu, the skew angle (the deck re-derived from the
/// file's L and W, or eta0), xi, and a factor on the substructure stiffness. Responses are stored
/// per deck with a suffix _d<i> (the decks of the file), then for the cell.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "records/excitations.h"
#include "records/incidence.h"
#include "records/measures.h"
#include "solver/common/excitation.h"
#include "solver/dynamics/abutment_springs.h"
#include "solver/dynamics/run_result.h"
#include "solver/dynamics/stripes.h"
#include "solver/model/model_file.h"
#include "spectra/cell.h"
#include "spectra/grid.h"
#include "spectra/response_table.h"
#include "spectra/shared_runs.h"
#include "spectra/solver_status.h"
#include "spectra/study.h"

namespace skewbridge::spectra {

/// One cell of a model-file sweep made concrete: what `skewbridge run` would be given.
struct ModelFileCell {
  std::optional<model::Model> model;  ///< the file's model with the cell's values
  /// The file's compliant abutments (law = "compliant"), else empty (dynamics::RunUnderLaw).
  std::optional<model::CompliantAbutments> compliant;
  std::unique_ptr<Excitation> excitation;  ///< the cell's ground motion
  model::RunControl control;               ///< the file's [run], with the cell's method
  double a_g_mps2 = 0.0;                   ///< amplitude: pulse a_g, or the record's PGA x scale
  double w_g_radps = 0.0;                  ///< pulse w_g, or 2 pi / T_m of the record
  double persistency_m = 0.0;              ///< L_e = a_g / w_g^2 (m)
  double gap_m = 0.0;                      ///< gap of the +x abutment (m, along x)
  std::vector<double> seat_width_m;        ///< per deck; empty without seat widths
  const SweepRecord* record = nullptr;     ///< the record of the cell, or nullptr
  double scale = 1.0;                      ///< factor on the accelerations
  double excitation_duration_s = 0.0;      ///< the ground motion's duration (s)
  std::size_t excitation_samples = 0;      ///< its samples (0 for a pulse)
};

/// A record as a model-file cell applies it: every acceleration times `factor` (left as read
/// when the factor is 1), linear between samples, along the unit (x, y) `direction`.
/// `skewbridge run --record` makes its excitation here too, so a run and a cell agree bit for bit.
records::SampledExcitation ScaledRecordExcitation(const records::GroundMotion& motion,
                                                  double factor, const Eigen::Vector2d& direction);

/// A pair of components as a cell applies it: both times `factor` (left as read when the factor
/// is 1), H1 along `incidence_deg` from the bridge's x axis and H2 at +90 deg
/// (records::PairExcitation). A pair (a, 0) gives the excitation of
/// ScaledRecordExcitation(a, factor, records::DirectionAt(incidence_deg)) sample for sample.
/// @throws InputError as records::PairExcitation.
records::SampledExcitation ScaledPairExcitation(const records::GroundMotion& h1,
                                                const records::GroundMotion& h2, double factor,
                                                double incidence_deg);

/// Evaluates the cells of a model-file sweep. Evaluate is a pure function of the cell index:
/// cells that differ only along an axis of the limit states alone (seat_over_L, seat_m: a seat
/// width moves no deck) share one dynamic run, the last ones kept, so a cell's responses are the
/// bits its own run would give whatever the order of evaluation. Scales its records to an
/// intensity when the sweep says so (RecordScaling, exposed by record_scaling).
class ModelFileEvaluator final : public CellEvaluator, public RecordScaling {
 public:
  /// Reads the model file and the records (LoadSweepRecords, if any), then builds every cell's
  /// model before any work.
  /// @throws InputError naming the spec file and key for a parameter this family does not take
  /// (spans, w0_over_wg, ...), a combination the model file cannot take (xi with a given damping
  /// matrix C, eta0 at a = 0, a pulse without a_g or w_g when the file's excitation is sampled),
  /// or a cell whose model is invalid (the model file's key named too); InputError from the
  /// model file, its excitation file or the record set.
  explicit ModelFileEvaluator(const CellGrid& spec);

  std::vector<ResponseInfo> Responses() const override { return table_.Infos(); }
  std::vector<std::pair<std::int32_t, std::string>> StatusNames() const override;
  CellOutcome Evaluate(std::span<const std::size_t> axis_index) const override;
  /// The cells from the first axis whose cells share a run or a trace (the stripe axis, a
  /// limit-only axis) to the last axis: the product of their sizes.
  std::uint64_t WorkBlock() const override { return work_block_; }
  const std::vector<SweepRecord>* Records() const override {
    return records_.empty() ? nullptr : &records_;
  }

  /// The model, excitation and run control of a cell (the excitation is made only when
  /// `with_excitation`, so that checking every cell does not copy records); `factor`, when
  /// given, replaces the cell's factor on the accelerations.
  /// @throws InputError naming the spec file and the key, as the constructor.
  ModelFileCell MakeCell(std::span<const std::size_t> axis_index, bool with_excitation,
                         std::optional<double> factor = std::nullopt) const;

  /// The cells scaled beyond [records] max_scale, as one line for the sweep's summary.
  std::vector<std::string> Notes() const override;
  /// The bridge's plausibility: every deck's mass per metre of span, the gaps (the file's, or
  /// the sweep's gap_m) and the seats of [limit_states] against the spans, and the fundamental
  /// period of every cell's model.
  std::vector<std::string> Warnings() const override { return warnings_; }
  /// This evaluator when the sweep scales its records to an intensity ([records] scale_to or
  /// im), else nullptr.
  const RecordScaling* record_scaling() const override {
    return record_im_.empty() ? nullptr : this;
  }
  /// The cell's stripe, its record's own measure at the cell's T1 and the factor between them.
  std::optional<CellScaling> Scaling(std::span<const std::size_t> axis_index) const override;
  /// The record's own measure at the cell's T1 ([records] scale_to or im).
  /// @pre record_scaling() != nullptr
  double UnscaledIntensity(std::span<const std::size_t> axis_index) const override;
  /// @pre record_scaling() != nullptr
  CellOutcome EvaluateScaled(std::span<const std::size_t> axis_index, double factor) const override;
  /// The cell's record at dynamics::kStripeTraceFactor, built as the cell's excitation is, when
  /// Evaluate runs the cell as a stripe of its record (dynamics::RunScaledRecord with the cell's
  /// scale gives its run bit for bit), else nullptr (dynamics::Run gives it).
  std::unique_ptr<Excitation> StripeTraceExcitation(std::span<const std::size_t> axis_index) const;

 private:
  CellGrid spec_;
  model::ModelFile file_;
  std::vector<model::DeckAsWritten> written_;  ///< DecksAsWritten(model file)
  std::vector<SweepRecord> records_;           ///< LoadSweepRecords(spec_), read once per rank
  /// The file's sampled excitation (inline or read from its file, times units and scale),
  /// when no record or pulse replaces it, and its measures (L_e for Pi_delta).
  std::vector<double> samples_mps2_;
  double samples_dt_s_ = 0.0;
  std::optional<records::IntensityMeasures> samples_measures_;
  int n_decks_ = 1;
  bool seats_ = false;   ///< margins are stored (seat_over_L given, or the file's seat width)
  bool travel_ = false;  ///< corner travels are stored (the sweep declares limit states)
  // The intensity measure of the cells ([records] scale_to / im), fixed at construction: the
  // records' measures are computed once per distinct T1, not per cell.
  std::vector<double> t1_values_s_;        ///< distinct fundamental periods of the cells (s)
  std::vector<std::uint32_t> t1_of_cell_;  ///< per cell (row-major): index into t1_values_s_
  std::vector<double> record_im_;          ///< [record][T1 index]: unscaled measure (axis unit)
  std::vector<double> scale_of_cell_;      ///< per cell with scale_to: im / unscaled measure
  std::uint64_t scaled_too_far_ = 0;       ///< cells whose factor exceeds max_scale
  std::vector<std::string> warnings_;      ///< Warnings(), found at construction
  /// What one cell computed, as its responses read it (model_file_evaluator.cpp).
  struct CellValues;
  ResponseTable<CellValues> table_;  ///< the stored responses, each with how it is read
  void MakeResponseTable();
  std::uint64_t CellIndex(std::span<const std::size_t> axis_index) const;
  CellOutcome EvaluateAt(std::span<const std::size_t> axis_index,
                         std::optional<double> factor) const;
  std::size_t RecordIndex(std::span<const std::size_t> axis_index) const;
  /// A dynamic run with its cell, for the cells that differ from it only in the seat widths.
  struct SeatRun {
    ModelFileCell cell;
    dynamics::LawRun run;
  };
  mutable SharedRuns<SeatRun> shared_;  ///< the last runs (spectra/shared_runs.h)
  /// The cells under a record run as stripes of it (dynamics/stripes.h): records, no gap that
  /// follows the factor (no Pi_delta); the event-driven cells among them.
  bool stripes_ = false;
  /// The stripe axis (the intensity axis of [records] scale_to), when the stripes of a record
  /// share its contact-free response: the cells' factors are their own.
  std::optional<std::size_t> stripe_axis_;
  /// The stripes of one record and the cell's other axes (the cell with its stripe and
  /// limit-only axes at index 0, row-major): where each stripe's run stands after the shared
  /// contact-free response.
  struct StripeGroup {
    std::uint64_t key = 0;
    std::vector<dynamics::StripeStart> starts;  ///< per index of the stripe axis
  };
  /// The last groups, as many as there are cells between two stripes of one record that are
  /// not limit-only (the axes after the stripe axis), replaced in turn.
  mutable std::vector<StripeGroup> stripe_groups_;
  std::size_t stripe_capacity_ = 1;
  std::uint64_t work_block_ = 1;  ///< WorkBlock()
  mutable std::size_t next_stripe_group_ = 0;
  /// The pieces of `record`'s H1 that hold the acceleration peak of every scaled copy at the
  /// event-driven policy's ramp horizon (records::FindPeakPieces), found on the first call for
  /// that record and kept; nullptr for a pair.
  std::shared_ptr<const records::PeakPieces> RecordPeakPieces(const SweepRecord& record) const;
  /// Per record of records_, its RecordPeakPieces once found.
  RecordPeakCache peak_pieces_;
  /// The dynamic run of cell `c` (its own factor): as a stripe of its record when the cells run
  /// so, the method is event-driven and the law rigid, else its own run under its law.
  dynamics::LawRun CellRun(std::span<const std::size_t> axis_index, const ModelFileCell& c) const;
  /// The outcome of a cell from its cell and run (the cell's seat widths are its own).
  CellOutcome Outcome(std::span<const std::size_t> axis_index, const ModelFileCell& c,
                      const dynamics::LawRun& run) const;
  // The warnings of the bridge that do not need the cells' models (masses, gaps, seats).
  std::vector<std::string> BridgeWarnings() const;
};

}  // namespace skewbridge::spectra
