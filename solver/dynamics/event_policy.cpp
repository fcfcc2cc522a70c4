#include "solver/dynamics/event_policy.h"

namespace skewbridge::dynamics {

void ValidatePolicy(const EventPolicy& policy) { schema::Validate(policy, "event policy"); }

}  // namespace skewbridge::dynamics
