#pragma once
/// @file
/// Where the program's `sweep` command gets the physics: the evaluator for a specification's
/// family (the sweep.family values of jobs::KnownFamilies):
///  - subsystem, pilot-bridge: spectra::SpectraEvaluator, through the spectra mapping;
///  - multi-span: spectra::MultiSpanEvaluator (per-deck maxima and unseating margins);
///  - model-file: spectra::ModelFileEvaluator (a model file with some values replaced per cell).
/// The tests of the sweep machinery bypass this factory with their own evaluator
/// (tests/jobs/test_evaluator.h), which is no family of the program.

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
