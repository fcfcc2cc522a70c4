#include "jobs/sweep_command.h"

#include <exception>

#include "jobs/mpi/mpi_transport.h"
#include "jobs/stop_signal.h"
#include "solver/common/error.h"

namespace skewbridge::jobs {

void AddSweepArguments(CLI::App& cmd, SweepCommandArgs& args) {
  cmd.add_option("spec", args.spec_file, "Sweep specification (TOML, docs/sweep-format.md)")
      ->required();
  cmd.add_option("--out,-o", args.options.out,
                 "Output cube FILE.h5 (checkpoints in FILE.h5.partial)")
      ->required();
  cmd.add_flag("--resume", args.options.resume,
               "Continue FILE.h5.partial, recomputing only missing cells");
  cmd.add_flag("--force", args.options.force, "Replace an existing FILE.h5 / FILE.h5.partial");
  cmd.add_flag("--quiet,-q", args.quiet, "No progress lines on stderr");
  cmd.add_option("--checkpoint-seconds", args.options.checkpoint_seconds,
                 "Write finished cells to the file at least this often [s]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd.add_option("--checkpoint-cells", args.options.checkpoint_cells,
                 "Also write them every this many cells (0 = off)")
      ->capture_default_str();
}

int RunSweepCommand(const SweepCommandArgs& args, const EvaluatorFactory& factory,
                    const std::function<void(const std::string&)>& log) {
  MpiSession mpi;
  const bool root = mpi.Rank() == 0;
  try {
    const SweepSpec spec = LoadSweepSpec(args.spec_file);
    const std::unique_ptr<CellEvaluator> evaluator = factory(spec);
    StopSignal stop;
    SweepOptions options = args.options;
    options.stop = stop.Flag();
    if (root && !args.quiet) {
      options.progress = [&log](const SweepProgress& p) { log(FormatProgress(p)); };
    }
    const std::unique_ptr<Transport> transport =
        mpi.Size() == 1 ? MakeInProcessTransport() : MakeMpiTransport();
    const SweepReport report = RunSweep(spec, *evaluator, *transport, options);
    if (root) {
      log(FormatSummary(report));
    }
    if (stop.Received() != 0 && !report.complete) {
      return 128 + stop.Received();
    }
    // Only rank 0 knows whether the cube is complete; mpiexec reports its status.
    return report.complete || !root ? 0 : 3;
  } catch (const InputError&) {
    if (root) {
      throw;
    }
    return 2;
  } catch (const std::exception& e) {
    // Past setup, a failure on one rank would leave the others waiting: end them all.
    log(std::string("skewbridge: error: ") + e.what());
    AbortAll(1);
    return 1;
  }
}

}  // namespace skewbridge::jobs
