#pragma once
/// @file
/// The thresholds and rules of both integrators in one value, so that whatever chooses the
/// method (RunControl::method) passes the policy of either: a run uses the one of its method.

#include "solver/dynamics/event_policy.h"
#include "solver/dynamics/time_stepping_policy.h"

namespace skewbridge::dynamics {

/// The event-driven integrator's policy and Moreau-Jean's (defaults: the integrators' own).
struct RunPolicies {
  EventPolicy event;                 ///< used by a run of method kEventDriven (Simulate)
  TimeSteppingPolicy time_stepping;  ///< used by a run of method kTimeStepping
};

}  // namespace skewbridge::dynamics
