#pragma once
/// @file
/// Command-line mistakes in the program's own words: the one line after "skewbridge: error: "
/// for a CLI11 parse error (unknown sub-command, missing or unknown option, bad value).

#include <CLI/CLI.hpp>

#include <string>

namespace skewbridge::app {

/// One line naming the sub-command, the option or argument at fault and what is allowed (the
/// sub-commands or options of that sub-command, with the nearest one to a misspelling).
/// `app` is the program's parser after `parse` threw `e`.
std::string DescribeParseError(CLI::App& app, const CLI::ParseError& e);

}  // namespace skewbridge::app
