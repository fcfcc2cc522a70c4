#pragma once
/// @file
/// The record correlation sets of a record-driven sweep [docs/theory.md §6; Dimitrakopoulos 2011,
/// §6]: the records of the sweep (read from a manifest or synthesised in memory) with their
/// measures, the w0x/w_g frequency-ratio groups, and the statistics of theta_m against the
/// persistency L_e over the record axis that rank 0 stores in the final cube
/// (docs/hdf5-layout.md).

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "jobs/cube.h"
#include "jobs/sweep_spec.h"
#include "records/ground_motion.h"
#include "records/measures.h"

namespace skewbridge::jobs {

/// A record of the sweep's record set, read and measured once.
struct SweepRecord {
  std::string label;                    ///< label in the record set
  std::string file;                     ///< as the manifest names it; "" when synthesised
  double scale = 1.0;                   ///< the manifest's factor on the accelerations
  records::GroundMotion motion;         ///< accelerations (m/s^2), scaled as the set says
  records::IntensityMeasures measures;  ///< PGA, T_m, w_g, L_e, ...
};

/// The records named by the spec's record axis (or fixed record), in axis order: read from
/// [records] set, or synthesised from [records] synthetic = {count, seed} exactly as
/// `skewbridge records synth` writes them (records::FormatAt2 read back by records::ParseRecord,
/// so both routes give the same samples), each measured with records::ComputeMeasures.
/// Empty when the spec names no record.
/// @throws InputError for a label that is not in the set, or an unreadable or unmeasurable
/// record.
std::vector<SweepRecord> LoadSweepRecords(const SweepSpec& spec);

/// The default w0x/w_g group edges: [0, 0.5), [0.5, 1), [1, 2), [2, inf) [docs/theory.md §6: the
/// rotations fade above w0x/w_g of about 2].
inline constexpr std::array<double, 3> kDefaultBandEdges{0.5, 1.0, 2.0};

/// [study] bands of the spec, or kDefaultBandEdges.
std::vector<double> BandEdges(const SweepSpec& spec);

/// The group of a frequency ratio: k for edges[k-1] <= ratio < edges[k] (edges[-1] = 0,
/// edges[size] = inf), as a double; NaN for a NaN ratio. @pre edges increasing.
double BandOf(double ratio, std::span<const double> edges);

/// Statistics of theta_m against L_e over the record axis, one entry per combination of the
/// other axes (row-major over their shape), per band entries [combination][band].
struct CorrelationTable {
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

/// What the final cube stores besides the cells for a record-driven or banded sweep.
struct StudyTables {
  std::vector<double> band_edges;    ///< set when the layout holds the response "band"
  std::string records_source;        ///< "set" or "synthetic"; "" without records
  std::string records_set;           ///< the manifest as written, or "synthetic count=N seed=S"
  std::vector<SweepRecord> records;  ///< LoadSweepRecords(spec)
  std::optional<CorrelationTable> correlation;  ///< with a record axis and a Pi_delta axis
};

/// Builds the tables from the whole cube (so a resumed sweep gets statistics of all its cells).
/// The correlation table needs a record axis, a Pi_delta axis and the responses theta_m and L_e
/// in the layout; the per-band statistics need the response band.
/// `records`: LoadSweepRecords(spec) when the caller already holds them (the evaluator's, see
/// CellEvaluator::Records), so that a synthetic suite is not made twice; nullptr to load them.
/// @throws InputError as LoadSweepRecords.
StudyTables MakeStudyTables(const SweepSpec& spec, const CubeLayout& layout, const CubeData& data,
                            const std::vector<SweepRecord>* records = nullptr);

}  // namespace skewbridge::jobs
