#pragma once
/// @file
/// The sub-commands of the `skewbridge` program; each file app/cmd_*.cpp adds one.

#include <CLI/CLI.hpp>

namespace skewbridge::app {

/// `skewbridge version`: prints the version and source revision.
void AddVersionCommand(CLI::App& app);

}  // namespace skewbridge::app
