#include "solver/contact/contact_policy.h"

#include <cmath>

#include "solver/common/error.h"

namespace skewbridge::contact {

void CheckContactPolicy(const ContactPolicy& policy) {
  const auto non_negative = [](double x) { return std::isfinite(x) && x >= 0.0; };
  SB_DEMAND(non_negative(policy.tie_tolerance) && non_negative(policy.contact_compliance) &&
                non_negative(policy.impact_compliance),
            "ContactPolicy: tolerances must be finite and >= 0");
  SB_DEMAND(
      policy.enumeration_unknowns >= 0 && policy.enumeration_unknowns <= lcp::kMaxEnumerationSize,
      "ContactPolicy: enumeration_unknowns outside 0 .. lcp::kMaxEnumerationSize");
}

}  // namespace skewbridge::contact
