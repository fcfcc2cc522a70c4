#include "solver/contact/contact_policy.h"

#include <optional>
#include <string>

#include "solver/common/error.h"

namespace skewbridge::contact {

void CheckContactPolicy(const ContactPolicy& policy) {
  if (const std::optional<std::string> problem = schema::FirstViolation(policy)) {
    AbortOnBrokenInvariant("the contact policy is within its ranges", __FILE__, __LINE__,
                           ("ContactPolicy: " + *problem).c_str());
  }
}

}  // namespace skewbridge::contact
