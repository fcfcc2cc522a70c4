#pragma once
/// @file
/// The record correlation sets of a record-driven sweep [docs/theory.md §6; Dimitrakopoulos 2011,
/// §4]: the records of the sweep (read from a manifest or synthesised in memory) with their
/// measures, the w0x/w_g frequency-ratio groups, and the statistics of theta_m against the
/// persistency L_e over the record axis, which rank 0 stores in the final cube
/// (docs/hdf5-layout.md; jobs/study.h gathers them from the cube).

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "records/excitations.h"
#include "records/ground_motion.h"
#include "records/measures.h"
#include "records/record_set.h"
#include "spectra/grid.h"

namespace skewbridge::spectra {

/// A record of the sweep's record set, read and measured once.
struct SweepRecord {
  std::string label;             ///< label in the record set
  std::string file;              ///< relative to the manifest's folder; "" if synthesised
  double scale = 1.0;            ///< the manifest's factor on the accelerations
  records::GroundMotion motion;  ///< accelerations (m/s^2), scaled as the set says; H1 of a pair
  records::IntensityMeasures measures;  ///< PGA, T_m, w_g, L_e, CAV, ... of `motion`
  /// The second horizontal component H2 of a pair (same dt and npts as `motion`, the shorter of
  /// the two files padded with zeros at its end); empty for a single record.
  std::optional<records::GroundMotion> motion_h2;
  /// The measures of motion_h2 (of a pair only).
  std::optional<records::IntensityMeasures> measures_h2;
  std::string file_h2;  ///< a pair's H2 file, relative to the manifest's folder; "" if single
  /// Zero samples appended at the end of H1 (0) and H2 (1) to make a pair's lengths equal.
  std::array<std::size_t, 2> padded_samples{0, 0};
  /// The spectral measures at the sweep's fundamental period T1, when every cell of the sweep
  /// has the same T1 (a model-file sweep whose axes leave the model's modes alone); NaN
  /// otherwise (the cells then store T1 and their measure themselves).
  double t1_s = std::numeric_limits<double>::quiet_NaN();
  double spectral_xi = 0.05;  ///< damping ratio of sa_t1 and avgsa ([records] scale_to / im)
  double sa_t1_mps2 = std::numeric_limits<double>::quiet_NaN();  ///< Sa(T1, xi) (m/s^2)
  double avgsa_mps2 = std::numeric_limits<double>::quiet_NaN();  ///< AvgSa(T1, xi) (m/s^2)
  /// A pair's measures at t1_s and spectral_xi (m/s^2; the angle in deg from H1 towards H2)
  /// [Boore 2010], set with sa_t1_mps2 by SetSpectralMeasuresAtT1; NaN for a single record.
  double rotd50_t1_mps2 = std::numeric_limits<double>::quiet_NaN();
  double rotd100_t1_mps2 = std::numeric_limits<double>::quiet_NaN();  ///< RotD100(T1, xi)
  double gm_t1_mps2 = std::numeric_limits<double>::quiet_NaN();       ///< sqrt(Sa_H1 Sa_H2) at T1
  double rotd100_angle_t1_deg = std::numeric_limits<double>::quiet_NaN();  ///< angle of RotD100

  /// Whether the record is a pair of horizontal components (motion is H1, motion_h2 is H2).
  bool IsPair() const { return motion_h2.has_value(); }
};

/// The measure `im` names of a record as given (unscaled), at period t1_s where the measure
/// takes "T1": Sa and AvgSa (0.2-3 T1, records::kAvgSaPeriodCount periods) in g, PGA in g,
/// PGV in m/s, and of a pair RotD50, RotD100 and GM in g (records::PairResponseSpectrum) or
/// AvgSa_RotD50 in g (records::AverageRotD50, 0.2-3 T1): the unit of the intensity axis (im_g,
/// im_mps). The values SetSpectralMeasuresAtT1 stored for
/// this very period and damping are taken as they are (one computation per record and period).
/// @pre im.measure is one of Sa, AvgSa, PGA, PGV (single records) or RotD50, RotD100, GM,
/// AvgSa_RotD50 (pairs, CheckMeasureOfRecords); t1_s > 0 when im.at_t1.
double RecordIntensity(const SweepRecord& record, const IntensityMeasureSpec& im, double t1_s);

/// Sets the record's spectral measures at the sweep's one fundamental period t1_s and damping xi
/// (t1_s, spectral_xi, sa_t1_mps2, avgsa_mps2; of a pair also RotD50, RotD100 with its angle,
/// and GM), each computed once.
void SetSpectralMeasuresAtT1(SweepRecord& record, double t1_s, double xi);

/// Refuses a measure that does not fit a record of the sweep: a pair measure (RotD50, RotD100,
/// GM) of a single record, or a one-component measure (Sa, AvgSa, PGA, PGV) of a pair, whose
/// value would depend on which component is H1.
/// @throws InputError naming spec.source, the field records.scale_to (or records.im).measure
/// and the first record that does not fit.
void CheckMeasureOfRecords(const CellGrid& spec, const std::vector<SweepRecord>& records);

/// The unit of the measure's axis and of the cells' im: "g", or "m/s" for PGV.
std::string IntensityUnit(const IntensityMeasureSpec& im);

/// A one-line description of the measure: "Sa(T1, xi = 0.05): pseudo-spectral acceleration ...".
std::string IntensityDescription(const IntensityMeasureSpec& im);

/// The measure, period and damping a cube's im_measure and im_description attributes name, read
/// back from the text IntensityDescription writes (measure, at_t1, period_s, xi; scale and
/// max_scale are not in it). nullopt when `description` is not such a text for `measure`.
std::optional<IntensityMeasureSpec> ParseIntensityDescription(std::string_view measure,
                                                              std::string_view description);

/// The records named by the spec's record axis (or fixed record), in axis order: read from
/// [records] set, or synthesised from [records] synthetic = {count, seed} exactly as
/// `skewbridge records synth` writes them (records::FormatAt2 read back by records::ParseRecord,
/// so both routes give the same samples), each measured with records::ComputeMeasures.
/// Empty when the spec names no record.
/// @throws InputError for a label that is not in the set, or an unreadable or unmeasurable
/// record.
std::vector<SweepRecord> LoadSweepRecords(const CellGrid& spec);

/// The record set a grid names: its manifest ([records] set) or its folder and pattern
/// (records::MakeFolderSet, with the grid's units and dt for files that state none).
/// @throws InputError from the manifest, or naming the spec's records.folder / records.pattern.
records::RecordSet LoadSpecRecordSet(const CellGrid& spec);

/// Every record label of the grid's synthetic suite or record set, in set order (what
/// `record = "*"` stands for). @throws InputError as LoadSpecRecordSet.
std::vector<std::string> AllRecordLabels(const CellGrid& spec);

/// Whether `units` names the units of a record file (records::ParseUnits: g, m/s^2, cm/s^2).
bool KnownRecordUnits(std::string_view units);

/// The default w0x/w_g group edges: [0, 0.5), [0.5, 1), [1, 2), [2, inf) [docs/theory.md §6: the
/// rotations fade above w0x/w_g of about 2].
inline constexpr std::array<double, 3> kDefaultBandEdges{0.5, 1.0, 2.0};

/// [study] bands of the spec, or kDefaultBandEdges.
std::vector<double> BandEdges(const CellGrid& spec);

/// The group of a frequency ratio: k for edges[k-1] <= ratio < edges[k] (edges[-1] = 0,
/// edges[size] = inf), as a double; NaN for a NaN ratio. @pre edges increasing.
double BandOf(double ratio, std::span<const double> edges);

/// Statistics of theta_m against L_e over the record axis, one entry per combination of the
/// other axes (row-major over their shape), per band entries [combination][band].
struct CorrelationTable {
  std::string y = "theta_m";            ///< the rotation response correlated (theta_m_d0: one deck)
  std::vector<std::string> axis_order;  ///< keys of the other axes, in cube order
  std::vector<std::size_t> shape;       ///< their sizes
  std::vector<std::int64_t> n;          ///< cells used: status ok, done, theta_m and L_e finite
  std::vector<double> pearson;          ///< Pearson r(L_e, theta_m)
  std::vector<double> spearman;         ///< Spearman rho(L_e, theta_m), average ranks for ties
  std::vector<std::int64_t> loglog_n;   ///< cells with theta_m > 0 and L_e > 0
  std::vector<double> loglog_slope;     ///< log10 theta_m = intercept + slope log10 L_e
  std::vector<double> loglog_intercept;
  std::vector<double> loglog_r2;
  std::vector<std::string> reason;  ///< "" or why a statistic is NaN
  std::size_t bands = 0;            ///< number of groups (edges + 1)
  std::vector<std::int64_t> band_n;
  std::vector<double> band_pearson;  ///< NaN where the group has < kMinBandRecords cells
  std::vector<double> band_spearman;
  std::vector<double> band_loglog_slope;
  std::vector<double> band_loglog_intercept;
  std::vector<double> band_loglog_r2;
};

/// A frequency-ratio group gets statistics only from this many records on.
inline constexpr std::int64_t kMinBandRecords = 3;

/// The correlation table of a grid with a record axis: for every combination of the other
/// axes, the statistics of theta_m against L_e over the records whose cell is `usable` (done,
/// status ok) with finite values. `band` (per cell, NaN-free group index) may be empty: then no
/// per-band statistics. Arrays are indexed by the row-major cell index of `grid`.
/// @pre grid has a record axis; theta, le, usable (and band if not empty) have CellCount() entries
CorrelationTable CorrelateOverRecords(const CellGrid& grid, std::span<const double> theta,
                                      std::span<const double> le, std::span<const double> band,
                                      std::span<const std::uint8_t> usable, std::size_t band_count);

/// Each record's peak pieces (records::FindPeakPieces) found once per rank: the pieces a record
/// excitation's Peak reads instead of walking every sample.
class RecordPeakCache {
 public:
  /// The peak pieces of `record`, an element of `records`, at the ramp horizon horizon_s (s);
  /// null for a pair or a record of fewer than 2 samples (their Peak walks the samples).
  std::shared_ptr<const records::PeakPieces> Get(const std::vector<SweepRecord>& records,
                                                 const SweepRecord& record, double horizon_s) const;

 private:
  /// Per record of the sweep, its pieces once found.
  mutable std::vector<std::shared_ptr<const records::PeakPieces>> kept_;
};

}  // namespace skewbridge::spectra
