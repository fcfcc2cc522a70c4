// The acceleration-level contact problem through the contact layer: a deck held against the
// +x abutment by a constant force, against the static balance of the two corner forces (closed
// form); a tangential push below / above mu lambda_N sticks / slides with the closed-form
// sliding acceleration; a Painleve configuration is reported, not answered.
#include "solver/contact/contact_problem.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <new>
#include <vector>

#include "solver/contact/impact_problem.h"
#include "tests/contact/test_models.h"

namespace skewbridge::contact {
namespace {

using testing::kDeg;

struct Resting {
  model::Model model;
  ContactKinematics kin;
  Eigen::Vector2d n, t;
  model::LeverArms arms;
};

// The deck at rest against the +x abutment (x = delta, theta = 0, u = 0).
Resting RestingDeck(double a_deg, double eta0, double mu) {
  Resting r{testing::FreeDeck(a_deg, eta0, 20.0, 0.04, 0.5, mu, model::AbutmentSet::kPlusX, 1000.0),
            {},
            {},
            {},
            {}};
  r.kin.Resize(r.model);
  Evaluate(r.model, Eigen::Vector3d(0.04, 0.0, 0.0), Eigen::Vector3d::Zero(), r.kin);
  const double a = a_deg * kDeg;
  r.n = {-std::cos(a), std::sin(a)};
  r.t = {std::sin(a), std::cos(a)};
  r.arms = model::ComputeLeverArms(r.model.body(0).geometry);
  return r;
}

TEST(ContactProblem, NormalForcesEqualTheStaticBalanceOfAPushedDeck) {
  // Push F_n into the face (along -n) and a moment M_z: the corner forces balance
  //   lambda_1 + lambda_2 = F_n,  r_1 lambda_1 + r_2 lambda_2 + M_z = 0.
  for (double a_deg : {20.0, 30.0, 45.0}) {
    for (double eta0 : {0.6, 1.48}) {
      for (double mu : {0.0, 0.3}) {
        Resting r = RestingDeck(a_deg, eta0, mu);
        const double F_n = 5e4;
        // Choose lambda_1 = 0.3 F_n, lambda_2 = 0.7 F_n and the moment that makes them so.
        const double M_z = -(0.3 * r.arms.r1_m + 0.7 * r.arms.r2_m) * F_n;
        Eigen::Vector3d h;
        h << -F_n * r.n, M_z;
        ContactProblem problem(r.model);
        ContactResult res = problem.MakeResult();
        const std::vector<ClosedContact> closed{{0, 0}, {1, 0}};
        ASSERT_EQ(problem.Solve(r.kin, closed, h, res), ContactStatus::kSolved);
        EXPECT_NEAR(res.lambda_N(0), 0.3 * F_n, 1e-9 * F_n);
        EXPECT_NEAR(res.lambda_N(1), 0.7 * F_n, 1e-9 * F_n);
        EXPECT_LT(res.du_dt.norm(), 1e-12 * F_n / 1000.0);
        EXPECT_NEAR(res.lambda_T(0) + res.lambda_T(1), 0.0, 1e-9 * F_n);
        for (int j = 0; j < 2; ++j) {
          EXPECT_EQ(res.outcome[j], ContactOutcome::kSticks);
        }
      }
    }
  }
}

TEST(ContactProblem, TangentialPushBelowTheConeSticksAndAboveSlides) {
  const double mu = 0.3;
  const double F_n = 1e4;
  for (double ratio : {0.5, 0.9, 1.1, 2.0}) {
    for (double direction : {1.0, -1.0}) {
      Resting r = RestingDeck(30.0, 1.2, mu);
      const double F_t = direction * ratio * mu * F_n;
      const bool slides = ratio > 1.0;
      // Friction resists with -F_t when sticking and -mu F_n sign(F_t) when sliding; the
      // moment is set so that the normal forces are equal: lambda_1 = lambda_2 = F_n / 2.
      const double friction_total = slides ? -direction * mu * F_n : -F_t;
      const double M_z = -(0.5 * F_n * (r.arms.r1_m + r.arms.r2_m) + r.arms.rT_m * friction_total);
      Eigen::Vector3d h;
      h << -F_n * r.n + F_t * r.t, M_z;
      ContactProblem problem(r.model);
      ContactResult res = problem.MakeResult();
      const std::vector<ClosedContact> closed{{0, 0}, {1, 0}};
      ASSERT_EQ(problem.Solve(r.kin, closed, h, res), ContactStatus::kSolved);
      EXPECT_NEAR(res.lambda_N(0), 0.5 * F_n, 1e-9 * F_n);
      EXPECT_NEAR(res.lambda_N(1), 0.5 * F_n, 1e-9 * F_n);
      EXPECT_NEAR(res.lambda_T(0) + res.lambda_T(1), friction_total, 1e-9 * F_n);
      for (int j = 0; j < 2; ++j) {
        EXPECT_LE(std::abs(res.lambda_T(j)), mu * res.lambda_N(j) * (1 + 1e-12));
        EXPECT_NEAR(res.gammadot_N(j), 0.0, 1e-9);
      }
      const double m = 1000.0;
      if (!slides) {
        EXPECT_LT(res.du_dt.norm(), 1e-12 * F_n / m);
        EXPECT_NEAR(res.gammadot_T(0), 0.0, 1e-12);
        EXPECT_EQ(res.outcome[0], ContactOutcome::kSticks);
      } else {
        // A translation along t with a_T = (F_t - mu F_n sign F_t) / m, no rotation.
        const double a_T = (F_t + friction_total) / m;
        EXPECT_NEAR(res.du_dt(0), a_T * r.t.x(), 1e-9 * std::abs(a_T));
        EXPECT_NEAR(res.du_dt(1), a_T * r.t.y(), 1e-9 * std::abs(a_T));
        EXPECT_NEAR(res.du_dt(2), 0.0, 1e-12 * std::abs(a_T));
        for (int j = 0; j < 2; ++j) {
          EXPECT_NEAR(res.lambda_T(j), -mu * direction * res.lambda_N(j), 1e-9 * F_n);
          EXPECT_EQ(res.outcome[j], direction > 0 ? ContactOutcome::kStartsSlipPositive
                                                  : ContactOutcome::kStartsSlipNegative);
        }
        // The same state posed as sliding (set G with s = sign F_t) gives the same motion.
        const int s = direction > 0 ? 1 : -1;
        const std::vector<ClosedContact> sliding{{0, s}, {1, s}};
        ContactResult g = problem.MakeResult();
        ASSERT_EQ(problem.Solve(r.kin, sliding, h, g), ContactStatus::kSolved);
        EXPECT_LT((g.du_dt - res.du_dt).norm(), 1e-9 * std::abs(a_T));
        EXPECT_EQ(g.outcome[0], ContactOutcome::kSlides);
      }
    }
  }
}

TEST(ContactProblem, PullingAwayDetachesWithZeroForce) {
  Resting r = RestingDeck(30.0, 0.8, 0.2);
  Eigen::Vector3d h;
  h << 100.0 * r.n, 0.0;  // along +n: away from the face
  ContactProblem problem(r.model);
  ContactResult res = problem.MakeResult();
  const std::vector<ClosedContact> closed{{0, 0}, {1, 0}};
  ASSERT_EQ(problem.Solve(r.kin, closed, h, res), ContactStatus::kSolved);
  for (int j = 0; j < 2; ++j) {
    EXPECT_EQ(res.lambda_N(j), 0.0);
    EXPECT_EQ(res.outcome[j], ContactOutcome::kDetaches);
    EXPECT_NEAR(res.gammadot_N(j), 0.1, 1e-12);  // n . (100 n) / m
  }
}

TEST(ContactProblem, PainleveConfigurationIsReportedAsAStatus) {
  // One sliding contact with A = w_N^T M^-1 (w_N - mu s w_T) < 0 and b < 0 (pushed in): the
  // scalar LCP w = A z + b has no solution, Lemke ends on a secondary ray [Painleve].
  const model::Model model =
      testing::FreeDeck(45.0, 2.5, 20.0, 0.04, 0.5, 5.0, model::AbutmentSet::kPlusX, 1000.0);
  ContactKinematics kin;
  kin.Resize(model);
  const Eigen::Vector3d q(0.04, 0.0, 0.0);
  Evaluate(model, q, Eigen::Vector3d::Zero(), kin);
  const Eigen::Vector3d Minv = model.inverse_mass_diagonal();
  const Eigen::Vector3d w_N = kin.W_N.col(1);
  const Eigen::Vector3d w_T = kin.W_T.col(1);
  const int s = w_N.dot(Minv.asDiagonal() * w_T) > 0 ? 1 : -1;
  const double A = w_N.dot(Minv.asDiagonal() * (w_N - 5.0 * s * w_T));
  ASSERT_LT(A, 0.0);
  Eigen::Vector3d h = -1e3 * w_N;  // b = w_N^T M^-1 h < 0
  ContactProblem problem(model);
  ContactResult res = problem.MakeResult();
  const std::vector<ClosedContact> closed{{1, s}};
  EXPECT_EQ(problem.Solve(kin, closed, h, res), ContactStatus::kPainleve);
  EXPECT_EQ(res.lcp_status, lcp::LcpStatus::kSecondaryRay);
  EXPECT_STREQ(ToString(res.status), "painleve");
}

TEST(ContactProblem, TieToleranceDecidesBetweenStayingClosedAndDetaching) {
  // A frictionless corner sliding along its face under a large tangential load F t and a tiny
  // pull delta n: d gamma_N/dt = delta / m exactly (n . t = 0), lambda_N = 0. The scale of the
  // row is the sum of the magnitudes of its terms, |n_x t_x| F / m + |n_y t_y| F / m =
  // F sin(2a) / m; a separating acceleration within ContactPolicy::tie_tolerance of that scale is
  // a tie and the contact stays closed (docs/theory.md §3.15), beyond it the contact detaches.
  const double a_deg = 30.0, m = 1000.0, F = 1e4, delta = 1e-7;
  Resting r = RestingDeck(a_deg, 1.2, 0.0);
  Eigen::Vector3d h;
  h << F * r.t + delta * r.n, 0.0;
  const double scale = F * std::sin(2.0 * a_deg * kDeg) / m;  // 8.66 m/s^2
  const double separation = delta / m;                        // 1e-10 m/s^2
  const std::vector<ClosedContact> closed{{0, 1}};
  ContactProblem problem(r.model);
  ContactResult res = problem.MakeResult();
  struct Case {
    double tie_tolerance;
    ContactOutcome outcome;
  };
  // The default 1e-9 (band 8.7e-9 m/s^2) keeps the contact; 1e-12 (8.7e-12) and 0 let it go.
  for (const Case& c :
       {Case{ContactPolicy{}.tie_tolerance, ContactOutcome::kSlides},
        Case{1e-12, ContactOutcome::kDetaches}, Case{0.0, ContactOutcome::kDetaches}}) {
    ASSERT_EQ(separation > c.tie_tolerance * scale, c.outcome == ContactOutcome::kDetaches);
    ContactPolicy policy;
    policy.tie_tolerance = c.tie_tolerance;
    problem.SetPolicy(policy);
    ASSERT_EQ(problem.Solve(r.kin, closed, h, res), ContactStatus::kSolved);
    EXPECT_EQ(res.outcome[0], c.outcome) << "tie_tolerance " << c.tie_tolerance;
    EXPECT_EQ(res.lambda_N(0), 0.0);
    EXPECT_NEAR(res.gammadot_N(0), separation, 1e-6 * separation);
  }
}

TEST(ContactPolicy, DefaultIsWithinItsRanges) {
  // The problems start from ContactPolicy{} unchecked: it must pass the check SetPolicy makes.
  EXPECT_FALSE(schema::FirstViolation(ContactPolicy{}).has_value());
}

TEST(ContactPolicy, SameBytesComparesTheMembersNotThePadding) {
  // Two equal policies in storage whose padding differs (all ones against all zeros) are the
  // same bytes; a change of any one member's bits (a sign of zero included) is not.
  alignas(ContactPolicy) unsigned char ones[sizeof(ContactPolicy)], zeros[sizeof(ContactPolicy)];
  std::memset(ones, 0xff, sizeof ones);
  std::memset(zeros, 0x00, sizeof zeros);
  ContactPolicy* a = new (ones) ContactPolicy{};
  ContactPolicy* b = new (zeros) ContactPolicy{};
  ASSERT_NE(std::memcmp(ones, zeros, sizeof ones), 0);  // the padding does differ
  EXPECT_TRUE(SameBytes(*a, *b));
  EXPECT_TRUE(SameBytes(*b, *a));
  const auto differs = [&](auto change) {
    ContactPolicy c = *a;
    change(c);
    return !SameBytes(*a, c) && !SameBytes(c, *a);
  };
  EXPECT_TRUE(differs([](ContactPolicy& p) { p.tie_tolerance *= 2.0; }));
  EXPECT_TRUE(differs([](ContactPolicy& p) { p.contact_compliance = 0.0; }));
  EXPECT_TRUE(differs([](ContactPolicy& p) { p.impact_compliance = 3e-9; }));
  EXPECT_TRUE(differs([](ContactPolicy& p) { p.enumeration_unknowns = 0; }));
  ContactPolicy plus_zero, minus_zero;
  plus_zero.tie_tolerance = 0.0;
  minus_zero.tie_tolerance = -0.0;
  EXPECT_FALSE(SameBytes(plus_zero, minus_zero));
}

TEST(ContactPolicy, SetPolicyChecksEveryPolicyOtherThanTheOneHeld) {
  // Both problems skip the check for the bytes they hold: a policy out of range still aborts
  // after the same valid policy was set twice.
  Resting r = RestingDeck(30.0, 1.2, 0.0);
  ContactProblem problem(r.model);
  ImpactProblem impact(r.model);
  ContactPolicy good;
  good.tie_tolerance = 2e-9;
  for (int i = 0; i < 2; ++i) {
    problem.SetPolicy(good);
    impact.SetPolicy(good);
  }
  ContactPolicy bad = good;
  bad.impact_compliance = -1.0;
  EXPECT_DEATH(problem.SetPolicy(bad), "ContactPolicy: impact_compliance");
  EXPECT_DEATH(impact.SetPolicy(bad), "ContactPolicy: impact_compliance");
  EXPECT_TRUE(SameBytes(good, good));
  EXPECT_FALSE(SameBytes(good, bad));
}

TEST(ContactProblem, NoClosedContactGivesTheFreeAcceleration) {
  Resting r = RestingDeck(30.0, 1.0, 0.1);
  ContactProblem problem(r.model);
  ContactResult res = problem.MakeResult();
  const Eigen::Vector3d h(1.0, 2.0, 3.0);
  ASSERT_EQ(problem.Solve(r.kin, {}, h, res), ContactStatus::kSolved);
  EXPECT_LT((res.du_dt - r.model.inverse_mass_diagonal().cwiseProduct(h)).norm(), 1e-15);
}

}  // namespace
}  // namespace skewbridge::contact
