#pragma once
/// @file
/// The grid of a sweep as the physics sees it: the family, the axes and fixed values of the
/// parameters, and where the records and the model come from. jobs::SweepSpec adds to it what
/// only the sweep machinery needs (the file text, the cube name, the stored responses); an
/// evaluator reads nothing else (docs/architecture.md, "The life of one grid point").

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "solver/dynamics/run_policies.h"
#include "solver/model/run_control.h"

namespace skewbridge::spectra {

/// Whether a parameter takes numbers or text labels (pulse shape, record label).
enum class ParameterKind { kNumber, kLabel };

/// One axis of the grid: numbers (values) or labels, never both.
struct Axis {
  std::string key;  ///< A parameter key (jobs::KnownParameters()).
  ParameterKind kind = ParameterKind::kNumber;
  std::vector<double> values;       ///< Coordinates of a numeric axis, in the given order.
  std::vector<std::string> labels;  ///< Coordinates of a label axis.
  std::string spacing;  ///< "list", "linspace", "logspace" or "all" (record = "*" or implied).
  /// Number of coordinates (>= 1 after validation).
  std::size_t Size() const {
    return kind == ParameterKind::kNumber ? values.size() : labels.size();
  }
};

/// A parameter held constant over the sweep.
struct FixedValue {
  std::string key;  ///< A parameter key (jobs::KnownParameters()).
  ParameterKind kind = ParameterKind::kNumber;
  double value = 0.0;  ///< For numbers.
  std::string label;   ///< For labels.
};

/// What a limit state compares (docs/sweep-format.md, [limit_states]).
enum class LimitStateKind {
  kUnseating,         ///< a corner's travel normal to its end line beyond its seat width
  kRotation,          ///< max |theta| of any deck above a value (rad)
  kSeatDisplacement,  ///< a corner's travel normal to its end line above a value (m)
  kResidual,          ///< a corner's residual travel normal to its end line above a value (m)
  kJointClosing,      ///< any impact (a gap closes)
  kResponse,          ///< a stored response above a value (its unit)
};

/// One limit state of a sweep: each cell stores its demand and its exceedance (0/1).
struct LimitState {
  std::string name;  ///< "unseating", "rotation", ... or the response's name (kResponse)
  LimitStateKind kind = LimitStateKind::kResponse;
  double threshold = 0.0;  ///< rad, m or the response's unit; unused by unseating and joints
  std::string response;    ///< kResponse: the response compared
  /// kUnseating: seat widths (m) per support line (abutment, pier lines, abutment) or one for
  /// all; empty: the sweep's own (seat_over_L times each deck's length).
  std::vector<double> seat_m;
  std::string at;  ///< "spec.toml:LINE" of its key, for messages
};

/// The intensity measure of a record-driven sweep's cells ([records] scale_to or im,
/// docs/sweep-format.md): Sa(T, xi), AvgSa(T1, xi) over 0.2-3 T1 [Eads et al. 2015], PGA or PGV
/// of the record as the cell applies it; for record pairs RotD50, RotD100 [Boore 2010] or the
/// geometric mean GM of the two components' Sa(T, xi).
struct IntensityMeasureSpec {
  /// "Sa", "AvgSa", "PGA", "PGV", or of a pair "RotD50", "RotD100", "GM", "AvgSa_RotD50" (the
  /// geometric mean of RotD50 over the periods of AvgSa); empty: none given.
  std::string measure;
  bool at_t1 = false;     ///< period = "T1": the fundamental period of each cell's model
  double period_s = 0.0;  ///< the period (Sa) or conditioning period (AvgSa*) when !at_t1 (s)
  double xi = 0.05;       ///< damping ratio of the spectrum (Sa, AvgSa)
  /// true: [records] scale_to, every record scaled so that its measure equals the cell's im_g
  /// (or im_mps) coordinate (stripes); false: [records] im, records unscaled (cloud).
  bool scale = false;
  /// [records] max_scale: cells whose scale factor exceeds it are flagged scaled_too_far (and
  /// still computed); 0 = no limit.
  double max_scale = 0.0;
  /// [records] beyond_max_scale = "exclude": the fragility fits (stripes, cloud, IDA) leave out
  /// the cells scaled beyond max_scale and count them; false ("keep"): they enter every fit.
  bool exclude_beyond_max_scale = false;
  /// The axis (or fixed) key that carries the target: "im_g" (Sa, AvgSa, PGA) or "im_mps" (PGV).
  std::string AxisKey() const { return measure == "PGV" ? "im_mps" : "im_g"; }
  /// Whether the measure is of a pair of horizontal components (RotD50, RotD100, GM,
  /// AvgSa_RotD50).
  bool OfPair() const {
    return measure == "RotD50" || measure == "RotD100" || measure == "GM" ||
           measure == "AvgSa_RotD50";
  }
  /// Whether the measure is a spectral ordinate with a period and a damping ratio (Sa, AvgSa
  /// and the pair measures).
  bool Spectral() const { return measure == "Sa" || measure == "AvgSa" || OfPair(); }
};

/// Incremental dynamic analysis ([ida], docs/sweep-format.md): each cell scales its record up
/// through a sequence of intensities chosen by the hunt-and-fill search [Vamvatsikos and Cornell
/// 2002, EESD 31:491-514; 2004, Earthquake Spectra 20(2):523-553] until every limit state is
/// exceeded, in the unit of the [records] scale_to measure (g, or m/s for PGV).
struct IdaSpec {
  bool enabled = false;         ///< [ida] given
  double start = 0.1;           ///< first intensity of the hunt (g or m/s)
  double step = 0.1;            ///< first step of the hunt (g or m/s)
  double step_increase = 0.05;  ///< added to the step after each hunting run (g or m/s)
  double tolerance = 0.02;      ///< bisect until each capacity is bracketed this tightly
  double max_im = 5.0;          ///< the hunt stops here: beyond, a capacity is not reached
  int max_runs = 16;            ///< runs per cell: hunt, bisection, then filling of gaps
};

/// The validated grid of a sweep. Axes are in the canonical order of the parameter table,
/// whatever the order in the file, so equal grids give equal cube layouts.
struct CellGrid {
  std::string source;                     ///< Where it came from (file name), for messages.
  std::string family;                     ///< "subsystem", "pilot-bridge", "multispan", ...
  std::string model_file;                 ///< [sweep] model, as written (family "model-file" only).
  std::filesystem::path model_path;       ///< model_file resolved against the spec's folder.
  std::string record_set;                 ///< [records] set, as written, or empty.
  std::filesystem::path record_set_path;  ///< record_set resolved against the spec's folder.
  /// [records] folder and pattern: a set of every matching file, without a manifest
  /// (records::MakeFolderSet); empty when not given.
  std::string record_folder;
  std::filesystem::path record_folder_path;  ///< record_folder resolved against the spec's folder.
  std::string record_pattern;                ///< [records] pattern, a file-name glob.
  std::string record_units;                  ///< [records] units for files stating none, or "".
  double record_dt_s = 0.0;                  ///< [records] dt for files stating none, or 0.
  std::string record_folder_at;              ///< "spec.toml:LINE" of folder, for messages.
  std::string record_pattern_at;             ///< "spec.toml:LINE" of pattern, for messages.
  /// [records] pairs = true: the folder's files are record pairs, paired by name
  /// (records::PairsByName).
  bool record_pairs_by_name = false;
  /// [records] pairs = "FILE.csv": the table of the folder that names the pairs; empty: none.
  std::string record_pairs_table;
  std::string record_pairs_at;  ///< "spec.toml:LINE" of pairs, for messages.
  /// [records] synthetic = {count, seed}: a suite made in memory (records::SynthesizeSuite)
  /// instead of a manifest; count 0 when not given.
  int synthetic_count = 0;
  std::uint64_t synthetic_seed = 0;  ///< The suite's seed (labels "synth-<seed>-<index>").
  /// [study] bands: increasing, positive w0x/w_g edges of the frequency-ratio groups; empty
  /// when not given (the evaluator then uses 0.5, 1, 2) [docs/theory.md §6].
  std::vector<double> study_bands;
  IntensityMeasureSpec im;  ///< [records] scale_to / im; im.measure empty when not given
  std::vector<Axis> axes;
  std::vector<FixedValue> fixed;
  /// Where the file names each axis and fixed key: "axes.KEY" or "fixed.KEY" to
  /// "spec.toml:LINE", for messages (empty for a grid built in code).
  std::map<std::string, std::string, std::less<>> key_at;
  std::vector<LimitState> limit_states;  ///< [limit_states], in canonical order; may be empty
  IdaSpec ida;                           ///< [ida]; ida.enabled false when not given
  /// [event_policy] and [time_stepping_policy]: the integrators' defaults with the members the
  /// sweep sets; every run of the sweep uses the one of its method (CellEvaluator::policies).
  dynamics::RunPolicies policies;

  /// The number of coordinates per axis, in axis order.
  std::vector<std::size_t> Shape() const;
  /// Product of the axis sizes (1 for a sweep without axes), UINT64_MAX when it overflows.
  std::uint64_t CellCount() const;
  /// Axis indices of the cell with row-major linear index `cell` (last axis fastest).
  /// @pre cell < CellCount()
  std::vector<std::size_t> AxisIndex(std::uint64_t cell) const;
  /// The axis with this key, or nullptr.
  const Axis* FindAxis(std::string_view key) const;
  /// The fixed value with this key, or nullptr.
  const FixedValue* FindFixed(std::string_view key) const;
};

/// The value of numeric parameter `key` in the cell with axis indices `index` (its axis
/// coordinate, else its fixed value, else `fallback`); `given` (if not null) says whether the
/// grid mentions the key.
double NumberOf(const CellGrid& grid, std::span<const std::size_t> index, std::string_view key,
                double fallback, bool* given = nullptr);

/// The label of parameter `key` in the cell (axis, fixed value or `fallback`).
std::string LabelOf(const CellGrid& grid, std::span<const std::size_t> index, std::string_view key,
                    std::string fallback = {});

/// The integrator of the cell: its label of parameter "method" (event-driven or time-stepping),
/// or `fallback` where the grid does not name the key.
/// @throws InputError naming the grid's source for another label.
model::Method MethodOf(const CellGrid& grid, std::span<const std::size_t> index,
                       model::Method fallback);

/// The integrators of all the grid's cells, each once: the labels of its "method" axis or fixed
/// value, else `fallback`.
/// @throws InputError as MethodOf.
std::vector<model::Method> MethodsOf(const CellGrid& grid, model::Method fallback);

/// Whether the grid names `key` as an axis or a fixed value.
bool Mentions(const CellGrid& grid, std::string_view key);

/// Where the grid names `key`, for a message: "spec.toml:LINE: axes.KEY" (or fixed.KEY), the
/// grid's source without a line when the key's line is not known.
/// @pre Mentions(grid, key)
std::string KeyWhere(const CellGrid& grid, std::string_view key);

/// Whether the grid gives seat widths: seat_over_L or seat_m (axis or fixed value).
bool MentionsSeat(const CellGrid& grid);

/// The seat width (m) of a deck of length `length_m` in the cell: seat_over_L times the length,
/// else seat_m as given, else 0 with `given` (if not null) false.
double SeatWidthOf(const CellGrid& grid, std::span<const std::size_t> index, double length_m,
                   bool* given = nullptr);

}  // namespace skewbridge::spectra
