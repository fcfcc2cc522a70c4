// Substructure builders and the Model's validation: the pilot bridge's modes against bounds
// derived from Ostrowski's theorem, classical damping against its modal definition, and every
// rejected field against the words of its message.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "solver/common/error.h"
#include "solver/model/builders.h"
#include "solver/model/checks.h"

namespace skewbridge::model::builders_test {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// The pilot bridge of [docs/theory.md §6].
DeckSpec PilotSpec() {
  DeckSpec spec;
  spec.mass_kg = 1547e3;
  spec.inertia_kgm2 = 1079100e3;
  spec.geometry = {89.14, 19.36, 20.0 * kDeg};
  spec.stiffness = DeckSpec::StiffnessKind::kPrincipal;
  spec.w1_radps = 18.0;
  spec.w2_radps = 19.0;
  spec.w_theta_radps = 26.0;
  spec.axis_rad = 20.0 * kDeg;
  spec.centre_of_rigidity_m = {-0.24, 0.01};
  spec.xi = 0.05;
  spec.abutments = AbutmentSet::kBoth;
  spec.gap_plus_m = spec.gap_minus_m = 0.05;
  spec.restitution = 0.5;
  spec.friction = 0.3;
  return spec;
}

TEST(Builders, UncoupledStiffnessIsDiagonalMassTimesSquaredFrequencies) {
  Body body;
  body.mass_kg = 2.0;
  body.inertia_kgm2 = 7.0;
  const Eigen::Matrix3d K = UncoupledStiffness(body, 3.0, 4.0, 5.0);
  Eigen::Matrix3d expected = Eigen::Vector3d(18.0, 32.0, 175.0).asDiagonal();
  EXPECT_EQ(K, expected);
}

TEST(Builders, PrincipalAxesStiffnessWithoutEccentricityHasItsAxesAtTheGivenAngle) {
  Body body;
  body.mass_kg = 3.0;
  body.inertia_kgm2 = 11.0;
  const double phi = 20.0 * kDeg;
  const Eigen::Matrix3d K = PrincipalAxesStiffness(body, 18.0, 19.0, 26.0, phi, {0.0, 0.0});
  const Eigen::Vector3d axis1(std::cos(phi), std::sin(phi), 0.0);
  const Eigen::Vector3d axis2(-std::sin(phi), std::cos(phi), 0.0);
  EXPECT_LT((K * axis1 - 3.0 * 18.0 * 18.0 * axis1).norm(), 1e-10 * K.norm());
  EXPECT_LT((K * axis2 - 3.0 * 19.0 * 19.0 * axis2).norm(), 1e-10 * K.norm());
  EXPECT_NEAR(K(2, 2), 11.0 * 26.0 * 26.0, 1e-12 * K(2, 2));
  EXPECT_EQ(K(0, 2), 0.0);
}

TEST(Builders, PilotBridgeFrequenciesAreEighteenNineteenTwentySixWithinTheEccentricityBound) {
  const Model model = BuildDeckModel(PilotSpec());
  const Modes modes = ComputeModes(model.M(), model.K());
  // In mass-scaled coordinates (x, y, rho theta), K~ = T~^T Omega T~ with Omega's eigenvalues
  // 18^2, 19^2, 26^2 and T~ = [[1, 0, -e_y/rho], [0, 1, e_x/rho], [0, 0, 1]]. Ostrowski's
  // theorem bounds each eigenvalue by sigma_min(T~)^2 and sigma_max(T~)^2 times the unperturbed
  // one: sigma^2 = 1 + e^2/2 -+ e sqrt(1 + e^2/4), e = |e| / rho.
  const double rho = std::sqrt(1079100e3 / 1547e3);
  const double e = Eigen::Vector2d(-0.24, 0.01).norm() / rho;
  const double s_max2 = 1.0 + 0.5 * e * e + e * std::sqrt(1.0 + 0.25 * e * e);
  const double s_min2 = 1.0 + 0.5 * e * e - e * std::sqrt(1.0 + 0.25 * e * e);
  const double nominal[3] = {18.0, 19.0, 26.0};
  std::cout << "pilot bridge frequencies (rad/s): " << modes.omega_radps.transpose()
            << "; eccentricity bound +-" << 0.5 * e << " relative\n";
  for (int k = 0; k < 3; ++k) {
    EXPECT_GE(modes.omega_radps(k), nominal[k] * std::sqrt(s_min2));
    EXPECT_LE(modes.omega_radps(k), nominal[k] * std::sqrt(s_max2));
  }
  // The shifts are of second order in e (no first-order term: Omega's eigenvectors are
  // translations or a rotation and T~ - E only couples them), so they are far inside the bound.
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(modes.omega_radps(k), nominal[k],
                nominal[k] * 2.0 * e * e * 26.0 * 26.0 / (26.0 * 26.0 - 19.0 * 19.0));
  }
}

TEST(Builders, ClassicalDampingGivesTheSameRatioInEveryMode) {
  for (const DeckSpec& spec : {PilotSpec()}) {
    const Model model = BuildDeckModel(spec);
    const Modes modes = ComputeModes(model.M(), model.K());
    const Eigen::MatrixXd modal_C = modes.phi.transpose() * model.C() * modes.phi;
    const Eigen::MatrixXd expected = (2.0 * 0.05 * modes.omega_radps).asDiagonal();
    EXPECT_LT((modal_C - expected).cwiseAbs().maxCoeff(), 1e-10 * expected.maxCoeff());
    // The modes are M-orthonormal.
    EXPECT_LT((modes.phi.transpose() * model.M() * modes.phi - Eigen::MatrixXd::Identity(3, 3))
                  .cwiseAbs()
                  .maxCoeff(),
              1e-12);
  }
}

TEST(Builders, DeckModelCarriesTheModesItsDampingWasBuiltFrom) {
  // The integrator's modal flow takes them instead of solving again: they must be the solve of
  // the model's own M and K, bit for bit, raw eigenvalues included.
  DeckSpec deck;
  deck.mass_kg = 3e5;
  deck.geometry = {45.0, 14.0, 0.5};
  deck.w0x_radps = 2.0;
  deck.w0y_radps = 2.5;
  deck.W0_radps = 4.0;
  deck.xi = 0.05;
  const Model m = BuildDeckModel(deck);
  ASSERT_NE(m.modes(), nullptr);
  const Modes solved = ComputeModes(m.M(), m.K());
  EXPECT_TRUE(m.modes()->phi == solved.phi);
  EXPECT_TRUE(m.modes()->eigenvalues == solved.eigenvalues);
  EXPECT_TRUE(m.modes()->omega_radps == solved.omega_radps);
  EXPECT_NEAR(solved.eigenvalues[0], 4.0, 1e-12);
  EXPECT_TRUE(m.C() == ClassicalDamping(m.M(), m.K(), deck.xi));
  deck.C = m.C();
  EXPECT_EQ(BuildDeckModel(deck).modes(), nullptr) << "a given C: nothing was solved";
}

// Whether two matrices hold the same bits.
bool SameBits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST(Builders, ADiagonalDecksModesAreTheBitsOfTheGeneralSolve) {
  // Random decks with diagonal M and K over many orders of magnitude, with equal frequencies
  // (the subsystem's w0x = w0y, and all three), a zero stiffness, and the default spec's own
  // decks: DiagonalDeckModes gives the bits of ComputeModes and ClassicalDamping every time.
  std::mt19937_64 rng(20261130);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked = 0;
  const auto check = [&](const Eigen::Vector3d& m, const Eigen::Vector3d& k, double xi) {
    const Eigen::MatrixXd M = m.asDiagonal();
    const Eigen::Matrix3d K = k.asDiagonal();
    Modes modes;
    Eigen::MatrixXd C;
    ASSERT_TRUE(DiagonalDeckModes(M, K, xi, modes, C)) << m.transpose() << " " << k.transpose();
    const Modes solved = ComputeModes(M, K);
    EXPECT_TRUE(SameBits(modes.eigenvalues, solved.eigenvalues))
        << m.transpose() << " / " << k.transpose();
    EXPECT_TRUE(SameBits(modes.omega_radps, solved.omega_radps));
    EXPECT_TRUE(SameBits(modes.phi, solved.phi)) << m.transpose() << " / " << k.transpose();
    EXPECT_TRUE(SameBits(C, ClassicalDamping(M, solved, xi)));
    ++checked;
  };
  for (int n = 0; n < 20000; ++n) {
    const double mass = std::pow(10.0, 2.0 + 6.0 * unit(rng));
    const double inertia = mass * std::pow(10.0, -1.0 + 5.0 * unit(rng));
    double w[3];
    for (double& v : w) v = std::pow(10.0, -2.0 + 4.0 * unit(rng));
    switch (n % 5) {
      case 1:
        w[1] = w[0];
        break;  // w0x = w0y
      case 2:
        w[1] = w[2] = w[0];
        break;  // all three equal
      case 3:
        w[static_cast<int>(n / 5) % 3] = 0.0;
        break;  // a free direction
      default:
        break;
    }
    const Eigen::Vector3d m(mass, mass, inertia);
    check(m, Eigen::Vector3d(mass * w[0] * w[0], mass * w[1] * w[1], inertia * w[2] * w[2]),
          0.2 * unit(rng));
  }
  // The default spec's decks (eta0 = 2, W0 = w0, xi = 0.05) at its skews and frequencies.
  for (int a = 10; a <= 80; a += 10) {
    for (int j = 0; j < 81; ++j) {
      DeckGeometry g{1.0, WidthFromEta0(2.0, a * std::numbers::pi / 180.0, 1.0),
                     a * std::numbers::pi / 180.0};
      const double inertia = UniformDeckInertia(1.0, g);
      const double w0 = std::pow(10.0, std::log10(0.2) + j * (std::log10(25.0) / 80.0));
      check(Eigen::Vector3d(1.0, 1.0, inertia),
            Eigen::Vector3d(w0 * w0, w0 * w0, inertia * w0 * w0), 0.05);
    }
  }
  EXPECT_EQ(checked, 20000 + 8 * 81);
  // Not of the form: an off-diagonal entry (even -0), a zero mass: the general solve's.
  Modes modes;
  Eigen::MatrixXd C;
  const Eigen::MatrixXd M = Eigen::Vector3d(3e5, 3e5, 5.0e7).asDiagonal();
  Eigen::Matrix3d K = Eigen::Vector3d(1.2e6, 1.9e6, 3.1e8).asDiagonal();
  K(0, 1) = K(1, 0) = 2.0e5;
  EXPECT_FALSE(DiagonalDeckModes(M, K, 0.05, modes, C));
  K(0, 1) = K(1, 0) = -0.0;
  EXPECT_FALSE(DiagonalDeckModes(M, K, 0.05, modes, C));
  K(0, 1) = K(1, 0) = 0.0;
  EXPECT_TRUE(DiagonalDeckModes(M, K, 0.05, modes, C));
  Eigen::MatrixXd M0 = M;
  M0(1, 1) = 0.0;
  EXPECT_FALSE(DiagonalDeckModes(M0, K, 0.05, modes, C));
}

TEST(Builders, DeckModelsFromTheMemoAreTheBitsOfTheirComputation) {
  // Decks that share all but one number of (M, K, xi): K's off-diagonal entry alone, M's
  // inertia alone, xi alone. Built twice over in turns (the second time from the thread's memo),
  // each model's modes and damping are the bits of ComputeModes and ClassicalDamping of its own
  // M, K and xi. A memo keyed on fewer of those numbers would hand one deck's to another.
  DeckSpec base;
  base.mass_kg = 3e5;
  base.geometry = {45.0, 14.0, 0.5};
  base.stiffness = DeckSpec::StiffnessKind::kMatrix;
  base.K = Eigen::Matrix3d::Zero();
  base.K.diagonal() << 1.2e6, 1.9e6, 3.1e8;
  base.K(0, 1) = base.K(1, 0) = 2.0e5;
  base.xi = 0.05;
  std::vector<DeckSpec> decks(4, base);
  decks[1].K(0, 1) = decks[1].K(1, 0) = 2.5e5;  // the off-diagonal entry alone
  decks[2].inertia_kgm2 = 6.1e7;                // M(2, 2) alone
  decks[3].xi = 0.02;                           // xi alone
  decks.push_back(PilotSpec());
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t i = 0; i < decks.size(); ++i) {
      const Model m = BuildDeckModel(decks[(i + pass) % decks.size()]);
      ASSERT_NE(m.modes(), nullptr);
      const Modes solved = ComputeModes(m.M(), m.K());
      EXPECT_TRUE(SameBits(m.modes()->phi, solved.phi)) << "pass " << pass << " deck " << i;
      EXPECT_TRUE(SameBits(m.modes()->eigenvalues, solved.eigenvalues));
      EXPECT_TRUE(SameBits(m.modes()->omega_radps, solved.omega_radps));
      EXPECT_TRUE(
          SameBits(m.C(), ClassicalDamping(m.M(), solved, decks[(i + pass) % decks.size()].xi)));
    }
  }
  // The memo itself: held after its computation, not found for a key one number away.
  DeckModesMemo memo;
  const Eigen::MatrixXd M = Eigen::Vector3d(3e5, 3e5, 5.0e7).asDiagonal();
  Eigen::Matrix3d K = base.K;
  Modes modes, found;
  Eigen::MatrixXd C, found_C;
  ASSERT_FALSE(memo.Find(M, K, 0.05, found, found_C));
  memo.Compute(M, K, 0.05, modes, C);
  ASSERT_TRUE(memo.Find(M, K, 0.05, found, found_C));
  EXPECT_TRUE(SameBits(found.phi, ComputeModes(M, K).phi));
  EXPECT_TRUE(SameBits(found.phi, modes.phi));
  EXPECT_TRUE(SameBits(found.omega_radps, modes.omega_radps));
  EXPECT_TRUE(SameBits(found.eigenvalues, modes.eigenvalues));
  EXPECT_TRUE(SameBits(found_C, C));
  EXPECT_FALSE(memo.Find(M, K, 0.02, found, found_C));
  Eigen::MatrixXd M2 = M;
  M2(2, 2) = 5.1e7;
  EXPECT_FALSE(memo.Find(M2, K, 0.05, found, found_C));
  K(1, 0) = K(0, 1) = 2.5e5;
  EXPECT_FALSE(memo.Find(M, K, 0.05, found, found_C));
  EXPECT_EQ(memo.size(), 1u);
}

TEST(Builders, AbutmentSetsCarryTheNamedCornersAgainstTheirFaces) {
  DeckSpec spec = PilotSpec();
  spec.abutments = AbutmentSet::kPlusX;
  const Model plus = BuildDeckModel(spec);
  ASSERT_EQ(plus.n_contacts(), 2);
  EXPECT_EQ(plus.contact(0).name, "P1");
  EXPECT_EQ(plus.contact(1).name, "P2");
  spec.abutments = AbutmentSet::kBoth;
  spec.gap_plus_m = 0.03;
  spec.gap_minus_m = 0.07;
  spec.overrides = {{"P3", 0.9, 0.1}};
  const Model both = BuildDeckModel(spec);
  ASSERT_EQ(both.n_contacts(), 4);
  EXPECT_EQ(both.FindContact("P3"), 2);
  EXPECT_EQ(both.contact(2).restitution, 0.9);
  EXPECT_EQ(both.contact(2).friction, 0.1);
  EXPECT_EQ(both.contact(3).restitution, 0.5);
  // At rest every gap is delta cos a [docs/theory.md §2].
  for (int c = 0; c < 4; ++c) {
    const Contact& k = both.contact(c);
    const double gap = k.face.normal.dot(k.point_m - k.face.point_m);
    EXPECT_NEAR(gap, (c < 2 ? 0.03 : 0.07) * std::cos(20.0 * kDeg), 1e-12);
  }
}

void ExpectMessage(const std::function<void()>& build, const std::vector<std::string>& words) {
  try {
    build();
    ADD_FAILURE() << "no InputError; expected one mentioning " << words.front();
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    for (const std::string& w : words) {
      EXPECT_NE(what.find(w), std::string::npos) << "'" << w << "' not in: " << what;
    }
  }
}

TEST(Builders, ADeckFieldIsRefusedExactlyWhenItsCheckRefusesIt) {
  // BuildDeckModel's checks against the named checks of checks.h: over values inside, at and
  // beyond each field's bounds (zeros of both signs, NaN, infinities), the deck is refused with
  // the check's own message when the check throws, and not for that field when it passes.
  constexpr double inf = std::numeric_limits<double>::infinity();
  const double values[] = {std::numeric_limits<double>::quiet_NaN(),
                           -inf,
                           -1.0,
                           -0.0,
                           0.0,
                           1e-300,
                           0.5,
                           1.0,
                           1.5,
                           89.999,
                           90.0,
                           1e300,
                           inf};
  const detail::Where where{"deck.toml", 0};
  struct Field {
    const char* name;
    std::function<void(DeckSpec&, double)> set;
    std::function<void(double)> check;
  };
  const std::vector<Field> fields = {
      {"deck.m", [](DeckSpec& s, double v) { s.mass_kg = v; },
       [&](double v) { detail::CheckPositive(v, "deck.m", where); }},
      {"deck.L", [](DeckSpec& s, double v) { s.geometry.length_m = v; },
       [&](double v) { detail::CheckPositive(v, "deck.L", where); }},
      {"deck.skew_deg",
       [](DeckSpec& s, double v) { s.geometry.skew_rad = v * std::numbers::pi / 180.0; },
       [&](double v) {
         detail::CheckRange(v * std::numbers::pi / 180.0 * 180.0 / std::numbers::pi, 0.0, 90.0,
                            true, "deck.skew_deg", where, "deg");
       }},
      {"substructure.w0x",
       [](DeckSpec& s, double v) {
         s.stiffness = DeckSpec::StiffnessKind::kUncoupled;
         s.w0x_radps = v;
         s.w0y_radps = s.W0_radps = 5.0;
       },
       [&](double v) { detail::CheckNonNegative(v, "substructure.w0x", where); }},
      {"substructure.xi", [](DeckSpec& s, double v) { s.xi = v; },
       [&](double v) { detail::CheckRange(v, 0.0, 1.0, true, "substructure.xi", where); }},
      {"abutments.eps_N", [](DeckSpec& s, double v) { s.restitution = v; },
       [&](double v) { detail::CheckRange(v, 0.0, 1.0, false, "abutments.eps_N", where); }},
      {"abutments.mu", [](DeckSpec& s, double v) { s.friction = v; },
       [&](double v) { detail::CheckNonNegative(v, "abutments.mu", where); }},
  };
  int refused = 0;
  for (const Field& f : fields) {
    for (const double v : values) {
      SCOPED_TRACE(std::string(f.name) + " = " + std::to_string(v));
      std::string expected;
      try {
        f.check(v);
      } catch (const InputError& e) {
        expected = e.what();
      }
      DeckSpec spec = PilotSpec();
      f.set(spec, v);
      std::string got;
      try {
        BuildDeckModel(spec, "deck.toml");
      } catch (const InputError& e) {
        got = e.what();
      }
      if (expected.empty()) {
        // Accepted by its check: a refusal, if any, names another field (an inertia or a
        // stiffness that overflows).
        EXPECT_EQ(got.find(std::string(f.name) + ":"), std::string::npos) << got;
      } else {
        EXPECT_EQ(got, expected);
        ++refused;
      }
    }
  }
  EXPECT_GT(refused, 20);
}

TEST(Builders, EveryInvalidSpecFieldIsNamedWithItsAllowedRange) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  const auto with = [](const std::function<void(DeckSpec&)>& change) {
    return [change] {
      DeckSpec spec = PilotSpec();
      change(spec);
      BuildDeckModel(spec, "bridge.toml");
    };
  };
  ExpectMessage(with([](DeckSpec& s) { s.geometry.width_m = 0.0; }),
                {"bridge.toml", "deck.W", "must be > 0", "got 0"});
  ExpectMessage(with([](DeckSpec& s) { s.geometry.length_m = -3.0; }),
                {"deck.L", "must be > 0", "got -3"});
  ExpectMessage(with([](DeckSpec& s) { s.mass_kg = 0.0; }), {"deck.m", "must be > 0"});
  ExpectMessage(with([](DeckSpec& s) { s.inertia_kgm2 = -1.0; }), {"deck.I_m", "must be > 0"});
  ExpectMessage(with([](DeckSpec& s) { s.geometry.skew_rad = 90.0 * kDeg; }),
                {"deck.skew_deg", "[0, 90) deg", "got 90"});
  ExpectMessage(with([](DeckSpec& s) { s.geometry.skew_rad = -1.0 * kDeg; }),
                {"deck.skew_deg", "[0, 90) deg"});
  ExpectMessage(with([](DeckSpec& s) { s.restitution = 1.5; }),
                {"abutments.eps_N", "[0, 1]", "got 1.5"});
  ExpectMessage(with([](DeckSpec& s) { s.friction = -0.1; }), {"abutments.mu", "must be >= 0"});
  ExpectMessage(with([](DeckSpec& s) {
                  s.overrides = {{"P2", -0.5, std::nullopt}};
                }),
                {"abutments.contacts.P2.eps_N", "[0, 1]"});
  ExpectMessage(with([](DeckSpec& s) {
                  s.overrides = {{"P7", 0.5, std::nullopt}};
                }),
                {"abutments.contacts.P7", "unknown contact", "P1, P2, P3, P4"});
  ExpectMessage(with([](DeckSpec& s) { s.gap_minus_m = -0.01; }),
                {"abutments.gap_m", "must be >= 0"});
  ExpectMessage(with([](DeckSpec& s) { s.xi = 1.0; }), {"substructure.xi", "[0, 1)", "got 1"});
  ExpectMessage(with([](DeckSpec& s) { s.w1_radps = nan; }), {"substructure.w1", "finite"});
  ExpectMessage(with([](DeckSpec& s) { s.geometry.width_m = nan; }), {"deck.W", "finite"});
  ExpectMessage(with([](DeckSpec& s) {
                  s.stiffness = DeckSpec::StiffnessKind::kMatrix;
                  s.K = Eigen::Matrix3d::Identity();
                  s.K(0, 1) = 0.5;
                }),
                {"substructure.K", "symmetric"});
  ExpectMessage(with([](DeckSpec& s) {
                  s.stiffness = DeckSpec::StiffnessKind::kMatrix;
                  s.K = Eigen::Vector3d(1.0, -1.0, 1.0).asDiagonal();
                }),
                {"substructure.K", "positive semi-definite"});
  ExpectMessage(with([](DeckSpec& s) {
                  Eigen::Matrix3d C = Eigen::Matrix3d::Identity();
                  C(2, 0) = 3.0;
                  s.C = C;
                }),
                {"substructure.C", "symmetric"});
}

TEST(Builders, ModelRejectsBrokenContactsAndMatrices) {
  Body body;
  body.mass_kg = 1.0;
  body.inertia_kgm2 = 1.0;
  body.geometry = {10.0, 2.0, 0.3};
  std::vector<Contact> contacts =
      AbutmentContacts(body, 0, AbutmentSet::kPlusX, 0.1, 0.1, 0.5, 0.2);
  contacts[0].face.point_m.x() = 0.0;  // the face inside the deck: a negative gap at rest
  ExpectMessage(
      [&] {
        Model({body}, Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(), GroundInfluence(1),
              contacts, "m.toml");
      },
      {"m.toml", "abutments.gap_m", "must be >= 0", "P1"});
  ExpectMessage(
      [&] {
        Model({body}, Eigen::Matrix2d::Identity(), Eigen::Matrix3d::Zero(), GroundInfluence(1), {},
              "m.toml");
      },
      {"substructure.K", "must be 3 x 3", "got 2 x 2"});
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  K(1, 1) = std::numeric_limits<double>::quiet_NaN();
  ExpectMessage(
      [&] { Model({body}, K, Eigen::Matrix3d::Zero(), GroundInfluence(1), {}, "m.toml"); },
      {"substructure.K", "finite"});
}

TEST(Builders, AbutmentContactsAreTheFacesAndCornersOfEachCall) {
  // A sequence of decks whose geometry, gaps and abutment set repeat and change in every
  // combination (the thread's last geometry is reused): every contact is the faces and corners
  // computed for that call's deck, bit for bit, and its eps_N, mu and body are the call's.
  const auto bits = [](const Eigen::Vector2d& v) {
    return std::array<std::uint64_t, 2>{std::bit_cast<std::uint64_t>(v.x()),
                                        std::bit_cast<std::uint64_t>(v.y())};
  };
  const auto expect_face = [&](const Face& a, const Face& b) {
    EXPECT_EQ(a.body, b.body);
    EXPECT_EQ(bits(a.point_m), bits(b.point_m));
    EXPECT_EQ(bits(a.normal), bits(b.normal));
    EXPECT_EQ(bits(a.tangent), bits(b.tangent));
  };
  std::mt19937 rng(33);
  std::uniform_int_distribution<int> pick(0, 2);
  const DeckGeometry geometries[] = {{30.0, 10.0, 0.3}, {30.0, 10.0, 0.6}, {31.0, 10.0, 0.3}};
  const double gaps[] = {0.01, 0.02, 0.0};
  for (int call = 0; call < 300; ++call) {
    SCOPED_TRACE(call);
    Body body;
    body.mass_kg = 1.0;
    body.inertia_kgm2 = 1.0;
    body.geometry = geometries[pick(rng)];
    const double gap_plus = gaps[pick(rng)], gap_minus = gaps[pick(rng)];
    const AbutmentSet set = pick(rng) == 0 ? AbutmentSet::kBoth : AbutmentSet::kPlusX;
    const double eps = 0.1 * pick(rng), mu = 0.2 * pick(rng);
    const int index = pick(rng);
    const std::vector<Contact> contacts =
        AbutmentContacts(body, index, set, gap_plus, gap_minus, eps, mu);
    ASSERT_EQ(contacts.size(), set == AbutmentSet::kBoth ? 4u : 2u);
    for (std::size_t j = 0; j < contacts.size(); ++j) {
      const Contact& c = contacts[j];
      const int k = static_cast<int>(j) + 1;
      EXPECT_EQ(c.name, "P" + std::to_string(k));
      EXPECT_EQ(c.body, index);
      EXPECT_EQ(bits(c.point_m), bits(Corner(body.geometry, k)));
      expect_face(c.face, k <= 2 ? PlusXAbutmentFace(body.geometry, gap_plus)
                                 : MinusXAbutmentFace(body.geometry, gap_minus));
      EXPECT_EQ(std::bit_cast<std::uint64_t>(c.restitution), std::bit_cast<std::uint64_t>(eps));
      EXPECT_EQ(std::bit_cast<std::uint64_t>(c.friction), std::bit_cast<std::uint64_t>(mu));
    }
  }
}

TEST(Builders, ADiagonalMatrixIsCheckedByItsEigenvaluesItsDiagonal) {
  // A diagonal K or C's eigenvalues are its entries: entries >= 0 (zeros, a subnormal, eight
  // hundred decades apart) pass; a negative entry passes within -1e-9 of the largest and fails
  // beyond it, a NaN fails as not finite.
  Body body;
  body.mass_kg = 1.0;
  body.inertia_kgm2 = 1.0;
  body.geometry = {10.0, 2.0, 0.3};
  const auto diag = [](double a, double b, double c) {
    return Eigen::Matrix3d(Eigen::Vector3d(a, b, c).asDiagonal());
  };
  for (const Eigen::Matrix3d& A : {diag(1e6, 3e5, 0.0), diag(0.0, 0.0, 0.0),
                                   diag(5e-324, 1.0, 1e300), diag(1.0, 1.0, -0.5e-9)}) {
    EXPECT_NO_THROW(Model({body}, A, Eigen::Matrix3d::Zero(), GroundInfluence(1), {}, "m.toml"))
        << A.diagonal().transpose();
    EXPECT_NO_THROW(Model({body}, Eigen::Matrix3d::Identity(), A, GroundInfluence(1), {}, "m.toml"))
        << A.diagonal().transpose();
  }
  ExpectMessage(
      [&] {
        Model({body}, diag(1.0, 1.0, -2e-9), Eigen::Matrix3d::Zero(), GroundInfluence(1), {},
              "m.toml");
      },
      {"substructure.K", "positive semi-definite", "smallest eigenvalue -"});
  ExpectMessage(
      [&] {
        Model({body}, Eigen::Matrix3d::Identity(),
              diag(1.0, std::numeric_limits<double>::quiet_NaN(), 1.0), GroundInfluence(1), {},
              "m.toml");
      },
      {"substructure.C", "finite"});
}

TEST(Builders, SemiDefinitenessAllowsOneBillionthOfTheLargestEntryBelowZero) {
  // The check's bound: every eigenvalue >= -1e-9 max|A| (a rotated diagonal, so that the
  // eigenvalues are known and the matrix is full). Just inside passes; just outside fails and
  // the message gives the smallest eigenvalue.
  Body body;
  body.mass_kg = 1.0;
  body.inertia_kgm2 = 1.0;
  body.geometry = {10.0, 2.0, 0.3};
  const Eigen::Matrix3d Q =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  const auto with_smallest = [&](double lambda) {
    const Eigen::Matrix3d A = Q * Eigen::Vector3d(1e6, 3e5, lambda).asDiagonal() * Q.transpose();
    return Eigen::Matrix3d(0.5 * (A + A.transpose()));
  };
  const double scale = with_smallest(0.0).cwiseAbs().maxCoeff();
  for (double fraction : {0.0, -0.5e-9, -0.9e-9}) {
    EXPECT_NO_THROW(Model({body}, with_smallest(fraction * scale), Eigen::Matrix3d::Zero(),
                          GroundInfluence(1), {}, "m.toml"))
        << fraction;
    EXPECT_NO_THROW(Model({body}, Eigen::Matrix3d::Identity(), with_smallest(fraction * scale),
                          GroundInfluence(1), {}, "m.toml"))
        << fraction;
  }
  for (double fraction : {-1.2e-9, -1e-6, -0.5}) {
    ExpectMessage(
        [&] {
          Model({body}, with_smallest(fraction * scale), Eigen::Matrix3d::Zero(),
                GroundInfluence(1), {}, "m.toml");
        },
        {"substructure.K", "positive semi-definite", "smallest eigenvalue -"});
    ExpectMessage(
        [&] {
          Model({body}, Eigen::Matrix3d::Identity(), with_smallest(fraction * scale),
                GroundInfluence(1), {}, "m.toml");
        },
        {"substructure.C", "positive semi-definite"});
  }
}

}  // namespace
}  // namespace skewbridge::model::builders_test
