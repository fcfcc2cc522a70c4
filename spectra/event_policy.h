#pragma once
/// @file
/// The integrators' policies as the tables of their members that run files and cubes store
/// (solver/dynamics/event_policy.h, solver/dynamics/time_stepping_policy.h), and the setting of
/// one member by its stored name (a sweep's [event_policy] and [time_stepping_policy]).

#include <optional>
#include <string>
#include <vector>

#include "solver/dynamics/run_policies.h"
#include "solver/model/run_control.h"

namespace skewbridge::spectra {

/// The members of the policy of `method` in `policies` (the event-driven integrator's or
/// Moreau-Jean's), as run files and cubes store them (schema::Entries).
inline std::vector<schema::Entry> PolicyEntries(model::Method method,
                                                const dynamics::RunPolicies& policies) {
  return method == model::Method::kTimeStepping ? schema::Entries(policies.time_stepping)
                                                : schema::Entries(policies.event);
}

/// Sets the member `name` of `policy` ("steps_per_period", "contact.tie_tolerance"; a rule 1 or
/// 0, a count an integer) to `value`, unchecked; false when the policy has no member of that
/// name.
template <typename Policy>
bool SetPolicyMember(Policy* policy, const std::string& name, double value) {
  bool found = false;
  schema::Assign(policy, [&](const std::string& member) -> std::optional<double> {
    if (member != name) return std::nullopt;
    found = true;
    return value;
  });
  return found;
}

}  // namespace skewbridge::spectra
