#pragma once
// Checks shared by the mixed-law and mixed-row tests: a mixed run's energy ledger (rigid corners
// struck beside compliant springs) and its maxima against another integrator's to a tolerance.

#include <gtest/gtest.h>

#include <algorithm>
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

/// Expects every max|q_i| of `a` within rel_tol of `b`'s, relative to `b`'s (runs of two
/// integrators whose step controls differ agree to their Runge-Kutta tolerance's order, not to
/// the bit); returns the largest relative difference, for the log.
inline double ExpectMaximaWithin(const RunResult& a, const RunResult& b, double rel_tol) {
  double worst = 0.0;
  for (int i = 0; i < b.max_abs_q.size(); ++i) {
    const double x = a.max_abs_q[i], y = b.max_abs_q[i];
    worst = std::max(worst, std::abs(x - y) / y);
    EXPECT_NEAR(x, y, rel_tol * y) << "dof " << i;
  }
  return worst;
}

}  // namespace skewbridge::dynamics::testing
