#include "solver/contact/contact_policy.h"

#include <bit>
#include <cstdint>
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

bool SameBytes(const ContactPolicy& a, const ContactPolicy& b) {
  // Member by member: the struct's trailing padding is whatever the copy or the stack left
  // there, and a memcmp over it would say unequal for equal policies.
  // A member that fits in the padding leaves sizeof alone; the count of members does not.
  static_assert(schema::MemberCount<ContactPolicy>() == 4,
                "SameBytes compares each member: list a new one here");
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  return bits(a.tie_tolerance) == bits(b.tie_tolerance) &&
         bits(a.contact_compliance) == bits(b.contact_compliance) &&
         bits(a.impact_compliance) == bits(b.impact_compliance) &&
         a.enumeration_unknowns == b.enumeration_unknowns;
}

}  // namespace skewbridge::contact
