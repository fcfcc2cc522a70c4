#pragma once
/// @file
/// The event policy of the integrator as HDF5 attributes, so that a run file or a cube says
/// which thresholds and rules made it (docs/hdf5-layout.md, "The event policy").

#include <vector>
#include "jobs/h5/h5.h"

#include "spectra/event_policy.h"

namespace skewbridge::jobs::h5 {

/// Creates the group `event_policy` under `parent` with one attribute per member of the policy
/// `entries` (schema::Entries of the policy: float64, or int64 for counts and rules) and the
/// string lists `keys`, `units` and `relative_to` (the scale each member multiplies, "" for
/// none).
void WriteEventPolicy(hid_t parent, const std::vector<schema::Entry>& entries);

}  // namespace skewbridge::jobs::h5
