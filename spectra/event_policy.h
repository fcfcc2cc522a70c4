#pragma once
/// @file
/// The event policy the evaluators run the event-driven integrator with, as the table of its
/// members that run files and cubes store (solver/dynamics/event_policy.h).

#include <vector>

#include "solver/dynamics/event_policy.h"

namespace skewbridge::spectra {

/// The members of the policy every evaluator uses (the integrator's defaults).
inline std::vector<schema::Entry> EvaluatorEventPolicy() {
  return schema::Entries(dynamics::EventPolicy{});
}

}  // namespace skewbridge::spectra
