#include "jobs/evaluator_factory.h"

#include <algorithm>
#include <string>
#include <vector>

#include "jobs/cube.h"
#include "solver/common/error.h"
#include "spectra/ida.h"
#include "spectra/limit_states.h"
#include "spectra/model_file_evaluator.h"
#include "spectra/multispan_evaluator.h"
#include "spectra/spectra_evaluator.h"

namespace skewbridge::jobs {

namespace {

std::unique_ptr<CellEvaluator> FamilyEvaluator(const SweepSpec& spec) {
  if (spec.family == "multi-span") return std::make_unique<spectra::MultiSpanEvaluator>(spec);
  if (spec.family == "model-file") return std::make_unique<spectra::ModelFileEvaluator>(spec);
  return std::make_unique<spectra::SpectraEvaluator>(spec);
}

// Whether `policy` has a member away from the integrator's defaults.
template <typename Policy>
bool Changed(const Policy& policy) {
  const std::vector<schema::Entry> set = schema::Entries(policy),
                                   defaults = schema::Entries(Policy{});
  for (std::size_t i = 0; i < set.size(); ++i) {
    if (set[i].value != defaults[i].value) return true;
  }
  return false;
}

// A policy table that no cell's method reads would change nothing in silence: refused.
void CheckPoliciesRead(const SweepSpec& spec) {
  const std::vector<model::Method> methods = SweepMethods(spec);
  const auto runs = [&](model::Method m) {
    return std::find(methods.begin(), methods.end(), m) != methods.end();
  };
  if (Changed(spec.policies.event) && !runs(model::Method::kEventDriven)) {
    throw InputError::AtField(spec.source, "event_policy",
                              "sets the event-driven integrator's rules, but every cell of the "
                              "sweep runs method \"time-stepping\" (its thresholds are "
                              "[time_stepping_policy])");
  }
  if (Changed(spec.policies.time_stepping) && !runs(model::Method::kTimeStepping)) {
    throw InputError::AtField(spec.source, "time_stepping_policy",
                              "sets Moreau-Jean's thresholds, but no cell of the sweep runs method "
                              "\"time-stepping\" (give method = \"time-stepping\" as an axis or "
                              "a fixed value, or run.method in the model file)");
  }
}

}  // namespace

std::unique_ptr<CellEvaluator> MakeEvaluator(const SweepSpec& spec) {
  std::unique_ptr<CellEvaluator> family = FamilyEvaluator(spec);
  CheckPoliciesRead(spec);
  if (spec.limit_states.empty()) return family;
  auto limit_states = std::make_unique<spectra::LimitStateEvaluator>(std::move(family), spec);
  if (!spec.ida.enabled) return limit_states;
  return std::make_unique<spectra::IdaEvaluator>(std::move(limit_states), spec);
}

}  // namespace skewbridge::jobs
