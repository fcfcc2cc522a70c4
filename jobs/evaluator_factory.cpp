#include "jobs/evaluator_factory.h"

#include "spectra/ida.h"
#include "spectra/limit_states.h"
#include "spectra/model_file_evaluator.h"
#include "spectra/multispan_evaluator.h"
#include "spectra/spectra_evaluator.h"

namespace skewbridge::jobs {

namespace {

std::unique_ptr<CellEvaluator> FamilyEvaluator(const SweepSpec& spec) {
  if (spec.family == "multi-span") return std::make_unique<spectra::MultiSpanEvaluator>(spec);
  if (spec.family == "model-file") return std::make_unique<spectra::ModelFileEvaluator>(spec);
  return std::make_unique<spectra::SpectraEvaluator>(spec);
}

}  // namespace

std::unique_ptr<CellEvaluator> MakeEvaluator(const SweepSpec& spec) {
  std::unique_ptr<CellEvaluator> family = FamilyEvaluator(spec);
  if (spec.limit_states.empty()) return family;
  auto limit_states = std::make_unique<spectra::LimitStateEvaluator>(std::move(family), spec);
  if (!spec.ida.enabled) return limit_states;
  return std::make_unique<spectra::IdaEvaluator>(std::move(limit_states), spec);
}

}  // namespace skewbridge::jobs
