// Contact kinematics against the paper's closed forms [docs/theory.md §2] at random states, against
// finite differences of the gap (Jacobians) and of gamma along a trajectory (velocity terms).
#include "solver/contact/kinematics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "tests/contact/test_models.h"

namespace skewbridge::contact {
namespace {

using testing::kDeg;

// The closed forms for corner i with lever arm r_i at the +x abutment [docs/theory.md §2]:
//   g_i = (delta - x) cos a + y sin a + (1/2)[L cos a (1 - cos theta) + 2 r_i sin theta]
//   w_N,i = (-cos a, sin a, (1/2)[L cos a sin theta + 2 r_i cos theta])
//   w_T,i = (sin a, cos a, -r_i sin theta + r_T cos theta).
// The -x abutment is the +x one turned by 180 deg (P3 = -P1, P4 = -P2, n and A negated), so
// g_3(x, y, theta) = g_1(-x, -y, theta), and its Jacobians are those of P1 with the translational
// entries negated.
struct ClosedForm {
  double g;
  Eigen::Vector3d w_N, w_T;
};

ClosedForm PaperClosedForm(double a, double L, double delta, double r, double r_T,
                           const Eigen::Vector3d& q, bool minus_x) {
  const double x = minus_x ? -q(0) : q(0);
  const double y = minus_x ? -q(1) : q(1);
  const double th = q(2);
  const double sgn = minus_x ? -1.0 : 1.0;
  ClosedForm f;
  f.g = (delta - x) * std::cos(a) + y * std::sin(a) +
        0.5 * (L * std::cos(a) * (1.0 - std::cos(th)) + 2.0 * r * std::sin(th));
  f.w_N << -sgn * std::cos(a), sgn * std::sin(a),
      0.5 * (L * std::cos(a) * std::sin(th) + 2.0 * r * std::cos(th));
  f.w_T << sgn * std::sin(a), sgn * std::cos(a), -r * std::sin(th) + r_T * std::cos(th);
  return f;
}

TEST(ContactKinematics, GapsAndJacobiansEqualThePaperClosedFormsAtRandomStates) {
  std::mt19937_64 rng(20110813);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (double a_deg : {5.0, 20.0, 30.0, 45.0, 70.0}) {
    for (double eta0 : {0.5, 1.48, 3.0}) {
      const double L = 89.14;
      const double delta = 0.05;
      const model::Model model =
          testing::FreeDeck(a_deg, eta0, L, delta, 0.5, 0.3, model::AbutmentSet::kBoth);
      const model::DeckGeometry& deck = model.body(0).geometry;
      const model::LeverArms arms = model::ComputeLeverArms(deck);
      const double arm[4] = {arms.r1_m, arms.r2_m, arms.r1_m, arms.r2_m};
      ContactKinematics kin;
      kin.Resize(model);
      for (int trial = 0; trial < 50; ++trial) {
        const Eigen::Vector3d q(0.5 * unit(rng), 0.5 * unit(rng), 0.3 * unit(rng));
        const Eigen::Vector3d u(unit(rng), unit(rng), 0.1 * unit(rng));
        Evaluate(model, q, u, kin);
        for (int c = 0; c < 4; ++c) {
          const ClosedForm f =
              PaperClosedForm(deck.skew_rad, L, delta, arm[c], arms.rT_m, q, c >= 2);
          const double scale = L;
          EXPECT_NEAR(kin.gap_m(c), f.g, 1e-12 * scale) << "contact " << c;
          EXPECT_LT((kin.W_N.col(c) - f.w_N).norm(), 1e-12 * scale) << "contact " << c;
          EXPECT_LT((kin.W_T.col(c) - f.w_T).norm(), 1e-12 * scale) << "contact " << c;
          EXPECT_NEAR(kin.gamma_N(c), f.w_N.dot(u), 1e-12 * scale);
          EXPECT_NEAR(kin.gamma_T(c), f.w_T.dot(u), 1e-12 * scale);
        }
      }
    }
  }
}

TEST(ContactKinematics, GapAtRestIsDeltaCosA) {
  const model::Model model =
      testing::FreeDeck(35.0, 1.2, 40.0, 0.08, 0.5, 0.0, model::AbutmentSet::kBoth);
  for (int c = 0; c < 4; ++c) {
    EXPECT_NEAR(Gap(model, c, Eigen::Vector3d::Zero()), 0.08 * std::cos(35.0 * kDeg), 1e-14);
  }
}

// The normal Jacobian is the gradient of the gap (central differences, O(h^2)); the tangential
// Jacobian is the gradient of the tangential displacement of P relative to the face's material
// point that coincides with P at q0.
void CheckJacobiansByFiniteDifferences(const model::Model& model, const Eigen::VectorXd& q0) {
  const int n = model.n_dof();
  Eigen::VectorXd w_N(n), w_T(n);
  for (int c = 0; c < model.n_contacts(); ++c) {
    Jacobians(model, c, q0, w_N, w_T);
    const model::Contact& contact = model.contact(c);
    Eigen::Vector2d n0, t0;
    FaceDirections(model, c, q0, n0, t0);
    const Eigen::Vector2d P0 = PointPosition(model, c, q0);
    // The face material point at P0 as a function of q (fixed for the ground).
    const auto material = [&](const Eigen::VectorXd& q) -> Eigen::Vector2d {
      if (contact.face.body == model::kGround) {
        return P0;
      }
      const int j = 3 * contact.face.body;
      const Eigen::Vector2d X_j = model.body(contact.face.body).rest_position_m;
      const Eigen::Vector2d local = Rotation(q0(j + 2)).transpose() * (P0 - X_j - q0.segment<2>(j));
      return X_j + q.segment<2>(j) + Rotation(q(j + 2)) * local;
    };
    const double h = 1e-6;
    for (int k = 0; k < n; ++k) {
      Eigen::VectorXd qp = q0, qm = q0;
      qp(k) += h;
      qm(k) -= h;
      const double dg = (Gap(model, c, qp) - Gap(model, c, qm)) / (2 * h);
      const double dt = t0.dot((PointPosition(model, c, qp) - material(qp)) -
                               (PointPosition(model, c, qm) - material(qm))) /
                        (2 * h);
      EXPECT_NEAR(w_N(k), dg, 1e-7 * (1.0 + std::abs(dg))) << "contact " << c << " dof " << k;
      EXPECT_NEAR(w_T(k), dt, 1e-7 * (1.0 + std::abs(dt))) << "contact " << c << " dof " << k;
    }
  }
}

TEST(ContactKinematics, JacobiansAreGradientsOfTheGapForGroundAndBodyFaces) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const model::Model deck =
      testing::FreeDeck(30.0, 1.3, 20.0, 0.02, 0.5, 0.2, model::AbutmentSet::kBoth);
  const model::Model two = testing::TwoDecks();
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd q(3);
    q << unit(rng), unit(rng), 0.5 * unit(rng);
    CheckJacobiansByFiniteDifferences(deck, q);
    Eigen::VectorXd q2(6);
    q2 << unit(rng), unit(rng), 0.5 * unit(rng), unit(rng), unit(rng), 0.5 * unit(rng);
    CheckJacobiansByFiniteDifferences(two, q2);
  }
}

// Along q(t) = q0 + u0 t + a t^2 / 2 the rate of gamma = w(q)^T u is w^T a + what at t = 0.
void CheckVelocityTermsAlongTrajectory(const model::Model& model, const Eigen::VectorXd& q0,
                                       const Eigen::VectorXd& u0, const Eigen::VectorXd& acc) {
  const int n = model.n_dof();
  Eigen::VectorXd w_N(n), w_T(n);
  const auto gammas = [&](int c, double t, double& gN, double& gT) {
    const Eigen::VectorXd q = q0 + u0 * t + 0.5 * acc * t * t;
    const Eigen::VectorXd u = u0 + acc * t;
    Jacobians(model, c, q, w_N, w_T);
    gN = w_N.dot(u);
    gT = w_T.dot(u);
  };
  for (int c = 0; c < model.n_contacts(); ++c) {
    const double h = 1e-5;
    double gNp, gTp, gNm, gTm;
    gammas(c, h, gNp, gTp);
    gammas(c, -h, gNm, gTm);
    double what_N, what_T;
    VelocityTerms(model, c, q0, u0, what_N, what_T);
    Jacobians(model, c, q0, w_N, w_T);
    const double dN = (gNp - gNm) / (2 * h);
    const double dT = (gTp - gTm) / (2 * h);
    EXPECT_NEAR(w_N.dot(acc) + what_N, dN, 1e-6 * (1.0 + std::abs(dN))) << "contact " << c;
    EXPECT_NEAR(w_T.dot(acc) + what_T, dT, 1e-6 * (1.0 + std::abs(dT))) << "contact " << c;
  }
}

TEST(ContactKinematics, VelocityTermsMatchTheRateOfGammaAlongATrajectory) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const model::Model deck =
      testing::FreeDeck(20.0, 1.48, 89.14, 0.03, 0.5, 0.3, model::AbutmentSet::kBoth);
  const model::Model two = testing::TwoDecks();
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd q(3), u(3), a(3);
    q << unit(rng), unit(rng), 0.2 * unit(rng);
    u << unit(rng), unit(rng), 0.5 * unit(rng);
    a << unit(rng), unit(rng), 0.5 * unit(rng);
    CheckVelocityTermsAlongTrajectory(deck, q, u, a);
    Eigen::VectorXd q2(6), u2(6), a2(6);
    for (int k = 0; k < 6; ++k) {
      q2(k) = unit(rng);
      u2(k) = unit(rng);
      a2(k) = unit(rng);
    }
    CheckVelocityTermsAlongTrajectory(two, q2, u2, a2);
  }
  // For a ground face what_N = -thetadot^2 n . R(theta) p exactly [docs/theory.md §2].
  const Eigen::Vector3d q(0.1, -0.2, 0.05), u(0.3, 0.1, 0.7);
  double what_N, what_T;
  VelocityTerms(deck, 0, q, u, what_N, what_T);
  const model::Contact& c = deck.contact(0);
  EXPECT_NEAR(what_N, -0.49 * c.face.normal.dot(Rotation(0.05) * c.point_m), 1e-13 * 89.14);
  EXPECT_NEAR(what_T, -0.49 * c.face.tangent.dot(Rotation(0.05) * c.point_m), 1e-13 * 89.14);
}

// EvaluateContacts on a subset refills exactly the listed contacts, with the values of the full
// Evaluate at the new state, and leaves every other entry as the previous state left it.
TEST(ContactKinematics, EvaluateContactsRefillsTheListedContactsOnly) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const model::Model deck =
      testing::FreeDeck(30.0, 1.3, 20.0, 0.02, 0.5, 0.2, model::AbutmentSet::kBoth);
  const int n = deck.n_dof();
  Eigen::VectorXd q0(n), u0(n), q1(n), u1(n);
  for (int i = 0; i < n; ++i) {
    q0[i] = 0.1 * unit(rng);
    u0[i] = unit(rng);
    q1[i] = 0.1 * unit(rng);
    u1[i] = unit(rng);
  }
  ContactKinematics before, after, subset;
  before.Resize(deck);
  after.Resize(deck);
  subset.Resize(deck);
  Evaluate(deck, q0, u0, before);
  Evaluate(deck, q1, u1, after);
  Evaluate(deck, q0, u0, subset);
  ASSERT_GE(deck.n_contacts(), 3);
  const std::vector<int> listed = {0, deck.n_contacts() - 1};
  EvaluateContacts(deck, q1, u1, listed, subset);
  for (int c = 0; c < deck.n_contacts(); ++c) {
    const bool in = c == listed[0] || c == listed[1];
    const ContactKinematics& expected = in ? after : before;
    EXPECT_EQ(subset.gap_m[c], expected.gap_m[c]) << "contact " << c;
    EXPECT_EQ(subset.gamma_N[c], expected.gamma_N[c]) << "contact " << c;
    EXPECT_EQ(subset.gamma_T[c], expected.gamma_T[c]) << "contact " << c;
    EXPECT_EQ(subset.what_N[c], expected.what_N[c]) << "contact " << c;
    EXPECT_EQ(subset.what_T[c], expected.what_T[c]) << "contact " << c;
    EXPECT_EQ(subset.W_N.col(c), expected.W_N.col(c)) << "contact " << c;
    EXPECT_EQ(subset.W_T.col(c), expected.W_T.col(c)) << "contact " << c;
  }
}

TEST(ContactKinematics, EvaluateOfASingleDeckIsTheBitsOfEachContactsEvaluation) {
  // Evaluate takes a single deck's corners together (one rotation, scalar sums); EvaluateContacts
  // evaluates each contact alone through its geometry, Jacobians and velocity terms. Every field
  // is the same bits, zeros' signs included, at random states and at rest.
  std::mt19937_64 rng(44);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const model::Model& deck :
       {testing::FreeDeck(30.0, 2.0, 20.0, 0.04, 0.5, 0.0, model::AbutmentSet::kPlusX),
        testing::FreeDeck(65.0, 1.3, 89.14, 0.03, 0.5, 0.3, model::AbutmentSet::kBoth)}) {
    ContactKinematics together, alone;
    together.Resize(deck);
    alone.Resize(deck);
    std::vector<int> all(static_cast<std::size_t>(deck.n_contacts()));
    for (int c = 0; c < deck.n_contacts(); ++c) all[static_cast<std::size_t>(c)] = c;
    const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
    for (int trial = 0; trial < 300; ++trial) {
      Eigen::Vector3d q(0.5 * unit(rng), 0.5 * unit(rng), 0.3 * unit(rng));
      Eigen::Vector3d u(3.0 * unit(rng), 3.0 * unit(rng), unit(rng));
      if (trial % 10 == 0) {
        q << -0.0, 0.0, trial % 20 == 0 ? -0.0 : 0.0;
        u(trial % 3) = -0.0;
      }
      Evaluate(deck, q, u, together);
      EvaluateContacts(deck, q, u, all, alone);
      for (int c = 0; c < deck.n_contacts(); ++c) {
        EXPECT_EQ(bits(together.gap_m[c]), bits(alone.gap_m[c])) << c << " trial " << trial;
        EXPECT_EQ(bits(together.gamma_N[c]), bits(alone.gamma_N[c])) << c << " trial " << trial;
        EXPECT_EQ(bits(together.gamma_T[c]), bits(alone.gamma_T[c])) << c << " trial " << trial;
        EXPECT_EQ(bits(together.what_N[c]), bits(alone.what_N[c])) << c << " trial " << trial;
        EXPECT_EQ(bits(together.what_T[c]), bits(alone.what_T[c])) << c << " trial " << trial;
        for (int i = 0; i < 3; ++i) {
          EXPECT_EQ(bits(together.W_N(i, c)), bits(alone.W_N(i, c))) << c << " trial " << trial;
          EXPECT_EQ(bits(together.W_T(i, c)), bits(alone.W_T(i, c))) << c << " trial " << trial;
        }
      }
    }
  }
}

// EvaluateContacts of a single deck (its own path: one rotation, scalar sums) against the
// general per-contact functions, bit for bit: the gap of BodyFaceGap (the geometry of any face),
// the columns of Jacobians, w . u, and VelocityTerms, for random subsets of the contacts in
// random order at random states and at rest; the contacts not listed keep their values.
TEST(ContactKinematics, EvaluateContactsOfASingleDeckIsTheBitsOfTheGeneralPath) {
  std::mt19937_64 rng(55);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  for (const model::Model& deck :
       {testing::FreeDeck(30.0, 2.0, 20.0, 0.04, 0.5, 0.0, model::AbutmentSet::kPlusX),
        testing::FreeDeck(65.0, 1.3, 89.14, 0.03, 0.5, 0.3, model::AbutmentSet::kBoth),
        testing::FreeDeck(10.0, 1.7, 45.0, 0.02, 0.5, 0.6, model::AbutmentSet::kBoth)}) {
    const int nc = deck.n_contacts();
    ContactKinematics kin;
    kin.Resize(deck);
    Eigen::VectorXd w_N(3), w_T(3);
    for (int trial = 0; trial < 400; ++trial) {
      Eigen::Vector3d q(0.5 * unit(rng), 0.5 * unit(rng), 0.3 * unit(rng));
      Eigen::Vector3d u(3.0 * unit(rng), 3.0 * unit(rng), unit(rng));
      if (trial % 10 == 0) {
        q << -0.0, 0.0, trial % 20 == 0 ? -0.0 : 0.0;
        u(trial % 3) = -0.0;
      }
      std::vector<int> listed;
      for (int c = 0; c < nc; ++c) {
        if (rng() % 2 == 0) listed.push_back(c);
      }
      std::shuffle(listed.begin(), listed.end(), rng);
      constexpr double kMarker = 12345.0;  // in every entry a contact not listed must keep
      kin.gap_m.setConstant(kMarker);
      kin.gamma_N.setConstant(kMarker);
      kin.what_T.setConstant(kMarker);
      EvaluateContacts(deck, q, u, listed, kin);
      for (int c = 0; c < nc; ++c) {
        if (std::find(listed.begin(), listed.end(), c) == listed.end()) {
          EXPECT_EQ(kin.gap_m[c], kMarker) << c;
          EXPECT_EQ(kin.gamma_N[c], kMarker) << c;
          EXPECT_EQ(kin.what_T[c], kMarker) << c;
          continue;
        }
        Jacobians(deck, c, q, w_N, w_T);
        double what_N = 0.0, what_T = 0.0;
        VelocityTerms(deck, c, q, u, what_N, what_T);
        EXPECT_EQ(bits(kin.gap_m[c]), bits(BodyFaceGap(deck, c, q))) << c << " trial " << trial;
        EXPECT_EQ(bits(kin.gamma_N[c]), bits(w_N.dot(u))) << c << " trial " << trial;
        EXPECT_EQ(bits(kin.gamma_T[c]), bits(w_T.dot(u))) << c << " trial " << trial;
        EXPECT_EQ(bits(kin.what_N[c]), bits(what_N)) << c << " trial " << trial;
        EXPECT_EQ(bits(kin.what_T[c]), bits(what_T)) << c << " trial " << trial;
        for (int i = 0; i < 3; ++i) {
          EXPECT_EQ(bits(kin.W_N(i, c)), bits(w_N[i])) << c << " trial " << trial;
          EXPECT_EQ(bits(kin.W_T(i, c)), bits(w_T[i])) << c << " trial " << trial;
        }
      }
    }
  }
}

// GapRateScratch::SinCos against std::cos and std::sin, bit for bit, on a sequence that repeats
// arguments (the case it keeps), alternates +0 and -0 (equal, but sin(-0) = -0), and takes
// non-finite and large arguments.
TEST(ContactKinematics, SinCosIsTheBitsOfStdCosAndSin) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> thetas = {0.0, -0.0, -0.0, 0.0, nan, 0.0, 1e300, 1e300, -inf, 0.25, 0.25};
  for (int i = 0; i < 400; ++i) {
    const double theta = 0.3 * unit(rng);
    thetas.push_back(theta);
    if (i % 3 == 0) thetas.push_back(theta);  // the same bits again
    if (i % 7 == 0) thetas.push_back(std::nextafter(theta, 1.0));
  }
  GapRateScratch scratch;
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  for (std::size_t i = 0; i < thetas.size(); ++i) {
    double c = 0.0, s = 0.0;
    scratch.SinCos(thetas[i], c, s);
    EXPECT_EQ(bits(c), bits(std::cos(thetas[i]))) << "argument " << i << " = " << thetas[i];
    EXPECT_EQ(bits(s), bits(std::sin(thetas[i]))) << "argument " << i << " = " << thetas[i];
  }
}

// GapsAndRates against Gap, NormalRate and Evaluate, bit for bit, at random states: a single deck
// (its own path, from the corners' data copied by Resize, with and without a rest position off
// the origin) and two decks with a face on a body (the general path, whose rate sums the whole
// Jacobian column: Evaluate's to rounding).
void CheckGapsAndRatesAreTheBitsOfGapAndEvaluate(const model::Model& model, bool deck_path,
                                                 std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  GapRateScratch scratch;
  scratch.Resize(model);
  EXPECT_EQ(scratch.deck_corners > 0, deck_path) << model.source();
  ContactKinematics kin;
  kin.Resize(model);
  const int n = model.n_dof();
  Eigen::VectorXd gap(model.n_contacts()), gamma_N(model.n_contacts());
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::VectorXd q(n), u(n);
    for (int i = 0; i < n; ++i) {
      q[i] = (i % 3 == 2 ? 0.4 : 2.0) * unit(rng);
      u[i] = 3.0 * unit(rng);
    }
    if (trial == 0) {
      q.setZero();  // the rest state, with its exact zeros
      q[0] = -0.0;
    }
    GapsAndRates(model, q, u, gap, gamma_N, scratch);
    Evaluate(model, q, u, kin);
    for (int c = 0; c < model.n_contacts(); ++c) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(gap[c]),
                std::bit_cast<std::uint64_t>(Gap(model, c, q)))
          << model.source() << " contact " << c << " trial " << trial;
      EXPECT_EQ(std::bit_cast<std::uint64_t>(gap[c]), std::bit_cast<std::uint64_t>(kin.gap_m[c]))
          << model.source() << " contact " << c << " trial " << trial;
      // The event searches' gap (DeckGap on a single deck, Gap otherwise).
      EXPECT_EQ(std::bit_cast<std::uint64_t>(Gap(model, c, q, scratch)),
                std::bit_cast<std::uint64_t>(Gap(model, c, q)))
          << model.source() << " contact " << c << " trial " << trial;
      if (deck_path) {
        // Evaluate's rate sums the rows of the contact's bodies only: the same sum for one deck.
        EXPECT_EQ(std::bit_cast<std::uint64_t>(gamma_N[c]),
                  std::bit_cast<std::uint64_t>(kin.gamma_N[c]))
            << model.source() << " contact " << c << " trial " << trial;
      } else {
        EXPECT_NEAR(gamma_N[c], kin.gamma_N[c], 1e-14 * (1.0 + std::abs(kin.gamma_N[c])))
            << model.source() << " contact " << c << " trial " << trial;
      }
      EXPECT_EQ(std::bit_cast<std::uint64_t>(gamma_N[c]),
                std::bit_cast<std::uint64_t>(NormalRate(model, c, q, u, scratch)))
          << model.source() << " contact " << c << " trial " << trial;
      // The general form: w_N . u with the Jacobian column of the contact's geometry.
      Eigen::VectorXd w_N(n), w_T(n);
      Jacobians(model, c, q, w_N, w_T);
      if (deck_path) {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(NormalRate(model, c, q, u, scratch)),
                  std::bit_cast<std::uint64_t>(w_N.dot(u)))
            << model.source() << " contact " << c << " trial " << trial;
      }
    }
  }
}

TEST(ContactKinematics, GapsAndRatesAreTheBitsOfGapAndEvaluate) {
  std::mt19937_64 rng(33);
  CheckGapsAndRatesAreTheBitsOfGapAndEvaluate(
      testing::FreeDeck(30.0, 2.0, 20.0, 0.04, 0.5, 0.0, model::AbutmentSet::kPlusX), true, rng);
  CheckGapsAndRatesAreTheBitsOfGapAndEvaluate(
      testing::FreeDeck(65.0, 1.3, 89.14, 0.03, 0.5, 0.3, model::AbutmentSet::kBoth), true, rng);
  // One deck resting away from the origin: X enters the gaps.
  const model::Model base =
      testing::FreeDeck(20.0, 1.48, 30.0, 0.05, 0.5, 0.2, model::AbutmentSet::kBoth);
  const Eigen::Vector2d X(3.25, -1.5);
  std::vector<model::Body> bodies = base.bodies();
  bodies[0].rest_position_m = X;
  std::vector<model::Contact> contacts = base.contacts();
  for (model::Contact& contact : contacts) {
    contact.face.point_m += X;  // the abutments move with the deck: the same gaps at rest
  }
  const model::Model moved(bodies, base.K(), base.C(), base.r(), contacts, "moved-deck");
  CheckGapsAndRatesAreTheBitsOfGapAndEvaluate(moved, true, rng);
  CheckGapsAndRatesAreTheBitsOfGapAndEvaluate(testing::TwoDecks(), false, rng);
}

}  // namespace
}  // namespace skewbridge::contact
