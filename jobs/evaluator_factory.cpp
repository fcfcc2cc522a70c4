#include "jobs/evaluator_factory.h"

#include "jobs/model_file_evaluator.h"
#include "jobs/multispan_evaluator.h"
#include "jobs/spectra_evaluator.h"

namespace skewbridge::jobs {

std::unique_ptr<CellEvaluator> MakeEvaluator(const SweepSpec& spec) {
  if (spec.family == "multi-span") return std::make_unique<MultiSpanEvaluator>(spec);
  if (spec.family == "model-file") return std::make_unique<ModelFileEvaluator>(spec);
  return std::make_unique<SpectraEvaluator>(spec);
}

}  // namespace skewbridge::jobs
