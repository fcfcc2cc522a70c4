// Two horizontal components at an incidence angle (docs/theory.md §2): the rotation of a pair
// against the one-component excitation it must reduce to, sample by sample and run by run, and
// the analytic facts of docs/theory.md §4 under a transverse-only component.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "records/ground_motion.h"
#include "records/incidence.h"
#include "records/measures.h"
#include "solver/common/error.h"
#include "solver/dynamics/run.h"
#include "solver/model/builders.h"
#include "solver/model/model_file.h"
#include "spectra/model_file_evaluator.h"

namespace skewbridge::spectra::incidence_test {
namespace {

constexpr double kPi = std::numbers::pi;

// The first `seconds` of the Loma Prieta record of the test data (dt = 0.005 s).
records::GroundMotion Record(double seconds) {
  records::GroundMotion m = records::ReadRecord(std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) /
                                                "records" / "RSN763_LOMAP_GIL067.AT2");
  m.acc_mps2.resize(static_cast<std::size_t>(seconds / m.dt_s) + 1);
  return m;
}

// A motion of the same dt and length as `like`, every sample zero.
records::GroundMotion Zero(const records::GroundMotion& like) {
  records::GroundMotion z = like;
  z.file = "zero";
  std::fill(z.acc_mps2.begin(), z.acc_mps2.end(), 0.0);
  return z;
}

// A second component: the record read backwards (the same dt, length and scale).
records::GroundMotion Reversed(const records::GroundMotion& like) {
  records::GroundMotion r = like;
  r.file = "reversed";
  std::reverse(r.acc_mps2.begin(), r.acc_mps2.end());
  return r;
}

// The pilot bridge of docs/examples/pilot-bridge.toml with both gaps `gap_m`.
model::Model PilotBridge(double gap_m) {
  model::DeckSpec spec = model::ParseModelFile(std::string(SKEWBRIDGE_TEST_DATA_DIR) +
                                               "/../../docs/examples/pilot-bridge.toml")
                             .deck;
  spec.gap_plus_m = spec.gap_minus_m = gap_m;
  return model::BuildDeckModel(spec);
}

// The subsystem: a uniform deck of L = 30 m at skew a (deg) and skew ratio eta0, uncoupled
// substructure w0x = w0y = W0 = 2 pi rad/s, both abutments at `gap_m`, frictionless.
model::Model Subsystem(double a_deg, double eta0, double gap_m) {
  model::DeckSpec spec;
  spec.mass_kg = 1.0e5;
  const double a = a_deg * kPi / 180.0;
  spec.geometry = {30.0, a == 0.0 ? 6.0 : model::WidthFromEta0(eta0, a, 30.0), a};
  spec.w0x_radps = spec.w0y_radps = spec.W0_radps = 2.0 * kPi;
  spec.abutments = model::AbutmentSet::kBoth;
  spec.gap_plus_m = spec.gap_minus_m = gap_m;
  spec.restitution = 0.5;
  spec.friction = 0.0;
  return model::BuildDeckModel(spec);
}

model::RunControl Control(double end_s) {
  model::RunControl control;
  control.end_time_s = end_s;
  control.energy_ledger = false;
  return control;
}

// Every sample of both columns, the empty y column of a motion along x read as zeros.
void ExpectSameSamples(const records::SampledExcitation& a, const records::SampledExcitation& b) {
  ASSERT_EQ(a.dt_s(), b.dt_s());
  ASSERT_EQ(a.ax_mps2().size(), b.ax_mps2().size());
  for (std::size_t k = 0; k < a.ax_mps2().size(); ++k) {
    const double ay = a.ay_mps2().empty() ? 0.0 : a.ay_mps2()[k];
    const double by = b.ay_mps2().empty() ? 0.0 : b.ay_mps2()[k];
    ASSERT_EQ(a.ax_mps2()[k], b.ax_mps2()[k]) << "sample " << k;
    ASSERT_EQ(ay, by) << "sample " << k;
  }
}

// Bit for bit: maxima, counts and status.
void ExpectSameRun(const dynamics::RunResult& a, const dynamics::RunResult& b) {
  ASSERT_EQ(a.status, b.status);
  EXPECT_EQ(a.impacts, b.impacts);
  EXPECT_EQ(a.events.size(), b.events.size());
  for (int i = 0; i < a.max_abs_q.size(); ++i) EXPECT_EQ(a.max_abs_q(i), b.max_abs_q(i)) << i;
  for (int i = 0; i < a.max_travel_m.size(); ++i) {
    EXPECT_EQ(a.max_travel_m(i), b.max_travel_m(i)) << i;
  }
}

TEST(Incidence, PairAlongH1AloneIsTheSingleRecordAlongTheAngleBitForBit) {
  const records::GroundMotion a = Record(12.0);
  const records::GroundMotion zero = Zero(a);
  const model::Model bridge = PilotBridge(0.004);
  for (const double alpha : {0.0, 30.0, 90.0, 137.5, -60.0}) {
    for (const double factor : {1.0, 1.7}) {
      SCOPED_TRACE("alpha = " + std::to_string(alpha) + ", factor = " + std::to_string(factor));
      const records::SampledExcitation pair = ScaledPairExcitation(a, zero, factor, alpha);
      const records::SampledExcitation single =
          ScaledRecordExcitation(a, factor, records::DirectionAt(alpha));
      ExpectSameSamples(pair, single);
      if (factor != 1.0 || alpha == 137.5) continue;  // the runs: three angles are enough
      const dynamics::RunResult p = dynamics::Run(bridge, pair, Control(14.0));
      const dynamics::RunResult s = dynamics::Run(bridge, single, Control(14.0));
      EXPECT_GT(s.impacts, 5);
      ExpectSameRun(p, s);
    }
  }
}

// The samples agree to their rounding (1e-15 of the peak). A run without contacts is linear in
// them and keeps 1e-12; with pounding each impact's time moves with the samples' last bit and the
// maxima agree to 3.3e-12 (measured at alpha = 100 deg, 14 s with 20-odd impacts), checked at
// 1e-10.
TEST(Incidence, EqualComponentsAreOneRecordRootTwoLargerAt45DegreesMore) {
  const records::GroundMotion a = Record(12.0);
  const model::Model free_deck = PilotBridge(1e3);
  const model::Model pounding = PilotBridge(0.004);
  for (const double alpha : {0.0, 20.0, 100.0}) {
    SCOPED_TRACE("alpha = " + std::to_string(alpha));
    const records::SampledExcitation pair = ScaledPairExcitation(a, a, 1.0, alpha);
    const records::SampledExcitation single =
        ScaledRecordExcitation(a, std::sqrt(2.0), records::DirectionAt(alpha + 45.0));
    const double pga =
        *std::max_element(a.acc_mps2.begin(), a.acc_mps2.end(),
                          [](double u, double v) { return std::abs(u) < std::abs(v); });
    for (std::size_t k = 0; k < a.npts(); ++k) {
      ASSERT_NEAR(pair.ax_mps2()[k], single.ax_mps2()[k], 1e-15 * std::abs(pga)) << k;
      ASSERT_NEAR(pair.ay_mps2()[k], single.ay_mps2()[k], 1e-15 * std::abs(pga)) << k;
    }
    for (const model::Model* bridge : {&free_deck, &pounding}) {
      const bool contacts = bridge == &pounding;
      SCOPED_TRACE(contacts ? "pounding" : "gaps never close");
      const dynamics::RunResult p = dynamics::Run(*bridge, pair, Control(14.0));
      const dynamics::RunResult s = dynamics::Run(*bridge, single, Control(14.0));
      ASSERT_EQ(p.status, dynamics::RunStatus::kOk);
      ASSERT_EQ(s.status, dynamics::RunStatus::kOk);
      EXPECT_EQ(p.impacts, s.impacts);
      if (contacts) {
        EXPECT_GT(s.impacts, 5);
      }
      const double tolerance = contacts ? 1e-10 : 1e-12;
      for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(p.max_abs_q(i), s.max_abs_q(i), tolerance * std::abs(s.max_abs_q(i))) << i;
      }
    }
  }
}

TEST(Incidence, ThePairMustShareDtAndLength) {
  const records::GroundMotion a = Record(2.0);
  records::GroundMotion b = Reversed(a);
  b.dt_s = 0.01;
  EXPECT_THROW(ScaledPairExcitation(a, b, 1.0, 0.0), InputError);
  b = Reversed(a);
  b.acc_mps2.pop_back();
  EXPECT_THROW(ScaledPairExcitation(a, b, 1.0, 0.0), InputError);
  EXPECT_THROW(ScaledPairExcitation(a, Reversed(a), 1.0, std::nan("")), InputError);
  // The rotation as written: a_x = a1 cos - a2 sin, a_y = a1 sin + a2 cos at 90 deg.
  const records::SampledExcitation turned = ScaledPairExcitation(a, Reversed(a), 1.0, 90.0);
  const std::size_t k = a.npts() / 3;
  EXPECT_NEAR(turned.ax_mps2()[k], -Reversed(a).acc_mps2[k], 1e-15);
  EXPECT_NEAR(turned.ay_mps2()[k], a.acc_mps2[k], 1e-15);
}

// docs/theory.md §4 fact 1 under a transverse-only component (H2 alone at incidence 0): the
// frictionless deck translates into an abutment with both corners of one end, so it leaves
// without rotation exactly when eta0 <= 1; at eta0 > 1 the same motion turns it.
TEST(Incidence, TransverseOnlyComponentTurnsTheFrictionlessDeckOnlyAboveEta0One) {
  const records::GroundMotion a = Record(12.0);
  const records::SampledExcitation transverse = ScaledPairExcitation(Zero(a), a, 1.0, 0.0);
  for (const double eta0 : {0.5, 1.0, 2.0}) {
    SCOPED_TRACE("eta0 = " + std::to_string(eta0));
    const model::Model deck = Subsystem(30.0, eta0, 0.01);
    const dynamics::RunResult r = dynamics::Run(deck, transverse, Control(14.0));
    ASSERT_EQ(r.status, dynamics::RunStatus::kOk);
    EXPECT_GT(r.impacts, 0);
    const double rho = std::sqrt(deck.body(0).inertia_kgm2 / deck.body(0).mass_kg);
    const double turn = r.max_abs_q(2) * rho / r.max_abs_q(1);  // rotation's corner over y_m
    if (eta0 <= 1.0) {
      EXPECT_LT(turn, 1e-12);
    } else {
      EXPECT_GT(turn, 1e-2);
    }
  }
}

// docs/theory.md §4 fact 3 under a transverse-only component: at a = 0 the gaps lie along x and
// never close, x and theta stay zero, and y is the linear oscillator of w0y and xi, whose peak
// over the samples the Nigam-Jennings recurrence gives independently (records/measures.h).
TEST(Incidence, TransverseOnlyComponentAtZeroSkewIsTheLinearOscillatorAcross) {
  const records::GroundMotion a = Record(12.0);
  const model::Model deck = Subsystem(0.0, 0.0, 0.002);
  for (const double alpha : {0.0, 90.0}) {
    // H2 alone at 0 deg, or H1 alone at 90 deg: both a purely transverse ground motion.
    const records::SampledExcitation transverse =
        alpha == 0.0 ? ScaledPairExcitation(Zero(a), a, 1.0, alpha)
                     : ScaledPairExcitation(a, Zero(a), 1.0, alpha);
    const dynamics::RunResult r = dynamics::Run(deck, transverse, Control(12.0));
    ASSERT_EQ(r.status, dynamics::RunStatus::kOk);
    EXPECT_EQ(r.impacts, 0);
    EXPECT_LT(r.max_abs_q(0), 1e-15 * r.max_abs_q(1));  // cos 90 deg is 6e-17, not 0
    EXPECT_LT(r.max_abs_q(2), 1e-15);
    const double w = 2.0 * kPi;
    const std::vector<double> period{2.0 * kPi / w};
    std::vector<double> ay = transverse.ay_mps2();
    const double sd = records::PseudoAccelerationSpectrum(ay, a.dt_s, period, 0.05)[0] / (w * w);
    // The samples' peak is below the continuous one by at most (w dt)^2 / 4 of it.
    EXPECT_GE(r.max_abs_q(1), sd * (1.0 - 1e-12));
    EXPECT_LE(r.max_abs_q(1), sd * (1.0 + (w * a.dt_s) * (w * a.dt_s) / 4.0));
  }
}

}  // namespace
}  // namespace skewbridge::spectra::incidence_test
