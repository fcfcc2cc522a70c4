#include "jobs/evaluator_factory.h"

#include "jobs/spectra_evaluator.h"

namespace skewbridge::jobs {

std::unique_ptr<CellEvaluator> MakeEvaluator(const SweepSpec& spec) {
  return std::make_unique<SpectraEvaluator>(spec);
}

}  // namespace skewbridge::jobs
