#include "jobs/evaluator_factory.h"

#include "solver/common/error.h"

namespace skewbridge::jobs {

// The spectra mapping (spectra/) plugs its evaluators in here, one family at a time; until
// then every family is refused before any work.
std::unique_ptr<CellEvaluator> MakeEvaluator(const SweepSpec& spec) {
  throw InputError::AtField(spec.source, "sweep.family",
                            "this build of skewbridge cannot evaluate family '" + spec.family +
                                "' yet (no evaluator is linked for it)");
}

}  // namespace skewbridge::jobs
