#include "jobs/sweep_cells.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace skewbridge::jobs {

std::uint64_t ChunkSize(std::uint64_t total, std::uint64_t seen, int ranks,
                        const SweepOptions& options, double cell_s) {
  const std::uint64_t left = total > seen ? total - seen : 0;
  const std::uint64_t share = left / (2 * static_cast<std::uint64_t>(ranks));
  std::uint64_t cap = std::max<std::uint64_t>(1, options.max_chunk);
  if (!(cell_s > 0.0)) {
    cap = 1;
  } else if (options.chunk_seconds / cell_s < static_cast<double>(cap)) {
    cap = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(options.chunk_seconds / cell_s));
  }
  return std::clamp<std::uint64_t>(share, 1, cap);
}

void EvaluateInto(const SweepSpec& spec, const CellEvaluator& evaluator, const CubeLayout& layout,
                  std::uint64_t cell, std::size_t i, ResultBatch& batch) {
  const std::size_t n = batch.Size();
  const std::vector<std::size_t> index = spec.AxisIndex(cell);
  const auto start = std::chrono::steady_clock::now();
  std::int32_t status = kStatusOk;
  std::string text;
  try {
    CellOutcome outcome = evaluator.Evaluate(index);
    // A cell without exactly the evaluator's responses is an internal error of its own status:
    // no value is guessed for it.
    const bool complete = CheckResponseCount(outcome, layout.evaluator_responses);
    status = outcome.status;
    batch.events[i] = outcome.stats.events;
    batch.steps[i] = outcome.stats.steps;
    if (outcome.status != kStatusOk) {
      text = std::move(outcome.status_text);
    }
    for (std::size_t r = 0; r < layout.source_index.size(); ++r) {
      batch.values[r * n + i] = complete ? outcome.responses[layout.source_index[r]]
                                         : std::numeric_limits<double>::quiet_NaN();
    }
  } catch (const std::exception& e) {
    status = kStatusException;
    text = e.what();
    for (std::size_t r = 0; r < layout.source_index.size(); ++r) {
      batch.values[r * n + i] = std::numeric_limits<double>::quiet_NaN();
    }
  }
  batch.status[i] = status;
  batch.wall_s[i] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (status != kStatusOk) {
    const auto it = std::find_if(batch.failures.begin(), batch.failures.end(),
                                 [&](const FailureNote& f) { return f.status == status; });
    if (it == batch.failures.end()) {
      batch.failures.push_back({status, 1, cell, std::move(text)});
    } else {
      ++it->count;
      if (cell < it->lowest_cell) {
        it->lowest_cell = cell;
        it->text = std::move(text);
      }
    }
  }
}

}  // namespace skewbridge::jobs
