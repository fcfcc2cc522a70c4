#include <cstdio>
#include <memory>

#include "jobs/app/commands.h"
#include "jobs/evaluator_factory.h"
#include "jobs/sweep_command.h"

namespace skewbridge::app {

void AddSweepCommand(CLI::App& app) {
  auto args = std::make_shared<jobs::SweepCommandArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "Evaluate a grid of parameters into an HDF5 cube (under mpirun); --dry-run estimates it");
  jobs::AddSweepArguments(*cmd, *args);
  cmd->callback([args] {
    const int code = jobs::RunSweepCommand(
        *args, jobs::MakeEvaluator,
        [](const std::string& s) { std::fprintf(stderr, "%s\n", s.c_str()); },
        [](const std::string& s) { std::fputs(s.c_str(), stdout); });
    if (code != 0) {
      throw CLI::RuntimeError(code);
    }
  });
}

}  // namespace skewbridge::app
