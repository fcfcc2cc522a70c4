#include "jobs/cube.h"

#include <algorithm>
#include <limits>

#include "solver/common/error.h"
#include "spectra/grid.h"
#include "spectra/model_file_evaluator.h"

namespace skewbridge::jobs {

CubeLayout MakeCubeLayout(const CellEvaluator& evaluator, const std::vector<std::string>& requested,
                          const std::string& source) {
  const std::vector<ResponseInfo> all = evaluator.Responses();
  CubeLayout layout;
  layout.evaluator_responses = all.size();
  layout.policies = evaluator.policies();
  if (requested.empty()) {
    layout.responses = all;
    for (std::size_t i = 0; i < all.size(); ++i) {
      layout.source_index.push_back(i);
    }
  }
  for (const std::string& name : requested) {
    const auto it =
        std::find_if(all.begin(), all.end(), [&](const ResponseInfo& r) { return r.name == name; });
    if (it == all.end()) {
      std::string allowed;
      for (const ResponseInfo& r : all) {
        allowed += (allowed.empty() ? "" : ", ") + r.name;
      }
      throw InputError::AtField(source, "sweep.responses",
                                "unknown response '" + name + "'; allowed: " + allowed);
    }
    layout.responses.push_back(*it);
    layout.source_index.push_back(static_cast<std::size_t>(it - all.begin()));
  }
  layout.status_names = {{kStatusResponseCount, "response-count"},
                         {kStatusException, "exception"},
                         {kStatusNotDone, "not_done"},
                         {kStatusOk, "ok"}};
  for (const auto& entry : evaluator.StatusNames()) {
    SB_DEMAND(entry.first > 0, "evaluator status codes must be positive");
    layout.status_names.push_back(entry);
  }
  return layout;
}

std::vector<model::Method> SweepMethods(const SweepSpec& spec) {
  model::Method fallback = model::Method::kEventDriven;
  if (spec.family == "model-file" && !spectra::Mentions(spec, "method")) {
    fallback = model::ParseModelFile(spec.model_path).run.method;
  }
  return spectra::MethodsOf(spec, fallback);
}

void CubeData::Reset(std::uint64_t cells, std::size_t response_count) {
  responses.assign(response_count,
                   std::vector<double>(cells, std::numeric_limits<double>::quiet_NaN()));
  status.assign(cells, kStatusNotDone);
  done.assign(cells, 0);
  run.assign(cells, 0);
  events.assign(cells, 0);
  steps.assign(cells, 0);
  wall_s.assign(cells, 0.0);
}

void CubeData::Store(std::uint64_t cell, std::int32_t status_code,
                     const std::vector<double>& values, const CellStats& stats,
                     std::int32_t run_number) {
  SB_DEMAND(cell < Cells(), "cell index out of range");
  for (std::size_t r = 0; r < responses.size(); ++r) {
    responses[r][cell] = r < values.size() ? values[r] : std::numeric_limits<double>::quiet_NaN();
  }
  status[cell] = status_code;
  run[cell] = run_number;
  events[cell] = stats.events;
  steps[cell] = stats.steps;
  wall_s[cell] = stats.wall_s;
}

}  // namespace skewbridge::jobs
