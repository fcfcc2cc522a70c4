#pragma once
/// @file
/// The risk/ group of a final cube (docs/hdf5-layout.md): what `skewbridge risk` reads of a
/// sweep (its fragility fits, stripes, the cells' T1 and scale factors, the measure of its IM)
/// and what it writes back (the rates of spectra::RiskTable, the hazard points integrated, and
/// the hazard file's identity in the sweep's inputs/).

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "spectra/risk_table.h"

namespace skewbridge::jobs::h5 {

/// One limit state's fragility as fragility/<name>/ stores it, per combination (row-major).
struct StoredFragility {
  std::string name;                          ///< the limit state
  std::vector<double> theta, beta;           ///< NaN where not fitted
  std::vector<double> se_ln_theta, se_beta;  ///< NaN when the group stores none (IDA fits)
  std::vector<double> cov_ln_theta_beta;     ///< likewise
  std::vector<std::string> reason;           ///< why not fitted, per combination
  std::vector<double> stripe_im;             ///< [combination][stripe], empty without stripes
  std::vector<std::int64_t> stripe_n;        ///< cells per stripe, likewise
};

/// What the risk command reads of one sweep of a final cube.
struct RiskSource {
  std::string sweep;                    ///< the sweep group's name
  std::string method;                   ///< fragility/ method: "stripes", "cloud" or "ida"
  std::string im;                       ///< fragility/ im: "im_g", "a_g", "im", "ida_capacity"
  std::string im_measure;               ///< the sweep's im_measure ("Sa", "PGA", ...)
  std::string im_description;           ///< the sweep's im_description
  std::string im_units;                 ///< "g" or "m/s"
  double max_scale = 0.0;               ///< records.max_scale; 0 when none (stored as inf)
  std::vector<std::string> cube_axes;   ///< the cube's axes, in order
  std::vector<std::size_t> cube_shape;  ///< their sizes
  std::vector<std::string> axis_order;  ///< the fragility's combination axes
  std::size_t stripes = 0;              ///< size of the stripe axis (0: none)
  std::vector<StoredFragility> limit_states;
  std::vector<double> t1_s;          ///< per cell: responses/T1, or empty
  std::vector<double> scale_factor;  ///< per cell: responses/scale_factor, or empty
  std::vector<double> status;        ///< per cell: the status (0 = ok)
};

/// Reads the fragility of sweep `sweep` of a final cube.
/// @throws InputError naming the file when it is not a final cube, has no such sweep, or the
/// sweep has no fragility/ group (no [limit_states], or a cube not finished).
RiskSource ReadRiskSource(const std::filesystem::path& path, const std::string& sweep);

/// The identity and description of the hazard a risk table was computed from.
struct RiskHazardInfo {
  std::string file;           ///< the path as given
  std::uint64_t bytes = 0;    ///< its size
  std::string sha256;         ///< 64 hex digits
  std::string format;         ///< "openquake-csv" or "two-column"
  std::string imt;            ///< the hazard's measure, as IntensityMeasureId::Describe says it
  std::string fragility_imt;  ///< the fragility's, likewise
  std::string kind;           ///< OpenQuake's kind ("mean", ...), else ""
  double investigation_time_yr = 0.0;  ///< OpenQuake's T, else 0
  std::int64_t site = 0;               ///< OpenQuake's site row
  double lon_deg = 0.0, lat_deg = 0.0;
  std::string conversion;         ///< the --convert applied, or ""
  double period_tolerance = 0.0;  ///< relative
  std::string created_utc;        ///< when the table was written
};

/// Writes sweep `sweep`'s risk/ group (replacing an earlier one) and the hazard file's entry
/// (role "hazard", replacing an earlier one) in its inputs/. The group is written under a
/// temporary name and renamed last, so that a failure leaves no risk/ group that looks whole.
/// @throws InputError naming the file when it cannot be opened for writing.
void WriteRisk(const std::filesystem::path& path, const std::string& sweep,
               const spectra::RiskTable& table, const RiskHazardInfo& hazard,
               const std::vector<std::string>& axis_order, const std::vector<std::size_t>& shape);

/// One limit state's stored rates, for `inspect`.
struct StoredRisk {
  std::string name;
  std::vector<double> rate_per_yr, rate_p16, rate_p84, p_50yr, return_period_yr, cornell_rate;
  std::vector<double> share_beyond_hazard;
  std::vector<std::string> reason, flags;
};

/// The risk/ group of a sweep as `inspect` prints it.
struct RiskSummary {
  bool present = false;                 ///< the sweep has a risk/ group
  std::vector<std::string> attrs;       ///< "key: value" lines of the hazard's identity and rule
  std::vector<std::string> notes;       ///< the common flags
  std::vector<std::string> axis_order;  ///< the combination axes (row-major)
  std::vector<StoredRisk> limit_states;
};

/// Reads sweep `sweep`'s risk/ group (present = false when there is none).
/// @throws InputError naming the file when it cannot be read.
RiskSummary ReadRiskSummary(const std::filesystem::path& path, const std::string& sweep);

}  // namespace skewbridge::jobs::h5
