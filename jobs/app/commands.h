#pragma once
/// @file
/// The sub-commands of the `skewbridge` program; each file app/cmd_*.cpp adds one.

#include <CLI/CLI.hpp>

namespace skewbridge::app {

/// `skewbridge version`: prints the version and source revision.
void AddVersionCommand(CLI::App& app);
/// `skewbridge run MODEL.toml [--csv run.csv]`: one event-driven run and its summary.
void AddRunCommand(CLI::App& app);
/// `skewbridge sweep SPEC.toml --out FILE.h5`: runs a sweep (MPI inside), jobs/sweep_command.h.
void AddSweepCommand(CLI::App& app);
/// `skewbridge inspect FILE.h5`: prints the sweeps, axes, responses and completion of a cube.
void AddInspectCommand(CLI::App& app);
/// `skewbridge records info FILE|SET.toml`, `records synth`: record measures, synthetic suites.
void AddRecordsCommand(CLI::App& app);

}  // namespace skewbridge::app
