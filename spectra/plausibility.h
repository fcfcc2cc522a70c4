#pragma once
/// @file
/// Plausibility warnings of a sweep's grid (solver/model/plausibility.h for the limits): seat
/// widths relative to the span above a tenth, intensities above 5 g. The model-file family adds
/// those of its bridge (CellEvaluator::Warnings). Warnings, never errors: the program prints
/// them and goes on.

#include <string>
#include <vector>

#include "spectra/grid.h"

namespace skewbridge::spectra {

/// The warnings of `grid` itself, one line each, "SPEC: KEY: ...": a seat_over_L above 0.1 (a
/// seat_m above a tenth of the pilot bridge's span), an im_g above 5 g.
std::vector<std::string> GridWarnings(const CellGrid& grid);

}  // namespace skewbridge::spectra
