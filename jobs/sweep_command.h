#pragma once
/// @file
/// The `skewbridge sweep` command as a library entry point, so that the program and the test
/// driver (tests/jobs) run exactly the same code with different evaluators.

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <string>

#include "jobs/cell.h"
#include "jobs/sweep_runner.h"
#include "jobs/sweep_spec.h"

namespace skewbridge::jobs {

/// The command-line arguments of `sweep`.
struct SweepCommandArgs {
  std::string spec_file;  ///< SPEC.toml
  SweepOptions options;   ///< out, resume, force, checkpoint_seconds, checkpoint_cells
  bool quiet = false;     ///< No progress lines (the summary line is still printed).
};

/// Builds the evaluator of a specification (MakeEvaluator in the program, a test evaluator in
/// the tests). @throws InputError for a specification it cannot evaluate.
using EvaluatorFactory = std::function<std::unique_ptr<CellEvaluator>(const SweepSpec&)>;

/// Declares SPEC, --out, --resume, --force, --quiet, --checkpoint-seconds, --checkpoint-cells
/// on `cmd`, storing into `args`.
void AddSweepArguments(CLI::App& cmd, SweepCommandArgs& args);

/// Runs the command: MPI_Init (only here), parse the specification on every rank, build the
/// evaluator, catch SIGTERM/SIGINT as a stop request, run the sweep, MPI_Finalize. Rank 0
/// passes progress lines and the final summary to `log`.
/// @returns 0 when the cube is complete, 128 + signal when stopped by a signal (the partial
///          file stays resumable), 3 when cells are missing for another reason; 2 on ranks
///          other than 0 for bad input.
/// @throws InputError on rank 0 for bad input (before any work).
int RunSweepCommand(const SweepCommandArgs& args, const EvaluatorFactory& factory,
                    const std::function<void(const std::string&)>& log);

}  // namespace skewbridge::jobs
