#include <cstdio>

#include "jobs/app/commands.h"

namespace skewbridge::app {

void AddVersionCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("version", "Print the version and source revision");
  cmd->callback(
      [] { std::printf("skewbridge %s (%s)\n", SKEWBRIDGE_VERSION, SKEWBRIDGE_GIT_REVISION); });
}

}  // namespace skewbridge::app
