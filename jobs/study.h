#pragma once
/// @file
/// The tables a record-driven or banded sweep stores in its final cube besides the cells: the
/// records with their measures, the band edges and the correlation statistics of theta_m
/// against L_e over the record axis (spectra/study.h computes them; docs/hdf5-layout.md).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "jobs/cube.h"
#include "jobs/sweep_spec.h"
#include "spectra/fragility_table.h"
#include "spectra/over_axis.h"
#include "spectra/study.h"

namespace skewbridge::jobs {

// The sweep machinery's names for the record study, which spectra owns.
using spectra::BandEdges;
using spectra::BandOf;
using spectra::CorrelationTable;
using spectra::FragilityTable;
using spectra::kDefaultBandEdges;
using spectra::kMinBandRecords;
using spectra::LoadSweepRecords;
using spectra::SweepRecord;

/// The fragility of one limit state over the cube (docs/hdf5-layout.md, fragility/).
struct FragilityStudy {
  spectra::LimitState ls;   ///< the limit state as declared
  std::string demand_unit;  ///< unit of its demand
  std::string im;  ///< "im_g" / "im_mps" (the stripe axis), "im" (the cell's measure) or "a_g"
  std::string im_units;        ///< "g", or "m/s" for PGV
  std::string im_description;  ///< how the IM of a cell is obtained
  /// A fit at the worst incidence angle (fragility_worst_incidence/) rather than per
  /// combination of the axes (fragility/).
  bool worst_incidence = false;
  spectra::FragilityTable table;
};

/// The fragility of one limit state from the capacities of an IDA sweep ([ida]): per
/// combination of the axes other than `record`, the lognormal fit of the records' capacity
/// intensities (spectra::FitCapacities; docs/hdf5-layout.md, fragility/).
struct IdaFragilityStudy {
  spectra::LimitState ls;                 ///< the limit state as declared
  std::string im_units;                   ///< "g", or "m/s" for PGV
  std::vector<std::string> axis_order;    ///< the combination axes, in cube order
  std::vector<std::size_t> shape;         ///< their sizes ({} for one combination)
  std::vector<double> theta, beta;        ///< per combination: median capacity, dispersion
  std::vector<std::int64_t> n, censored;  ///< capacities used, capacities beyond max_im
  std::vector<std::string> reason;        ///< "" or why theta and beta are NaN
  std::vector<std::string> note;          ///< "" or how censored records entered the fit
  /// Per combination: capacities reached at a scale factor above [records] max_scale (flagged,
  /// censored at max_scale in the fit; counted in n_censored too).
  std::vector<std::int64_t> too_far;
};

/// The responses of the bridge over the incidence angle (an `incidence_deg` axis): per response,
/// its largest value over the angles, its median and the angle of the largest, over the grid
/// without the angle axis (docs/hdf5-layout.md, over_incidence/).
struct OverIncidence {
  std::vector<double> angles_deg;                   ///< the axis' coordinates [deg]
  std::vector<std::string> axis_order;              ///< the remaining axes, in cube order
  std::vector<std::size_t> shape;                   ///< their sizes ({} when none remain)
  std::vector<ResponseInfo> responses;              ///< the responses reduced, in layout order
  std::vector<spectra::AxisStatistics> statistics;  ///< one per response
};

/// What the final cube stores besides the cells for a record-driven or banded sweep.
struct StudyTables {
  std::vector<double> band_edges;    ///< set when the layout holds the response "band"
  std::string records_source;        ///< "set" or "synthetic"; "" without records
  std::string records_set;           ///< the manifest as written, or "synthetic count=N seed=S"
  std::vector<SweepRecord> records;  ///< LoadSweepRecords(spec)
  std::optional<CorrelationTable> correlation;  ///< with a record axis and a Pi_delta axis
  std::vector<FragilityStudy> fragility;        ///< one per limit state, with an IM
  /// With an incidence_deg axis, one per limit state of `fragility`: the fit over the grid
  /// without the angle axis, a cell exceeding when it exceeds at some angle (the worst angle).
  std::vector<FragilityStudy> fragility_worst_incidence;
  std::optional<OverIncidence> over_incidence;   ///< with an incidence_deg axis
  std::vector<IdaFragilityStudy> ida_fragility;  ///< one per limit state of an IDA sweep
  /// With an incidence_deg axis, one per limit state of `ida_fragility`: the fit over the
  /// combinations without the angle axis of each record's capacity at its worst angle (the
  /// lowest of its capacities over the angles).
  std::vector<IdaFragilityStudy> ida_fragility_worst_incidence;
  spectra::IntensityMeasureSpec im;  ///< [records] scale_to / im of the spec
  /// Cells done with scaled_too_far = 1 (the response), -1 when the layout has no such response.
  std::int64_t scaled_too_far = -1;
};

/// Builds the tables from the whole cube (so a resumed sweep gets statistics of all its cells).
/// The correlation table needs a record axis, a Pi_delta axis and the responses theta_m (or, for
/// a one-deck model-file sweep, theta_m_d0) and L_e in the layout; the per-band statistics need
/// the response band.
/// `records`: LoadSweepRecords(spec) when the caller already holds them (the evaluator's, see
/// CellEvaluator::Records), so that a synthetic suite is not made twice; nullptr to load them.
/// With limit states, each gets its fragility (spectra::FitFragilityOverCells): the IM of a cell
/// is the coordinate of an `im_g` or `im_mps` axis (records scaled to stripes of it) when the
/// sweep has one, else its response `im` ([records] im: the records' own measure, a cloud), else
/// its excitation amplitude a_g / g (a record's PGA times `scale`, with the `scale` axis as
/// stripes when there is one). With an `incidence_deg` axis the responses of the bridge are
/// reduced over it (OverIncidence) and each limit state is fitted again at the worst angle.
/// @throws InputError as LoadSweepRecords.
/// `fragility`: the studies MakeFragilityStudies made (the ranks' shared fits merged), so
/// that they are not fitted again; nullptr to fit them here.
StudyTables MakeStudyTables(const SweepSpec& spec, const CubeLayout& layout, const CubeData& data,
                            const std::vector<SweepRecord>* records = nullptr,
                            std::vector<FragilityStudy>* fragility = nullptr);

/// The fragility of each limit state over the cube, as MakeStudyTables stores it: the fits per
/// combination, then, with an incidence_deg axis, the fits at the worst angle (worst_incidence
/// set); with `ranks` > 1 only the combinations of this rank's share are fitted
/// (spectra::FitShare, the jobs numbered over those fits in order), the others wait for
/// MergeFits.
std::vector<FragilityStudy> MakeFragilityStudies(const SweepSpec& spec, const CubeLayout& layout,
                                                 const CubeData& data, int rank = 0, int ranks = 1);

/// The columns of `data` that MakeFragilityStudies reads (done, status, the IM, a_g,
/// scaled_too_far and every limit state's demand and outcome), as bytes for the other ranks.
std::string PackFragilityInputs(const SweepSpec& spec, const CubeLayout& layout,
                                const CubeData& data);
/// A cube image holding only those columns (the others empty), from PackFragilityInputs.
CubeData UnpackFragilityInputs(const CubeLayout& layout, std::string_view bytes);

/// The fits this rank made (its share of MakeFragilityStudies: point fits, cloud fits and
/// bootstrap intervals of its combinations), as bytes for rank 0.
std::string PackFits(const std::vector<FragilityStudy>& studies, int rank, int ranks);
/// Puts another rank's fits (PackFits) into `studies`.
void MergeFits(std::vector<FragilityStudy>& studies, std::string_view bytes);

}  // namespace skewbridge::jobs
