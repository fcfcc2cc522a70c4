#include "solver/dynamics/time_stepping_policy.h"

namespace skewbridge::dynamics {

void ValidatePolicy(const TimeSteppingPolicy& policy) {
  schema::Validate(policy, "time-stepping policy");
}

}  // namespace skewbridge::dynamics
