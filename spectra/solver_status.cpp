#include "spectra/solver_status.h"

#include "solver/dynamics/simulate.h"
#include "spectra/cell.h"

namespace skewbridge::spectra {

std::int32_t CellStatusOf(dynamics::RunStatus status) {
  switch (status) {
    case dynamics::RunStatus::kOk:
      return kStatusOk;
    case dynamics::RunStatus::kPainleve:
      return kStatusPainleve;
    case dynamics::RunStatus::kLcpFailure:
      return kStatusLcpFailure;
    case dynamics::RunStatus::kStepLimit:
      return kStatusStepLimit;
    case dynamics::RunStatus::kNonFinite:
      return kStatusNonFinite;
    case dynamics::RunStatus::kEventCascade:
      return kStatusEventCascade;
  }
  return kStatusStepLimit;  // unreachable: every enumerator is handled above
}

std::vector<std::pair<std::int32_t, std::string>> SolverStatusNames() {
  return {{kStatusPainleve, dynamics::ToString(dynamics::RunStatus::kPainleve)},
          {kStatusLcpFailure, dynamics::ToString(dynamics::RunStatus::kLcpFailure)},
          {kStatusStepLimit, dynamics::ToString(dynamics::RunStatus::kStepLimit)},
          {kStatusNonFinite, dynamics::ToString(dynamics::RunStatus::kNonFinite)},
          {kStatusEventCascade, dynamics::ToString(dynamics::RunStatus::kEventCascade)}};
}

}  // namespace skewbridge::spectra
