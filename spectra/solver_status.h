#pragma once
/// @file
/// One mapping from the solver's run status to the status code a cube stores per cell, shared
/// by every evaluator that runs the deck solver, so a code means the same in every cube.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "solver/common/excitation.h"
#include "solver/dynamics/run_result.h"
#include "solver/model/model.h"
#include "solver/model/model_file.h"

namespace skewbridge::spectra {

/// Cell status codes of a solver run (0 is ok; spectra/cell.h reserves the negative ones).
enum SolverStatus : std::int32_t {
  kStatusPainleve = 1,      ///< the contact problem had no consistent forces
  kStatusLcpFailure = 2,    ///< an LCP hit its pivot limit or had invalid input
  kStatusStepLimit = 3,     ///< the run did not reach its end time within its step budget
  kStatusNonFinite = 4,     ///< the state stopped being finite (NaN or Inf)
  kStatusEventCascade = 5,  ///< the mode decision did not settle at one instant
};

/// The cell status of a run that ended with `status`.
std::int32_t CellStatusOf(dynamics::RunStatus status);

/// The names of the SolverStatus codes, as CellEvaluator::StatusNames returns them.
std::vector<std::pair<std::int32_t, std::string>> SolverStatusNames();

}  // namespace skewbridge::spectra
