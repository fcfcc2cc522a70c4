#include "solver/contact/contact_policy.h"

#include <cstring>
#include <optional>
#include <string>
#include <type_traits>

#include "solver/common/error.h"

namespace skewbridge::contact {

void CheckContactPolicy(const ContactPolicy& policy) {
  if (const std::optional<std::string> problem = schema::FirstViolation(policy)) {
    AbortOnBrokenInvariant("the contact policy is within its ranges", __FILE__, __LINE__,
                           ("ContactPolicy: " + *problem).c_str());
  }
}

bool SameBytes(const ContactPolicy& a, const ContactPolicy& b) {
  static_assert(std::is_trivially_copyable_v<ContactPolicy>);
  return std::memcmp(&a, &b, sizeof(ContactPolicy)) == 0;
}

}  // namespace skewbridge::contact
