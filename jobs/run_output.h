#pragma once
/// @file
/// One run (event-driven or time-stepping) stored in HDF5 (docs/run-output.md): provenance,
/// summary, energy ledger, event log and, when recorded, the time histories. Free of <hdf5.h>.

#include <cstdint>
#include <filesystem>
#include <string_view>

#include "solver/dynamics/run_result.h"
#include "solver/model/model.h"

namespace skewbridge::jobs {

/// The format name stored in the root attribute "format" of a run file.
inline constexpr const char* kRunFormat = "skewbridge-run";
/// The version stored in the root attribute "format_version" of a run file.
inline constexpr std::int64_t kRunFormatVersion = 1;

/// Writes (truncating) the run file at `path` in the layout of docs/run-output.md; the group
/// "histories" only when result.histories holds samples. `model_text` is stored verbatim;
/// `method` (run.method: "event-driven" | "time-stepping") and `time_step_s` (the Moreau-Jean
/// step h in s, NaN for event-driven) become the root attributes of the same names.
/// @pre result comes from dynamics::Simulate or dynamics::SimulateTimeStepping on `model`
/// (sizes match n_dof and contacts).
/// @throws h5::H5Error on I/O failure (the caller removes the partial file).
void WriteRunHdf5(const std::filesystem::path& path, const model::Model& model,
                  const dynamics::RunResult& result, std::string_view model_text,
                  std::string_view method, double time_step_s);

}  // namespace skewbridge::jobs
