#pragma once
/// @file
/// One run (event-driven or time-stepping) stored in HDF5 (docs/run-output.md): provenance,
/// summary, energy ledger, event log and, when recorded, the time histories. Free of <hdf5.h>.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "solver/dynamics/run_policies.h"
#include "solver/dynamics/run_result.h"
#include "solver/model/model.h"

namespace skewbridge::jobs {

/// The format name stored in the root attribute "format" of a run file.
inline constexpr const char* kRunFormat = "skewbridge-run";
/// The version stored in the root attribute "format_version" of a run file.
inline constexpr std::int64_t kRunFormatVersion = 1;

/// Where a run's ground motion and model came from beyond the model file: a record read by
/// `run --record` or `--record-set`, its scale factor, or the cube cell it re-runs
/// (docs/run-output.md, group `origin`). Empty for a run of a model file as written.
struct RunOrigin {
  /// String attributes of the group, in order (e.g. {"record_file", "NIS090.AT2"}).
  std::vector<std::pair<std::string, std::string>> text;
  /// Number attributes of the group, in order (e.g. {"scale_factor", 2.5}).
  std::vector<std::pair<std::string, double>> numbers;
  /// The ground acceleration the run applied, sample k at t = k dt_s (m/s^2, x and y); empty
  /// for a pulse.
  std::vector<double> ground_ax_mps2, ground_ay_mps2;
  double ground_dt_s = 0.0;  ///< their sample interval (s)
  /// Whether there is anything to store.
  bool Empty() const { return text.empty() && numbers.empty() && ground_ax_mps2.empty(); }
};

/// What the compliant joints of a run gave (docs/run-output.md, group `joints`); empty for a run
/// under the rigid law.
struct RunJoints {
  /// The joints' responses, as a model-file sweep stores them (dynamics::JointResponses): name,
  /// unit, value.
  struct Response {
    std::string name;    ///< e.g. "spring_force_px"
    std::string unit;    ///< "N", "m", "s" or "1"
    double value = 0.0;  ///< its value for the run
  };
  std::vector<Response> responses;     ///< in the order of dynamics::JointResponses
  double stored_J = 0.0;               ///< energy the springs and keys would give back by unloading
  double dissipated_J = 0.0;           ///< the springs' and keys' work less what they store
  std::vector<std::string> key_names;  ///< per shear key, "+x.key+y", ...
  std::vector<double> key_force_N;     ///< per key, its largest force (N)
  std::vector<double> key_deformation_m;  ///< per key, its largest deformation beyond its gap (m)
  std::vector<double> key_break_time_s;   ///< per key, when it broke (s); inf if intact
  std::vector<std::string> spring_names;  ///< per backfill or joint spring, "+x.1", ..., "J0.1"
  std::vector<double> spring_force_N;     ///< per spring, its largest force (N)
  std::vector<double> spring_deformation_m;  ///< per spring, its largest deformation (m)
  std::vector<double> spring_slip_m;         ///< per spring, its plastic slip along the wall (m)
  /// Whether there is anything to store.
  bool Empty() const { return responses.empty(); }
};

/// Writes (truncating) the run file at `path` in the layout of docs/run-output.md; the group
/// "histories" only when result.histories holds samples. `model_text` is stored verbatim;
/// `method` (run.method: "event-driven" | "time-stepping") and `time_step_s` (the Moreau-Jean
/// step h in s, NaN for event-driven) become the root attributes of the same names.
/// @pre result comes from dynamics::Simulate or dynamics::SimulateTimeStepping on `model`
/// (sizes match n_dof and contacts). `origin`, when not empty, becomes the group `origin`.
/// The policy of `method` in `policies`, the one the run used, becomes the group
/// `event_policy` or `time_stepping_policy`. `joints`, when not empty, becomes the group `joints`.
/// @throws h5::H5Error on I/O failure (the caller removes the partial file).
void WriteRunHdf5(const std::filesystem::path& path, const model::Model& model,
                  const dynamics::RunResult& result, std::string_view model_text,
                  std::string_view method, double time_step_s, const RunOrigin& origin = {},
                  const dynamics::RunPolicies& policies = {}, const RunJoints& joints = {});

}  // namespace skewbridge::jobs
