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
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "records/ground_motion.h"
#include "records/measures.h"
#include "records/record_set.h"
#include "spectra/grid.h"

namespace skewbridge::spectra {

/// A record of the sweep's record set, read and measured once.
struct SweepRecord {
  std::string label;                    ///< label in the record set
  std::string file;                     ///< relative to the manifest's folder; "" if synthesised
  double scale = 1.0;                   ///< the manifest's factor on the accelerations
  records::GroundMotion motion;         ///< accelerations (m/s^2), scaled as the set says
  records::IntensityMeasures measures;  ///< PGA, T_m, w_g, L_e, CAV, ...
  /// The spectral measures at the sweep's fundamental period T1, when every cell of the sweep
  /// has the same T1 (a model-file sweep whose axes leave the model's modes alone); NaN
  /// otherwise (the cells then store T1 and their measure themselves).
  double t1_s = std::numeric_limits<double>::quiet_NaN();
  double spectral_xi = 0.05;  ///< damping ratio of sa_t1 and avgsa ([records] scale_to / im)
  double sa_t1_mps2 = std::numeric_limits<double>::quiet_NaN();  ///< Sa(T1, xi) (m/s^2)
  double avgsa_mps2 = std::numeric_limits<double>::quiet_NaN();  ///< AvgSa(T1, xi) (m/s^2)
};

/// The measure `im` names of a record as given (unscaled), at period t1_s where the measure
/// takes "T1": Sa and AvgSa (0.2-3 T1, records::kAvgSaPeriodCount periods) in g, PGA in g,
/// PGV in m/s: the unit of the intensity axis (im_g, im_mps).
/// @pre im.measure is one of Sa, AvgSa, PGA, PGV; t1_s > 0 when im.at_t1.
double RecordIntensity(const SweepRecord& record, const IntensityMeasureSpec& im, double t1_s);

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

}  // namespace skewbridge::spectra
