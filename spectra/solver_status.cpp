#include "spectra/solver_status.h"

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
  }
  return kStatusStepLimit;  // unreachable: every enumerator is handled above
}

std::vector<std::pair<std::int32_t, std::string>> SolverStatusNames() {
  return {{kStatusPainleve, dynamics::ToString(dynamics::RunStatus::kPainleve)},
          {kStatusLcpFailure, dynamics::ToString(dynamics::RunStatus::kLcpFailure)},
          {kStatusStepLimit, dynamics::ToString(dynamics::RunStatus::kStepLimit)}};
}

}  // namespace skewbridge::spectra
