#include "jobs/sweep_command.h"

#include <chrono>
#include <cstdio>
#include <exception>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "jobs/dry_run.h"
#include "jobs/mpi/mpi_transport.h"
#include "jobs/output_lock.h"
#include "jobs/stop_signal.h"
#include "solver/common/error.h"
#include "spectra/plausibility.h"

namespace skewbridge::jobs {
namespace {

// Refuses a grid larger than the limit before anything is allocated or evaluated for it.
void CheckCellCount(const SweepSpec& spec, std::uint64_t max_cells) {
  const std::uint64_t cells = spec.CellCount();
  if (cells <= max_cells) {
    return;
  }
  std::string shape;
  for (const Axis& axis : spec.axes) {
    shape += (shape.empty() ? "" : " x ") + std::to_string(axis.Size());
  }
  const std::string count = cells == std::numeric_limits<std::uint64_t>::max()
                                ? "more than 1.8e19"
                                : std::to_string(cells);
  throw InputError::AtLine(spec.source, 0,
                           "the grid has " + count + " cells (" + shape + "), more than " +
                               "--max-cells " + std::to_string(max_cells) +
                               "; use fewer axis values or raise --max-cells");
}

// Passes every call through and records whether the collective Finish has returned: a
// failure after it (the final cube's write on rank 0, which ends the chunk farm before
// Finish) leaves no rank waiting, so it needs no MPI_Abort.
class FinishWatch final : public Transport {
 public:
  explicit FinishWatch(std::unique_ptr<Transport> inner) : inner_(std::move(inner)) {}
  int Rank() const override { return inner_->Rank(); }
  int Size() const override { return inner_->Size(); }
  std::string BroadcastText(const std::string& text) override {
    return inner_->BroadcastText(text);
  }
  void BroadcastPending(PendingCells& pending) override { inner_->BroadcastPending(pending); }
  std::pair<std::uint64_t, std::uint64_t> Claim(std::uint64_t count, std::uint64_t block) override {
    return inner_->Claim(count, block);
  }
  void StopClaims() override { inner_->StopClaims(); }
  void Send(std::vector<char> message) override { inner_->Send(std::move(message)); }
  void EndStream() override { inner_->EndStream(); }
  bool Receive(const std::function<void(std::span<const char>)>& handle, double wait_s) override {
    return inner_->Receive(handle, wait_s);
  }
  ReceiveStats Received() const override { return inner_->Received(); }
  bool AllTrue(bool mine) override { return inner_->AllTrue(mine); }
  std::vector<std::string> GatherText(const std::string& mine) override {
    return inner_->GatherText(mine);
  }
  void Farm(std::size_t count, const std::function<std::vector<char>(std::size_t)>& job,
            const std::function<std::vector<char>(std::span<const char>)>& work,
            const std::function<void(std::size_t, std::span<const char>)>& done) override {
    inner_->Farm(count, job, work, done);
  }
  void Finish() override {
    inner_->Finish();
    finished_ = true;
  }
  bool finished() const { return finished_; }

 private:
  std::unique_ptr<Transport> inner_;
  bool finished_ = false;
};

}  // namespace

void AddSweepArguments(CLI::App& cmd, SweepCommandArgs& args) {
  cmd.add_option("spec", args.spec_file, "Sweep specification (TOML, docs/sweep-format.md)")
      ->required();
  CLI::Option* out =
      cmd.add_option("--out,-o", args.options.out,
                     "Output cube FILE.h5 (checkpoints in FILE.h5.partial, lock in FILE.h5.lock)");
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
  cmd.add_option("--max-cells", args.max_cells,
                 "Refuse a grid of more cells than this before any work")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd.add_flag("--dry-run", args.dry_run,
               "Print the cell count, the records and a time estimate from a few cells timed "
               "here; write nothing");
  cmd.add_option("--ranks", args.ranks,
                 "With --dry-run: estimate the time on this many ranks (default: the ranks "
                 "it runs on)")
      ->check(CLI::PositiveNumber);
  cmd.add_option("--sample-cells", args.sample_cells, "With --dry-run: cells to time")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd.add_flag("--scale-table", args.scale_table,
               "With --dry-run: the full record x stripe table of scale factors (printed "
               "anyway up to 20 records)");
  // --out is required for a real run only: checked once every option is parsed.
  cmd.parse_complete_callback([out, &args] {
    if (!args.dry_run && out->count() == 0) {
      throw CLI::RequiredError(out->get_name());
    }
  });
}

int RunSweepCommand(const SweepCommandArgs& args, const EvaluatorFactory& factory,
                    const std::function<void(const std::string&)>& log,
                    const std::function<void(const std::string&)>& print) {
  MpiSession mpi;
  const bool root = mpi.Rank() == 0;
  // The rank that found the problem prints it and flushes before any rank leaves, then all
  // return 2 through MPI_Finalize: no MPI_Abort, whose teardown could swallow the line.
  auto report = [&](const std::string& message, bool reporter) {
    if (reporter) {
      log("skewbridge: error: " + message);
      std::fflush(stderr);
    }
    mpi.Barrier();
    return 2;
  };

  // Everything that can be checked before the first cell, on every rank; the ranks agree.
  std::optional<SweepSpec> spec;
  std::unique_ptr<CellEvaluator> evaluator;
  std::optional<OutputLock> lock;
  std::string problem;
  double setup_s = 0.0;
  try {
    if (root && !args.dry_run) {
      CheckOutputPath(args.options.out);
    }
    spec.emplace(LoadSweepSpec(args.spec_file));
    CheckCellCount(*spec, args.max_cells);
    if (root && !args.dry_run) {
      lock.emplace(args.options.out);  // held until the run has ended
    }
    const auto start = std::chrono::steady_clock::now();
    evaluator = factory(*spec);
    setup_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } catch (const InputError& e) {
    problem = e.what();
  }
  const int first = mpi.FirstRankWith(!problem.empty());
  if (first < mpi.Size()) {
    return report(problem, mpi.Rank() == first);
  }
  if (root) {
    // Values more often a unit slip than a bridge: said once, before any work; the sweep runs.
    std::vector<std::string> warnings = spectra::GridWarnings(*spec);
    for (std::string& w : evaluator->Warnings()) warnings.push_back(std::move(w));
    for (const std::string& w : warnings) log("skewbridge: warning: " + w);
  }
  if (args.dry_run) {
    std::string text;
    if (root) {
      try {
        text = DryRunReport(*spec, *evaluator, args.ranks > 0 ? args.ranks : mpi.Size(),
                            args.sample_cells, args.options.root_computes_up_to_ranks, setup_s,
                            args.scale_table);
      } catch (const InputError& e) {
        problem = e.what();
      }
    }
    if (!problem.empty()) {
      return report(problem, root);
    }
    if (root) {
      (print ? print : log)(text);
      std::fflush(stdout);
    }
    mpi.Barrier();
    return 0;
  }

  std::unique_ptr<FinishWatch> transport;
  try {
    StopSignal stop;
    SweepOptions options = args.options;
    options.stop = stop.Flag();
    if (root && !args.quiet) {
      options.progress = [&log](const SweepProgress& p) { log(FormatProgress(p)); };
    }
    transport = std::make_unique<FinishWatch>(mpi.Size() == 1 ? MakeInProcessTransport()
                                                              : MakeMpiTransport());
    const SweepReport sweep = RunSweep(*spec, *evaluator, *transport, options);
    if (root) {
      log(FormatSummary(sweep));
      for (const std::string& note : evaluator->Notes()) log("sweep: " + note);
    }
    if (stop.Received() != 0 && !sweep.complete) {
      return 128 + stop.Received();
    }
    // Only rank 0 knows whether the cube is complete; mpiexec reports its status.
    return sweep.complete || !root ? 0 : 3;
  } catch (const InputError& e) {
    // RunSweep's setup errors are shared by broadcast, so every rank is here.
    return report(e.what(), root);
  } catch (const std::exception& e) {
    log(std::string("skewbridge: error: ") + e.what());
    std::fflush(stderr);
    if (mpi.Size() == 1 || (transport != nullptr && transport->finished())) {
      return 1;  // nobody waits for this process: a clean exit, no abort
    }
    // Past setup, a failure on one rank would leave the others waiting: end them all.
    AbortAll(1);
    return 1;
  }
}

}  // namespace skewbridge::jobs
