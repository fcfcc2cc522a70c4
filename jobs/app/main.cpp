// The `skewbridge` program: parses the command line and hands over to the libraries.
// Bad input surfaces here as one line on stderr and exit status 2.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <thread>

#include "jobs/app/commands.h"
#include "jobs/app/parse_error.h"
#include "solver/common/error.h"

namespace {

// Whether this process is rank 0 of an mpiexec launch, or not launched by one. A command line
// fails to parse the same way on every rank, before MPI starts: the launcher's rank variable
// lets one rank say so, where every rank would print the same line.
bool FirstOrOnlyProcess() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"}) {
    if (const char* rank = std::getenv(name)) {
      return std::string(rank) == "0";
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"skewbridge: seismic response of skew bridges with pounding deck-abutment joints"};
  app.name("skewbridge");
  app.require_subcommand(1);
  app.set_version_flag(
      "-V,--version",
      std::string("skewbridge ") + SKEWBRIDGE_VERSION + " (" + SKEWBRIDGE_GIT_REVISION + ")",
      "Print the version and source revision and exit");
  skewbridge::app::AddVersionCommand(app);
  skewbridge::app::AddRunCommand(app);
  skewbridge::app::AddModesCommand(app);
  skewbridge::app::AddSweepCommand(app);
  skewbridge::app::AddInspectCommand(app);
  skewbridge::app::AddRecordsCommand(app);
  skewbridge::app::AddRiskCommand(app);
  skewbridge::app::AddRestitutionCommand(app);
  if (argc == 1) {  // no arguments: the usage, not "A subcommand is required"
    std::fputs(app.help().c_str(), stdout);
    return 0;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::RuntimeError& e) {  // a command's own exit status, already reported
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    if (!FirstOrOnlyProcess()) {
      // mpiexec ends the job at the first non-zero exit: give rank 0 time to print its line.
      std::this_thread::sleep_for(std::chrono::seconds(1));
      return 2;
    }
    std::fprintf(stderr, "skewbridge: error: %s\n",
                 skewbridge::app::DescribeParseError(app, e).c_str());
    return 2;
  } catch (const skewbridge::InputError& e) {
    std::fprintf(stderr, "skewbridge: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "skewbridge: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
