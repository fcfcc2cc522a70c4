#pragma once
/// @file
/// The narrow interface between the sweep machinery and the physics: one cell of a sweep is
/// one solver run, a pure function of the cell's axis indices (docs/hdf5-layout.md).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "solver/dynamics/run_policies.h"

namespace skewbridge::spectra {

struct SweepRecord;  // spectra/study.h

/// Reserved cell status codes; evaluators use 0 for success and positive codes for expected
/// numerical outcomes (Lemke ray, Painleve situation, ...), named by CellEvaluator::StatusNames.
inline constexpr std::int32_t kStatusOk = 0;
/// The cell has not been computed yet (the fill value of the status dataset).
inline constexpr std::int32_t kStatusNotDone = -1;
/// CellEvaluator::Evaluate threw; the sweep records it and goes on.
inline constexpr std::int32_t kStatusException = -2;
/// The evaluator returned another number of responses than it declares: a bug of the
/// evaluator, stored as a failed cell with its message (CheckResponseCount); the sweep goes on.
inline constexpr std::int32_t kStatusResponseCount = -3;

/// One scalar response of a cell, e.g. {"theta_m_norm", "1", "theta_m rho w_g^2 / a_g"}.
struct ResponseInfo {
  std::string name;         ///< HDF5 dataset name: letters, digits and '_' only.
  std::string unit;         ///< "1" for dimensionless.
  std::string description;  ///< One line, with the normalisation [docs/theory.md §5].
};

/// Solver statistics of one cell (not part of the bit-identical comparison: wall_s varies).
struct CellStats {
  std::int64_t events = 0;  ///< Contact events (impacts, detachments, stick/slip transitions).
  std::int64_t steps = 0;   ///< Integration steps.
  double wall_s = 0.0;      ///< Wall-clock time of the evaluation [s].
};

/// What one cell evaluation returns.
struct CellOutcome {
  std::int32_t status = kStatusOk;  ///< kStatusOk, or an evaluator-defined positive code.
  std::string status_text;          ///< Free text for a failed cell (not stored per cell).
  /// One value per response of CellEvaluator::Responses(), in that order, whatever the status
  /// (a failed cell's values of its run are NaN).
  std::vector<double> responses;
  CellStats stats;
};

/// Whether `outcome` holds exactly `declared` responses. If not, makes it the failed cell of
/// status kStatusResponseCount, without responses, with the message "internal error: the
/// evaluator returned N responses for the M it declares" (an outcome that already has that
/// status, from an evaluator inside a decorator, keeps its message); no value is guessed.
inline bool CheckResponseCount(CellOutcome& outcome, std::size_t declared) {
  if (outcome.responses.size() == declared) return true;
  if (outcome.status != kStatusResponseCount) {
    outcome.status_text = "internal error: the evaluator returned " +
                          std::to_string(outcome.responses.size()) + " responses for the " +
                          std::to_string(declared) + " it declares";
    outcome.status = kStatusResponseCount;
  }
  outcome.responses.clear();
  return false;
}

/// How the record of one cell is scaled to its intensity stripe ([records] scale_to): the
/// factor on the record's accelerations is target / unscaled (docs/sweep-format.md).
struct CellScaling {
  double t1_s = 0.0;      ///< fundamental period of the cell's model (s)
  double unscaled = 0.0;  ///< the record's own intensity measure (g or m/s, the axis unit)
  double target = 0.0;    ///< the cell's stripe: its im_g or im_mps coordinate (same unit)
  double factor = 1.0;    ///< target / unscaled
  bool too_far = false;   ///< factor > [records] max_scale (false without max_scale)
};

/// How the cells of a family that scales its records to an intensity ([records] scale_to or im)
/// scale them: an optional capability of an evaluator, which it exposes through
/// CellEvaluator::record_scaling (nullptr for a family without records to scale) and a decorator
/// exposes unchanged, so no decorator forwards these functions one by one.
class RecordScaling {
 public:
  virtual ~RecordScaling() = default;

  /// How the cell's record is scaled to its stripe, decided at construction (no run); empty
  /// unless the sweep scales its records to an intensity axis (an [ida] sweep has none).
  virtual std::optional<CellScaling> Scaling(std::span<const std::size_t> axis_index) const = 0;

  /// The record's own intensity measure in the cell ([records] scale_to or im: g, or m/s for
  /// PGV, at the cell's T1).
  virtual double UnscaledIntensity(std::span<const std::size_t> axis_index) const = 0;

  /// Evaluates the cell with its record's accelerations multiplied by `factor` in place of the
  /// cell's own factor (incremental dynamic analysis runs one cell at many factors). The
  /// responses are those of the family's evaluator that exposes this capability (its
  /// Responses()), not a decorator's: a decorator adds its own (LimitStateEvaluator).
  virtual CellOutcome EvaluateScaled(std::span<const std::size_t> axis_index,
                                     double factor) const = 0;

 protected:
  RecordScaling() = default;
  RecordScaling(const RecordScaling&) = default;
  RecordScaling& operator=(const RecordScaling&) = default;
};

/// Computes cells of a sweep. Implementations must be pure: the outcome depends only on the
/// axis indices (no state carried between cells), so that a cube is bit-identical whatever the
/// number of ranks and the order of execution. Evaluate is called from one thread per process.
class CellEvaluator {
 public:
  virtual ~CellEvaluator() = default;

  /// The responses stored per cell, in the order CellOutcome::responses follows.
  virtual std::vector<ResponseInfo> Responses() const = 0;

  /// Names of the positive status codes this evaluator returns (code, name), e.g. {1, "ray"}.
  virtual std::vector<std::pair<std::int32_t, std::string>> StatusNames() const { return {}; }

  /// The records this evaluator read or synthesised for the sweep (LoadSweepRecords, in axis
  /// order), so that rank 0 builds the final cube's record table without making them again;
  /// nullptr when it holds none (then rank 0 loads them itself).
  virtual const std::vector<SweepRecord>* Records() const { return nullptr; }
  /// Facts about the sweep's cells decided at construction that its summary reports, one line
  /// each (e.g. the cells whose records were scaled beyond max_scale); none by default.
  virtual std::vector<std::string> Notes() const { return {}; }
  /// Values of the bridge that are more often a unit slip than a bridge (a gap wider than a
  /// tenth of the span, a deck lighter than 1 t/m, a fundamental period outside 0.02-10 s;
  /// solver/model/plausibility.h), decided at construction, one line each; none by default.
  virtual std::vector<std::string> Warnings() const { return {}; }

  /// How this evaluator's family scales its records to an intensity (RecordScaling), or nullptr
  /// when it scales none; a decorator returns its inner evaluator's.
  virtual const RecordScaling* record_scaling() const { return nullptr; }

  /// Evaluates one cell; axis_index[k] indexes axis k of the CellGrid (its canonical order).
  /// A failed cell returns a non-zero status and, like every cell, one value per response.
  virtual CellOutcome Evaluate(std::span<const std::size_t> axis_index) const = 0;

  /// The cells among which this evaluator shares work (one dynamic run for several seat widths,
  /// one contact-free trace for the stripes of a record) lie in blocks of this many consecutive
  /// cells of the cube (row-major), each block starting at a multiple of it: a rank that
  /// evaluates whole blocks does each shared piece of work once. 1 (the default): no sharing.
  virtual std::uint64_t WorkBlock() const { return 1; }

  /// The integrators' policies every run of this evaluator uses (the sweep's [event_policy] and
  /// [time_stepping_policy] over the defaults); the cube stores the one of each method its
  /// cells ran. A decorator holds its inner evaluator's.
  const dynamics::RunPolicies& policies() const { return policies_; }

 protected:
  /// An evaluator whose runs use the integrators' default policies.
  CellEvaluator() = default;
  /// An evaluator whose runs use `policies`.
  explicit CellEvaluator(const dynamics::RunPolicies& policies) : policies_(policies) {}

 private:
  dynamics::RunPolicies policies_;
};

}  // namespace skewbridge::spectra
