// A record's run as a stripe of it (dynamics::RunScaledRecord: the record's contact-free response
// traced at 2^-40, scaled to the factor, and the event-driven run from the scaled state at the
// start of the first free step in which a gap may close), for the one-deck model of the
// record-scaling tests (abutments 20 mm away) under the real record NIS090.AT2 at factors with
// and without impacts:
// - recording histories and the energy ledger changes none of its results: maxima and their
//   times, end state, corner travels, counts and events have the bits of the run without them;
// - its history samples are the output grid 0, dt, 2 dt, ... without a gap or a repeat across
//   the restart, and they follow the run at the factor from rest (dynamics::Run) within 1e-9 of
//   the peak until the first impact;
// - the energy ledger, the trace's work over [0, t_s] (quadratic in the factor) and the restarted
//   run's after it, balances: |balance error| within 1e-9 of the input work (a conservation law
//   the stitch breaks by the whole energy at t_s if either part is left out);
// - against dynamics::Run at the same factor: the same status and impact count, the maxima
//   within 1e-12 without impacts, and at a power of two (the record's samples and the linear
//   flow scale exactly) the direct run's bits.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "records/ground_motion.h"
#include "solver/dynamics/run.h"
#include "solver/dynamics/stripes.h"
#include "solver/model/model_file.h"

namespace skewbridge::dynamics {
namespace {

const std::string kDataDir = SKEWBRIDGE_TEST_DATA_DIR;

std::uint64_t Bits(double x) { return std::bit_cast<std::uint64_t>(x); }

// The record along x at `factor`, each sample times the factor as a sweep scales it.
records::SampledExcitation Scaled(const records::GroundMotion& motion, double factor) {
  records::GroundMotion scaled = motion;
  for (double& a : scaled.acc_mps2) a *= factor;
  return records::ToExcitation(scaled);
}

// Whether two runs' results have the same bits (histories and ledger aside).
void ExpectSameBits(const RunResult& a, const RunResult& b) {
  ASSERT_EQ(a.status, b.status);
  ASSERT_EQ(a.max_abs_q.size(), b.max_abs_q.size());
  for (Eigen::Index i = 0; i < a.max_abs_q.size(); ++i) {
    EXPECT_EQ(Bits(a.max_abs_q[i]), Bits(b.max_abs_q[i])) << "max_abs_q " << i;
    EXPECT_EQ(Bits(a.time_of_max_s[i]), Bits(b.time_of_max_s[i])) << "time_of_max_s " << i;
    EXPECT_EQ(Bits(a.q_end[i]), Bits(b.q_end[i])) << "q_end " << i;
    EXPECT_EQ(Bits(a.u_end[i]), Bits(b.u_end[i])) << "u_end " << i;
  }
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

TEST(StripeRun, HistoriesAndLedgerObserveItAndTheLedgerBalancesAcrossTheRestart) {
  const model::ModelFile file = model::ParseModelFile(kDataDir + "/models/one-deck-records.toml");
  const records::GroundMotion motion = records::ReadRecord(kDataDir + "/records/NIS090.AT2");
  const model::Model& model = file.model;
  const records::SampledExcitation trace = Scaled(motion, kStripeTraceFactor);
  const RunPolicies policies;
  model::RunControl plain = file.run;
  plain.method = model::Method::kEventDriven;
  plain.output_interval_s = 0.0;
  plain.energy_ledger = false;
  model::RunControl recorded = plain;
  recorded.output_interval_s = 0.01;
  recorded.energy_ledger = true;
  const int n = model.n_dof();
  int with_impacts = 0, without = 0, powers_of_two = 0;
  for (const double factor : {0.02, 0.05, 0.5, 1.0, 2.7, 4.0, 6.3}) {
    SCOPED_TRACE("factor " + std::to_string(factor));
    const records::SampledExcitation excitation = Scaled(motion, factor);
    const RunResult stripe = RunScaledRecord(model, excitation, trace, factor, plain, policies);
    const RunResult full = RunScaledRecord(model, excitation, trace, factor, recorded, policies);
    ExpectSameBits(full, stripe);

    // The output grid, whole across the restart.
    const Histories& h = full.histories;
    ASSERT_GE(h.t_s.size(), 2u);
    ASSERT_EQ(h.q.size(), h.t_s.size() * static_cast<std::size_t>(n));
    ASSERT_EQ(h.gap_m.size(), h.t_s.size() * static_cast<std::size_t>(model.n_contacts()));
    for (std::size_t k = 0; k < h.t_s.size(); ++k) {
      ASSERT_EQ(h.t_s[k], recorded.output_interval_s * static_cast<double>(k)) << "sample " << k;
    }
    EXPECT_GE(h.t_s.back(), full.end_time_s - recorded.output_interval_s);

    // The ledger stitched over the restart balances.
    const EnergyLedger& e = full.energy;
    ASSERT_TRUE(std::isfinite(e.input_J) && e.input_J > 0.0);
    EXPECT_LE(std::abs(e.balance_error_J), 1e-9 * e.input_J)
        << "input " << e.input_J << ", damping " << e.damping_J << ", impacts " << e.impact_J;

    // The run at the factor from rest.
    const RunResult own = dynamics::Run(model, excitation, recorded, policies);
    ASSERT_EQ(own.status, full.status);
    EXPECT_EQ(own.impacts, full.impacts);
    const double t_first = full.events.empty() ? full.end_time_s + 1.0 : full.events[0].t_s;
    const Histories& g = own.histories;
    ASSERT_EQ(g.t_s.size(), h.t_s.size());
    for (std::size_t k = 0; k < h.t_s.size() && h.t_s[k] < t_first; ++k) {
      for (int i = 0; i < n; ++i) {
        const std::size_t at = k * static_cast<std::size_t>(n) + static_cast<std::size_t>(i);
        EXPECT_LE(std::abs(h.q[at] - g.q[at]), 1e-9 * own.max_abs_q[i])
            << "sample " << k << ", q " << i;
      }
    }
    if (full.impacts == 0) {
      ++without;
      for (int i = 0; i < n; ++i) {
        EXPECT_LE(std::abs(full.max_abs_q[i] - own.max_abs_q[i]), 1e-12 * own.max_abs_q[i]);
      }
    } else {
      ++with_impacts;
    }
    if (factor == 1.0 || factor == 4.0) {
      ++powers_of_two;
      ExpectSameBits(full, own);
    }
  }
  EXPECT_GE(with_impacts, 2);
  EXPECT_GE(without, 2);
  EXPECT_EQ(powers_of_two, 2);
}

}  // namespace
}  // namespace skewbridge::dynamics
