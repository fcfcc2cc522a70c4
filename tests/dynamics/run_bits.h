#pragma once
// Bit-for-bit comparison of two runs' results, for the tests whose claim is "the same bits".

#include <gtest/gtest.h>

#include <bit>
#include <cstddef>
#include <cstdint>

#include "solver/dynamics/simulate.h"

namespace skewbridge::dynamics::testing {

/// Sees every free step up to the first event and lets the run go on: with an observer the run
/// takes the general flight loop, which records each step one member at a time and scans its
/// maxima in order (the reference for the deck's record loop). Counts the steps it saw.
class PassThrough final : public FreeStepObserver {
 public:
  bool Step(double, const Eigen::Ref<const Eigen::VectorXd>&, double, double,
            const Eigen::Ref<const Eigen::VectorXd>&, const RunResult&) override {
    ++steps;
    return true;
  }
  long steps = 0;  ///< free steps seen
};

/// The bits of x, so that two doubles compare equal only when they are the same value.
inline std::uint64_t Bits(double x) { return std::bit_cast<std::uint64_t>(x); }

/// Expects two runs' results to have the same bits: status, maxima and their times, end state,
/// corner travels, step and impact counts, the smallest impact separation and every event's time
/// (histories and the ledger aside).
inline void ExpectSameRunBits(const RunResult& a, const RunResult& b) {
  ASSERT_EQ(a.status, b.status);
  ASSERT_EQ(a.max_abs_q.size(), b.max_abs_q.size());
  for (Eigen::Index i = 0; i < a.max_abs_q.size(); ++i) {
    EXPECT_EQ(Bits(a.max_abs_q[i]), Bits(b.max_abs_q[i])) << "max_abs_q " << i;
    EXPECT_EQ(Bits(a.time_of_max_s[i]), Bits(b.time_of_max_s[i])) << "time_of_max_s " << i;
    EXPECT_EQ(Bits(a.q_end[i]), Bits(b.q_end[i])) << "q_end " << i;
    EXPECT_EQ(Bits(a.u_end[i]), Bits(b.u_end[i])) << "u_end " << i;
  }
  ASSERT_EQ(a.max_travel_m.size(), b.max_travel_m.size());
  for (Eigen::Index d = 0; d < a.max_travel_m.size(); ++d) {
    EXPECT_EQ(Bits(a.max_travel_m[d]), Bits(b.max_travel_m[d])) << "max_travel_m " << d;
  }
  EXPECT_EQ(a.impacts, b.impacts);
  EXPECT_EQ(a.free_steps, b.free_steps);
  EXPECT_EQ(a.rk_steps, b.rk_steps);
  EXPECT_EQ(Bits(a.min_impact_separation_s), Bits(b.min_impact_separation_s));
  ASSERT_EQ(a.events.size(), b.events.size());
  for (std::size_t k = 0; k < a.events.size(); ++k) {
    EXPECT_EQ(Bits(a.events[k].t_s), Bits(b.events[k].t_s)) << "event " << k;
  }
}

/// Expects ExpectSameRunBits and, besides, the same detachment, stick, slip and rejected-step
/// counts and the same bits of the energy ledger's input, impact, friction and balance terms.
inline void ExpectSameRunAndLedgerBits(const RunResult& a, const RunResult& b) {
  ExpectSameRunBits(a, b);
  EXPECT_EQ(a.detachments, b.detachments);
  EXPECT_EQ(a.stick_transitions, b.stick_transitions);
  EXPECT_EQ(a.slip_transitions, b.slip_transitions);
  EXPECT_EQ(a.rk_rejected, b.rk_rejected);
  EXPECT_EQ(Bits(a.energy.input_J), Bits(b.energy.input_J));
  EXPECT_EQ(Bits(a.energy.impact_J), Bits(b.energy.impact_J));
  EXPECT_EQ(Bits(a.energy.friction_J), Bits(b.energy.friction_J));
  EXPECT_EQ(Bits(a.energy.balance_error_J), Bits(b.energy.balance_error_J));
}

}  // namespace skewbridge::dynamics::testing
