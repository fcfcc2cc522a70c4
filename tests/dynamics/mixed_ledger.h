#pragma once
// The energy ledger of a mixed run (rigid corners struck beside compliant springs), shared by
// the mixed-law and mixed-row tests.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "solver/dynamics/abutment_springs.h"

namespace skewbridge::dynamics::testing {

/// Expects a mixed run whose rigid corners and springs both took energy (impact loss > 0, the
/// springs' hysteresis above 1e-4 of the input) and whose ledger closes to 1e-6 of the input
/// energy; prints the closure for the log.
inline void ExpectMixedLedgerCloses(const LawRun& mixed) {
  const RunResult& r = mixed.run;
  EXPECT_GT(r.energy.impact_J, 0.0);
  EXPECT_GT(mixed.joint_dissipated_J, 1e-4 * r.energy.input_J);
  EXPECT_LT(std::abs(r.energy.balance_error_J), 1e-6 * r.energy.input_J)
      << "input " << r.energy.input_J << " impact " << r.energy.impact_J << " dissipated "
      << mixed.joint_dissipated_J << " stored " << mixed.joint_stored_J;
  std::printf("balance error / input: %.3e\n",
              std::abs(r.energy.balance_error_J) / r.energy.input_J);
}

}  // namespace skewbridge::dynamics::testing
