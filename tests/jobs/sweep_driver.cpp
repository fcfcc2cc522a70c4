// Test-only program: the `skewbridge sweep` entry point (jobs::RunSweepCommand) driven by the
// deterministic test evaluator, for the kill/resume and h5py tests launched by ctest.
#include <cstdio>

#include "jobs/sweep_command.h"
#include "solver/common/error.h"
#include "tests/jobs/test_evaluator.h"

int main(int argc, char** argv) {
  namespace jobs = skewbridge::jobs;
  CLI::App app{"sweep driver with the test evaluator"};
  jobs::SweepCommandArgs args;
  jobs::AddSweepArguments(app, args);
  std::int64_t work = 200;
  double sleep_ms = 0.0;
  app.add_option("--work", work, "Arithmetic iterations per cost unit of a cell");
  app.add_option("--sleep-ms", sleep_ms, "Added wall time per cell [ms]");
  try {
    app.parse(argc, argv);
    return jobs::RunSweepCommand(
        args,
        [&](const jobs::SweepSpec& spec) {
          return std::make_unique<jobs::testing::TestEvaluator>(spec, work, sleep_ms);
        },
        [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); });
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const skewbridge::InputError& e) {
    std::fprintf(stderr, "sweep_driver: error: %s\n", e.what());
    return 2;
  }
}
