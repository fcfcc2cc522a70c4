// The hyperbolic backfill law against the table of its source, its closed forms, the Shamsabadi
// and Caltrans conveniences, and an incremental trial / commit re-statement of the OpenSees
// HyperbolicGapMaterial algorithm (strain increments, stress clipped at zero).
#include "solver/joint/backfill.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "solver/common/error.h"

namespace skewbridge::joint {
namespace {

// Wilson and Elgamal's constants per metre of backwall width (the OpenSees manual's recommended
// values for a 1.68 m backwall): K_max = K_ur = 20 300 kN/m/m, R_f = 0.7, F_ult = 326 kN/m,
// gap 25.4 mm.
HyperbolicGap WilsonElgamalPerMetre() {
  HyperbolicGap law;
  law.k_max_N_per_m = 20300e3;
  law.k_ur_N_per_m = 20300e3;
  law.r_f = 0.7;
  law.f_ult_N = 326e3;
  law.gap_m = 0.0254;
  return law;
}

TEST(Backfill, ReproducesTheSourceTableBeyondTheGap) {
  const HyperbolicGap law = WilsonElgamalPerMetre();
  const BackfillState fresh;
  // The table gives kN/m rounded to 1 kN/m at 7.6, 25.4 and 76.4 mm beyond the gap.
  const double d_m[] = {0.0076, 0.0254, 0.0764};
  const double table_kN[] = {116.0, 245.0, 358.0};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(BackfillForce_N(law, fresh, law.gap_m + d_m[i]) / 1e3, table_kN[i], 0.5)
        << "d = " << d_m[i];
  }
  // Closed before the gap: nothing.
  EXPECT_EQ(BackfillForce_N(law, fresh, 0.0), 0.0);
  EXPECT_EQ(BackfillForce_N(law, fresh, 0.999 * law.gap_m), 0.0);
  EXPECT_EQ(BackfillForce_N(law, fresh, -0.1), 0.0);
}

TEST(Backfill, EnvelopeHasNoCapWhenTheFailureRatioIsBelowOne) {
  const HyperbolicGap law = WilsonElgamalPerMetre();
  // It passes F_ult at d = F_ult / (K_max (1 - R_f)) = 53.5 mm and tends to F_ult / R_f.
  const double d_ult = law.f_ult_N / (law.k_max_N_per_m * (1.0 - law.r_f));
  EXPECT_NEAR(d_ult, 0.05353, 1e-5);
  EXPECT_NEAR(EnvelopeForce_N(law, d_ult), law.f_ult_N, 1e-6 * law.f_ult_N);
  EXPECT_GT(EnvelopeForce_N(law, 2.0 * d_ult), law.f_ult_N);
  EXPECT_NEAR(EnvelopeForce_N(law, 1e6), law.f_ult_N / law.r_f, 1e-3 * law.f_ult_N);
  EXPECT_LT(EnvelopeForce_N(law, 1e6), law.f_ult_N / law.r_f);
  // The tangent: K_max at the gap, the derivative of the envelope (central difference) beyond.
  EXPECT_NEAR(EnvelopeTangent_N_per_m(law, 1e-12), law.k_max_N_per_m, 1e-6 * law.k_max_N_per_m);
  const double d = 0.03, h = 1e-7;
  const double slope = (EnvelopeForce_N(law, d + h) - EnvelopeForce_N(law, d - h)) / (2.0 * h);
  EXPECT_NEAR(EnvelopeTangent_N_per_m(law, d), slope, 1e-6 * slope);
}

// The OpenSees algorithm restated in compression-positive strains: envelope while the trial
// strain passes the committed extreme; otherwise the committed force plus K_ur times the
// increment, cut at zero, with the reloading strain fixed when unloading leaves the envelope.
class IncrementalHyperbolicGap {
 public:
  explicit IncrementalHyperbolicGap(const HyperbolicGap& law) : law_(law) {}
  double Trial(double u_m) {
    const double du = u_m - u_c_;
    if (u_m >= u_min_c_) {
      u_min_t_ = u_m;
      f_t_ = EnvelopeForce_N(law_, u_m - law_.gap_m);
    } else if (du < 0.0) {  // unloading
      if (u_min_t_ == u_c_) reload_at_ = u_min_t_ - f_c_ / law_.k_ur_N_per_m;
      f_t_ = std::max(0.0, f_c_ + law_.k_ur_N_per_m * du);
    } else if (du > 0.0) {  // reloading
      f_t_ = f_c_ + law_.k_ur_N_per_m * du;
      if (u_m > reload_at_ && f_c_ == 0.0) f_t_ = law_.k_ur_N_per_m * (u_m - reload_at_);
      if (u_m < reload_at_) f_t_ = 0.0;
    }
    u_t_ = u_m;
    return f_t_;
  }
  void Commit() {
    u_c_ = u_t_;
    f_c_ = f_t_;
    u_min_c_ = u_min_t_;
  }

 private:
  HyperbolicGap law_;
  double u_c_ = 0.0, f_c_ = 0.0, u_t_ = 0.0, f_t_ = 0.0;
  double u_min_c_ = 0.0, u_min_t_ = 0.0, reload_at_ = 0.0;
};

TEST(Backfill, AgreesWithTheIncrementalAlgorithmOverCycles) {
  HyperbolicGap law = WilsonElgamalPerMetre();
  law.k_ur_N_per_m = 1.5 * law.k_max_N_per_m;
  // Excursions of growing and shrinking amplitude, partial unloadings, returns into the gap.
  const std::vector<double> turns_m = {0.0,   0.040, 0.030, 0.045, 0.0,   0.060, 0.058,
                                       0.070, 0.010, 0.065, 0.030, 0.090, 0.020};
  IncrementalHyperbolicGap reference(law);
  BackfillState state;
  int compared = 0;
  for (std::size_t k = 1; k < turns_m.size(); ++k) {
    const int steps = 400;
    for (int i = 1; i <= steps; ++i) {
      const double u = turns_m[k - 1] + (turns_m[k] - turns_m[k - 1]) * i / steps;
      const double expected = reference.Trial(u);
      const double force = BackfillForce_N(law, state, u);
      ASSERT_NEAR(force, expected, 1e-6 * law.f_ult_N) << "segment " << k << " u = " << u;
      reference.Commit();
      state = BackfillCommit(law, state, u);
      ++compared;
    }
  }
  EXPECT_EQ(compared, 12 * 400);
}

TEST(Backfill, PermanentSetWidensTheGapAfterEachExcursion) {
  const HyperbolicGap law = WilsonElgamalPerMetre();
  BackfillState state;
  EXPECT_EQ(PermanentSet_m(law, state), 0.0);
  const double d1 = 0.0254;
  state = BackfillCommit(law, state, law.gap_m + d1);
  const double set1 = PermanentSet_m(law, state);
  // d_set = d_max - F(d_max) / K_ur = 25.4 mm - 244.7 kN / 20 300 kN/m = 13.35 mm.
  EXPECT_NEAR(set1, d1 - EnvelopeForce_N(law, d1) / law.k_ur_N_per_m, 1e-15);
  EXPECT_NEAR(set1, 0.01335, 1e-5);
  // Open up to the set, the line above it, the envelope again past the peak.
  EXPECT_EQ(BackfillForce_N(law, state, law.gap_m + 0.99 * set1), 0.0);
  EXPECT_EQ(BackfillBranchAt(law, state, law.gap_m + 0.99 * set1), BackfillBranch::kOpen);
  const double mid = 0.5 * (set1 + d1);
  EXPECT_EQ(BackfillBranchAt(law, state, law.gap_m + mid), BackfillBranch::kLine);
  EXPECT_NEAR(BackfillForce_N(law, state, law.gap_m + mid), law.k_ur_N_per_m * (mid - set1), 1e-6);
  EXPECT_NEAR(BackfillTangent_N_per_m(law, state, law.gap_m + mid), law.k_ur_N_per_m, 0.0);
  EXPECT_EQ(BackfillBranchAt(law, state, law.gap_m + 1.01 * d1), BackfillBranch::kEnvelope);
  // Committing a smaller excursion keeps the memory; a larger one widens the set.
  EXPECT_EQ(BackfillCommit(law, state, law.gap_m + mid).d_max_m, d1);
  state = BackfillCommit(law, state, law.gap_m + 0.05);
  EXPECT_GT(PermanentSet_m(law, state), set1);
}

TEST(Backfill, ShamsabadiFormPassesItsTwoPoints) {
  // PyPBEE's Bridge_A: K50 = 969.6 kip/in, F_ult = 452.9 kip, backwall 4.64 ft high.
  const double kip = 4448.2216152605, inch = 0.0254, foot = 0.3048;
  const double k50 = 969.6 * kip / inch, f_ult = 452.9 * kip;
  const double y_max = ShamsabadiYMax_m(4.64 * foot);
  EXPECT_NEAR(y_max / inch, 0.05 * 4.64 * 12.0, 1e-12);
  const HyperbolicGap law = FromShamsabadi(k50, f_ult, y_max, inch, "bridge_a");
  EXPECT_NEAR(EnvelopeForce_N(law, y_max), f_ult, 1e-9 * f_ult);
  const double y50 = f_ult / (2.0 * k50);  // where the secant is K50 at half the capacity
  EXPECT_NEAR(EnvelopeForce_N(law, y50), 0.5 * f_ult, 1e-9 * f_ult);
  EXPECT_EQ(law.k_ur_N_per_m, law.k_max_N_per_m);
  EXPECT_GT(law.r_f, 0.0);
  EXPECT_LT(law.r_f, 1.0);
  EXPECT_THROW(FromShamsabadi(f_ult / y_max, f_ult, y_max, 0.0, "bridge_a"), InputError);
  EXPECT_THROW(FromShamsabadi(-1.0, f_ult, y_max, 0.0, "bridge_a"), InputError);
}

TEST(Backfill, CaltransRulesMeetTheOlderPerFootValuesAtTheReferenceHeight) {
  // At h = 5.5 ft the SDC 2.0 rules give w (5.5 * 5.5 + 20) = 50.25 w kip/in and
  // w 5.5 * 5.5^2.5 / 14.035 = 27.80 w kip: the older SDC values 50 kip/in per ft of width and
  // 5 ksf over the 5.5 ft wall (27.5 kip per ft), within 0.5 % and 1.1 %.
  const double kip = 4448.2216152605, inch = 0.0254, foot = 0.3048;
  const double w_ft = 10.0;
  const CaltransAbutment a = CaltransSdc2(w_ft * foot, 5.5 * foot, 1.0);
  EXPECT_NEAR(a.k_initial_N_per_m / (kip / inch) / w_ft, 50.0, 0.25);
  EXPECT_NEAR(a.p_bw_N / kip / w_ft, 27.5, 0.31);
  EXPECT_NEAR(a.k_initial_N_per_m / (kip / inch), 502.5, 1e-9);
  // Skew: R_sk = exp(-theta / 45 deg) scales both; e^-1 at 45 deg.
  const double r45 = CaltransSkewFactor(std::numbers::pi / 4.0);
  EXPECT_NEAR(r45, std::exp(-1.0), 1e-15);
  EXPECT_EQ(CaltransSkewFactor(0.0), 1.0);
  const CaltransAbutment skewed = CaltransSdc2(w_ft * foot, 5.5 * foot, r45);
  EXPECT_NEAR(skewed.p_bw_N, r45 * a.p_bw_N, 1e-9 * a.p_bw_N);
  // The envelope from them: K_max at the gap and P_bw at y_max = 0.05 h.
  const double y_max = ShamsabadiYMax_m(5.5 * foot);
  const HyperbolicGap law =
      FromInitialStiffness(a.k_initial_N_per_m, a.p_bw_N, y_max, 0.0, "caltrans");
  EXPECT_NEAR(EnvelopeForce_N(law, y_max), a.p_bw_N, 1e-9 * a.p_bw_N);
  EXPECT_NEAR(EnvelopeTangent_N_per_m(law, 1e-15), a.k_initial_N_per_m, 1e-6 * a.k_initial_N_per_m);
}

TEST(Backfill, RefusesConstantsOutsideTheirRanges) {
  HyperbolicGap law = WilsonElgamalPerMetre();
  EXPECT_NO_THROW(ValidateHyperbolicGap(law, "m.toml"));
  law.r_f = 1.2;
  try {
    ValidateHyperbolicGap(law, "m.toml");
    FAIL() << "r_f = 1.2 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("r_f"), std::string::npos) << e.what();
  }
  law = WilsonElgamalPerMetre();
  law.gap_m = -0.01;
  EXPECT_THROW(ValidateHyperbolicGap(law, "m.toml"), InputError);
}

}  // namespace
}  // namespace skewbridge::joint
