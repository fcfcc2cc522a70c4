#pragma once
/// @file
/// The sweep machinery's names for the cell interface, which spectra owns (spectra/cell.h):
/// the scheduler, the transport and the cube speak of cells, never of decks.

#include "spectra/cell.h"

namespace skewbridge::jobs {

using spectra::CellEvaluator;
using spectra::CellOutcome;
using spectra::CellStats;
using spectra::CheckResponseCount;
using spectra::kStatusException;
using spectra::kStatusNotDone;
using spectra::kStatusOk;
using spectra::kStatusResponseCount;
using spectra::RecordScaling;
using spectra::ResponseInfo;

}  // namespace skewbridge::jobs
