#pragma once
/// @file
/// The sub-commands of the `skewbridge` program; each file app/cmd_*.cpp adds one.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "solver/model/model.h"

namespace skewbridge::app {

/// `skewbridge version`: prints the version and source revision.
void AddVersionCommand(CLI::App& app);
/// `skewbridge run MODEL.toml [--csv run.csv]`: one event-driven run and its summary.
void AddRunCommand(CLI::App& app);
/// `skewbridge modes MODEL.toml`: natural frequencies, mode shapes, centre of rigidity and
/// principal stiffness axes of a model file.
void AddModesCommand(CLI::App& app);
/// Prints the natural frequencies w_k (rad/s), f_k (Hz) and periods of K phi = w^2 M phi.
void PrintNaturalFrequencies(const model::Model& model);
/// Prints the natural frequencies, the mode shapes and, for one deck, the centre of rigidity and
/// the principal stiffness axes (what `skewbridge modes` shows after its header line).
void PrintModes(const model::Model& model);
/// Prints each warning on stderr as "skewbridge: warning: ..." (the command goes on).
void PrintWarnings(const std::vector<std::string>& warnings);
/// `skewbridge sweep SPEC.toml --out FILE.h5`: runs a sweep (MPI inside), jobs/sweep_command.h.
void AddSweepCommand(CLI::App& app);
/// `skewbridge inspect FILE.h5`: prints the sweeps, axes, responses and completion of a cube.
void AddInspectCommand(CLI::App& app);
/// `skewbridge risk CUBE.h5 --hazard FILE`: annual rates of the limit states over a hazard
/// curve, jobs/risk_command.h.
void AddRiskCommand(CLI::App& app);
/// `skewbridge records info FILE|SET.toml`, `records synth`: record measures, synthetic suites.
void AddRecordsCommand(CLI::App& app);
/// `skewbridge restitution --mass-kg M ...`: the equivalent restitution, contact duration and
/// permanent set of a compliant abutment struck by a mass (docs/compliant.md).
void AddRestitutionCommand(CLI::App& app);

}  // namespace skewbridge::app
