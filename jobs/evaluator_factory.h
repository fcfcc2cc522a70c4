#pragma once
/// @file
/// Where the program's `sweep` command gets the physics: the evaluator for a specification's
/// family (subsystem, pilot-bridge, model-file), built by the spectra mapping.

#include <memory>

#include "jobs/cell.h"
#include "jobs/sweep_spec.h"

namespace skewbridge::jobs {

/// The evaluator of `spec`. This is also the hook for cross-field rules that need physics
/// (eta0 with a = 0, required parameters per family, record labels present in the set): they
/// throw here, before the output file is touched.
/// @throws InputError naming the field, for a family or a combination it cannot evaluate.
std::unique_ptr<CellEvaluator> MakeEvaluator(const SweepSpec& spec);

}  // namespace skewbridge::jobs
