// The `skewbridge` program: parses the command line and hands over to the libraries.
// Bad input surfaces here as one line on stderr and exit status 2.
#include <cstdio>
#include <exception>
#include <string>

#include "jobs/app/commands.h"
#include "solver/common/error.h"

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
  if (argc == 1) {  // no arguments: the usage, not "A subcommand is required"
    std::fputs(app.help().c_str(), stdout);
    return 0;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const skewbridge::InputError& e) {
    std::fprintf(stderr, "skewbridge: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "skewbridge: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
