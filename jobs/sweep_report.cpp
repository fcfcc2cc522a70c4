// The sweep's progress line and summary (jobs/sweep_runner.h).
#include <fmt/format.h>

#include "jobs/sweep_runner.h"

namespace skewbridge::jobs {

std::string FormatProgress(const SweepProgress& p) {
  const double percent =
      p.cells_total ? 100.0 * static_cast<double>(p.cells_done) / static_cast<double>(p.cells_total)
                    : 100.0;
  return fmt::format("sweep: {}/{} cells ({:.1f}%), {} failed, {:.1f} cells/s, ETA {:.0f} s",
                     p.cells_done, p.cells_total, percent, p.run_failed, p.cells_per_s, p.eta_s);
}

std::string FormatSummary(const SweepReport& r) {
  if (r.already_complete) {
    return fmt::format("sweep: already complete ({} cells); nothing to do", r.cells_total);
  }
  const double rate = r.wall_s > 0 ? static_cast<double>(r.cells_computed) / r.wall_s : 0.0;
  std::string failures;
  for (const auto& [name, count] : r.failed_by_status) {
    failures += fmt::format("{}{} {}", failures.empty() ? " (" : ", ", count, name);
  }
  if (!failures.empty()) {
    failures += ")";
  }
  const char* state = r.complete ? "complete" : (r.interrupted ? "interrupted" : "incomplete");
  return fmt::format(
      "sweep {}: run {}, {}/{} cells done, {} computed on {} ranks in {:.2f} s ({:.1f} cells/s), "
      "{} failed{}, {} checkpoints",
      state, r.run, r.cells_done, r.cells_total, r.cells_computed, r.ranks, r.wall_s, rate,
      r.cells_failed, failures, r.checkpoints);
}

}  // namespace skewbridge::jobs
