#pragma once
/// @file
/// The `skewbridge sweep` command as a library entry point, so that the program and the test
/// driver (tests/jobs) run exactly the same code with different evaluators.

#include <CLI/CLI.hpp>

#include <cstdint>
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
  /// Refuse a grid of more cells than this before any work (--max-cells).
  std::uint64_t max_cells = 100'000'000;
  /// --dry-run: print the grid, records and a time estimate (jobs/dry_run.h); write nothing.
  bool dry_run = false;
  /// --ranks: the rank count the dry run estimates for; 0 = the ranks it runs on.
  int ranks = 0;
  /// --sample-cells: cells the dry run times.
  std::size_t sample_cells = 8;
  /// --scale-table: with --dry-run, the full record x stripe table of scale factors whatever
  /// the number of records.
  bool scale_table = false;
};

/// Builds the evaluator of a specification (MakeEvaluator in the program, a test evaluator in
/// the tests). @throws InputError for a specification it cannot evaluate.
using EvaluatorFactory = std::function<std::unique_ptr<CellEvaluator>(const SweepSpec&)>;

/// Declares SPEC, --out, --resume, --force, --quiet, --checkpoint-seconds, --checkpoint-cells,
/// --max-cells, --dry-run, --ranks, --sample-cells, --scale-table on `cmd`, storing into `args`;
/// --out is required unless --dry-run is given.
void AddSweepArguments(CLI::App& cmd, SweepCommandArgs& args);

/// Runs the command: MPI_Init (only here); on every rank, before any work, the output path
/// (rank 0), the specification, the cell count against max_cells, the writer lock on
/// FILE.lock (rank 0, held for the whole run) and the evaluator; then catches SIGTERM/SIGINT
/// as a stop request, runs the sweep, MPI_Finalize. Rank 0 passes progress lines and the
/// final summary to `log`. Bad input is passed to `log` once, as "skewbridge: error: ...",
/// by the lowest rank that found it, before any rank returns.
/// With args.dry_run, rank 0 passes DryRunReport (no output path, lock or file) to `print`
/// (to `log` when empty) and every rank returns 0.
/// @returns 0 when the cube is complete, 2 on every rank for bad input (nothing computed),
///          128 + signal when stopped by a signal (the partial file stays resumable), 3 when
///          cells are missing for another reason, 1 for a failure while running (an I/O
///          error such as a full disk: one line naming the file and the system's reason, then
///          MPI_Abort only while other ranks still compute; FILE.partial stays resumable).
int RunSweepCommand(const SweepCommandArgs& args, const EvaluatorFactory& factory,
                    const std::function<void(const std::string&)>& log,
                    const std::function<void(const std::string&)>& print = {});

}  // namespace skewbridge::jobs
