#pragma once
/// @file
/// The policies the evaluators run the integrators with, as the tables of their members that run
/// files and cubes store (solver/dynamics/event_policy.h, solver/dynamics/time_stepping_policy.h).

#include <vector>

#include "solver/dynamics/event_policy.h"
#include "solver/dynamics/time_stepping_policy.h"
#include "solver/model/run_control.h"

namespace skewbridge::spectra {

/// The members of the event-driven policy every evaluator uses (the integrator's defaults).
inline std::vector<schema::Entry> EvaluatorEventPolicy() {
  return schema::Entries(dynamics::EventPolicy{});
}

/// The members of the policy every evaluator runs `method` with (dynamics::Run: the defaults).
inline std::vector<schema::Entry> EvaluatorPolicy(model::Method method) {
  return method == model::Method::kTimeStepping ? schema::Entries(dynamics::TimeSteppingPolicy{})
                                                : EvaluatorEventPolicy();
}

}  // namespace skewbridge::spectra
