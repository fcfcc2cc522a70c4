#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <string>

#include "jobs/app/commands.h"
#include "jobs/h5/cube_file.h"

namespace skewbridge::app {
namespace {

std::string AxisRange(const jobs::h5::AxisSummary& axis) {
  if (!axis.labels.empty()) {
    std::string out;
    for (std::size_t i = 0; i < axis.labels.size() && i < 6; ++i) {
      out += (i ? ", " : "") + axis.labels[i];
    }
    return axis.labels.size() > 6 ? out + ", ..." : out;
  }
  if (axis.values.empty()) {
    return "";
  }
  return fmt::format("{:g} .. {:g}", axis.values.front(), axis.values.back());
}

void PrintCube(const std::string& path) {
  for (const jobs::h5::SweepSummary& s : jobs::h5::SummarizeCube(path)) {
    std::printf("sweep %s (family %s, spec %s, created %s, skewbridge %s)\n", s.name.c_str(),
                s.family.c_str(), s.spec_hash.c_str(), s.created_utc.c_str(),
                s.program_version.c_str());
    std::printf("  axes:\n");
    for (const jobs::h5::AxisSummary& a : s.axes) {
      std::printf("    %-14s %6zu  %s%s\n", a.name.c_str(), a.size, AxisRange(a).c_str(),
                  a.unit.empty() || a.unit == "1" ? "" : (" [" + a.unit + "]").c_str());
    }
    std::printf("  responses:\n");
    for (const jobs::ResponseInfo& r : s.responses) {
      std::printf("    %-14s [%s] %s\n", r.name.c_str(), r.unit.c_str(), r.description.c_str());
    }
    const double percent = s.cells ? 100.0 * static_cast<double>(s.done) / s.cells : 100.0;
    std::printf("  completion: %llu/%llu cells done (%.1f%%), %s, %lld run(s)\n",
                static_cast<unsigned long long>(s.done), static_cast<unsigned long long>(s.cells),
                percent, s.complete ? "complete" : "NOT complete", static_cast<long long>(s.runs));
    for (const auto& [status, count] : s.done_by_status) {
      const auto example = s.status_examples.find(status);
      std::printf("    %-14s %llu%s\n", status.c_str(), static_cast<unsigned long long>(count),
                  example == s.status_examples.end() ? "" : ("  e.g. " + example->second).c_str());
    }
  }
}

}  // namespace

void AddInspectCommand(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd =
      app.add_subcommand("inspect", "Summarise a sweep cube: axes, responses, completion");
  cmd->add_option("file", *path, "Cube FILE.h5 (or FILE.h5.partial)")->required();
  cmd->callback([path] { PrintCube(*path); });
}

}  // namespace skewbridge::app
