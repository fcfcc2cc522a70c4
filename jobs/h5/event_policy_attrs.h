#pragma once
/// @file
/// The integrators' policies as HDF5 attributes, so that a run file or a cube says which
/// thresholds and rules made it (docs/hdf5-layout.md, "The event policy"): `event_policy` for the
/// event-driven integrator, `time_stepping_policy` for Moreau-Jean.

#include <string>
#include <vector>
#include "jobs/h5/h5.h"

#include "spectra/event_policy.h"

namespace skewbridge::jobs::h5 {

/// Creates the group `group` under `parent` with one attribute per member of the policy
/// `entries` (schema::Entries of the policy: float64, or int64 for counts and rules) and the
/// string lists `keys`, `units` and `relative_to` (the scale each member multiplies, "" for
/// none).
void WritePolicy(hid_t parent, const std::string& group, const std::vector<schema::Entry>& entries);

/// The group name of the policy of `method`: "event_policy" or "time_stepping_policy".
const char* PolicyGroup(model::Method method);

/// Writes, for each of `methods` once, its policy in `policies` (the one its runs used) in its
/// group (PolicyGroup).
void WriteMethodPolicies(hid_t parent, const std::vector<model::Method>& methods,
                         const dynamics::RunPolicies& policies);

}  // namespace skewbridge::jobs::h5
