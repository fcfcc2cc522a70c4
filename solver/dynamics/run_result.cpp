#include "solver/dynamics/run_result.h"

#include <fmt/format.h>

#include <string>

namespace skewbridge::dynamics {

const char* ToString(RunStatus status) {
  switch (status) {
    case RunStatus::kOk:
      return "ok";
    case RunStatus::kPainleve:
      return "painleve";
    case RunStatus::kLcpFailure:
      return "lcp-failure";
    case RunStatus::kStepLimit:
      return "step-limit";
    case RunStatus::kNonFinite:
      return "non-finite";
    case RunStatus::kEventCascade:
      return "event-cascade";
  }
  return "unknown";
}

std::string NonFiniteMessage(double t_before_s, double t_s) {
  return fmt::format(
      "the state (q, u) stopped being finite (or its square overflowed) between t = {:g} s and "
      "t = {:g} s (a load or a stiffness beyond any bridge)",
      t_before_s, t_s);
}

const char* ToString(EventKind kind) {
  switch (kind) {
    case EventKind::kImpact:
      return "impact";
    case EventKind::kPlasticClosure:
      return "plastic-closure";
    case EventKind::kDetachment:
      return "detachment";
    case EventKind::kStick:
      return "stick";
    case EventKind::kSlip:
      return "slip";
  }
  return "unknown";
}

}  // namespace skewbridge::dynamics
