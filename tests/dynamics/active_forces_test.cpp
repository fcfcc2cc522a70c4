/// EvaluateActiveForces (solver/dynamics/active_forces.h) against the independent active-set
/// solve of tests/dynamics/active_set_oracle.h (whole vectors, Eigen's full-pivot LU) on a free
/// rectangular deck and a skew deck clamped between its abutments: one corner sticking, sliding
/// either way or frictionless, two corners on one face, and the singular sets of two sticking
/// corners on one face and of four sticking corners between two faces, where the forces are
/// indeterminate and the split [docs/theory.md §3.13] is checked on its postconditions. The
/// friction power is checked against the power balance of the constrained motion: with every
/// closed contact at gamma_N = 0, u^T M du/dt - u^T h = sum lambda_T gamma_T = -friction power.

#include "solver/dynamics/active_forces.h"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "solver/contact/kinematics.h"
#include "solver/model/builders.h"
#include "tests/dynamics/active_set_oracle.h"

namespace skewbridge::dynamics::active_forces_test {
namespace {

using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::VectorXd;

constexpr double kMass = 1.0e5;  // kg

// A free rectangular deck, 30 m x 10 m (no substructure, no damping), against the abutments
// `set` at a 0.01 m gap, friction mu.
model::Model FreeDeck(double mu, model::AbutmentSet set = model::AbutmentSet::kPlusX) {
  model::DeckSpec spec;
  spec.mass_kg = kMass;
  spec.geometry = {30.0, 10.0, 0.0};
  spec.stiffness = model::DeckSpec::StiffnessKind::kUncoupled;
  spec.xi = 0.0;
  spec.abutments = set;
  spec.gap_plus_m = spec.gap_minus_m = 0.01;
  spec.friction = mu;
  return model::BuildDeckModel(spec);
}

// A 30 deg skew deck, 30 m x 10 m, between both abutments at zero gap (P1, P2 on the +x face,
// P3, P4 on the -x face), with a substructure (2 pi rad/s) and friction mu.
model::Model ClampedDeck(double mu) {
  model::DeckSpec spec;
  spec.mass_kg = kMass;
  spec.geometry = {30.0, 10.0, 30.0 * std::numbers::pi / 180.0};
  spec.w0x_radps = spec.w0y_radps = spec.W0_radps = 2.0 * std::numbers::pi;
  spec.abutments = model::AbutmentSet::kBoth;
  spec.friction = mu;
  return model::BuildDeckModel(spec);
}

// The position with rotation theta at which contact c touches its face (g = 0).
VectorXd Touching(const model::Model& m, int c, double theta) {
  VectorXd q(3);
  q << 0.0, 0.0, theta;
  q[0] -= contact::Gap(m, c, q) / m.contact(c).face.normal.x();
  return q;
}

// A velocity with gamma_N = 0 at every closed contact, gamma_T = 0 at every sticking one and
// gamma_T = s v_slip at one sliding with sign s (least squares: exact when consistent).
VectorXd ConsistentVelocity(const model::Model& m, const ContactModes& modes, const VectorXd& q,
                            double v_slip) {
  contact::ContactKinematics kin;
  kin.Resize(m);
  contact::Evaluate(m, q, VectorXd::Zero(m.n_dof()), kin);
  std::vector<VectorXd> rows;
  std::vector<double> rhs;
  for (int c = 0; c < modes.size(); ++c) {
    if (modes.closed(c)) {
      rows.push_back(kin.W_N.col(c));
      rhs.push_back(0.0);
      if (modes[c] != ContactMode::kFrictionless) {
        rows.push_back(kin.W_T.col(c));
        rhs.push_back(SlipSign(modes[c]) * v_slip);
      }
    }
  }
  MatrixXd R(rows.size(), m.n_dof());
  VectorXd b(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    R.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
    b[static_cast<Eigen::Index>(i)] = rhs[i];
  }
  return R.completeOrthogonalDecomposition().solve(b);
}

// One evaluation of the unit at (q, u) under a_g.
struct Evaluation {
  Evaluation(const model::Model& m, const ContactModes& modes, const Vector2d& a_g,
             const VectorXd& q, const VectorXd& u, KinematicsOf which = KinematicsOf::kAllContacts)
      : s(m, EventPolicy{}.rank_threshold), du(VectorXd::Zero(m.n_dof())) {
    EvaluateActiveForces(m, modes, EventPolicy{}, 1e-6 * kMass, a_g, q, u, which, du, s);
  }
  ActiveForcesStorage s;
  VectorXd du;
};

// The power balance of the constrained motion (every closed contact at gamma_N = 0): the power
// of the contact forces, u^T M du - u^T h, is sum lambda_T gamma_T = -friction power (W).
double ContactPower(const model::Model& m, const VectorXd& u, const VectorXd& du,
                    const VectorXd& h) {
  return u.dot(m.mass_diagonal().cwiseProduct(du)) - u.dot(h);
}

// The scale of the accelerations (m/s^2, rad/s^2): the applied forces' M^-1 h, or du/dt when
// larger (a stuck deck's du/dt is zero to rounding of that scale).
double AccelerationScale(const model::Model& m, const testing::OracleForces& o) {
  return std::max(m.inverse_mass_diagonal().cwiseProduct(o.h).cwiseAbs().maxCoeff(),
                  o.du.cwiseAbs().maxCoeff());
}

struct Row {
  std::string name;
  double mu;
  double theta_rad;                // P1 touches its face at this rotation
  std::vector<ContactMode> modes;  // of P1, P2
};

// Determinate sets: the unit's forces and accelerations are the oracle's to rounding, open
// contacts carry nothing, and the friction power is the power balance's.
TEST(ActiveForces, DeterminateSetsMatchTheIndependentSolve) {
  using enum ContactMode;
  const std::vector<Row> rows = {
      {"P1 sticking", 0.4, -0.01, {kStick, kOpen}},
      {"P1 sliding +", 0.4, -0.01, {kSlidePositive, kOpen}},
      {"P1 sliding -", 0.4, -0.01, {kSlideNegative, kOpen}},
      {"P1 frictionless", 0.0, -0.01, {kFrictionless, kOpen}},
      {"P1, P2 sliding + on one face", 0.4, 0.0, {kSlidePositive, kSlidePositive}},
      {"P1 sticking, P2 sliding - on one face", 0.4, 0.0, {kStick, kSlideNegative}},
      {"P1, P2 frictionless on one face", 0.0, 0.0, {kFrictionless, kFrictionless}},
  };
  const Vector2d a_g(-2.0, 1.5);  // m/s^2: presses the deck into the +x face, and along it
  for (const Row& row : rows) {
    SCOPED_TRACE(row.name);
    const model::Model m = FreeDeck(row.mu);
    ContactModes modes(m.n_contacts());
    for (int c = 0; c < 2; ++c) {
      modes.Set(c, row.modes[static_cast<std::size_t>(c)]);
    }
    const VectorXd q = Touching(m, 0, row.theta_rad);
    const VectorXd u = ConsistentVelocity(m, modes, q, 0.2);
    const testing::OracleForces o = testing::OracleActiveForces(m, modes, a_g, q, u);
    ASSERT_EQ(o.rank, o.A.rows()) << "a determinate set";
    for (int c = 0; c < 2; ++c) {
      if (modes.closed(c)) {
        ASSERT_NEAR(o.kin.gap_m[c], 0.0, 1e-12) << "contact " << c << " touches";
        ASSERT_NEAR(o.kin.gamma_N[c], 0.0, 1e-12) << "contact " << c;
      }
    }
    const Evaluation e(m, modes, a_g, q, u);
    EXPECT_FALSE(e.s.sys.rank_deficient());
    const double f_scale = o.x.cwiseAbs().maxCoeff();
    ASSERT_GT(f_scale, 0.1 * kMass);
    for (int c = 0; c < m.n_contacts(); ++c) {
      EXPECT_NEAR(e.s.lambda_N[c], o.lambda_N[c], 1e-12 * f_scale) << "contact " << c;
      EXPECT_NEAR(e.s.lambda_T[c], o.lambda_T[c], 1e-12 * f_scale) << "contact " << c;
    }
    const double a_scale = AccelerationScale(m, o);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(e.du[i], o.du[i], 1e-12 * a_scale) << "dof " << i;
    }
    // Friction power: -sum lambda_T gamma_T, and the power balance of the motion.
    double friction = 0.0;
    for (int c = 0; c < m.n_contacts(); ++c) {
      friction -= o.lambda_T[c] * o.kin.gamma_T[c];
    }
    const double p_scale = 1e-12 * f_scale * 0.2 + 1e-9;
    EXPECT_NEAR(e.s.friction_power_W, friction, p_scale);
    EXPECT_NEAR(e.s.friction_power_W, -ContactPower(m, u, e.du, o.h),
                1e-10 * (std::abs(u.dot(o.h)) + f_scale * 0.2));
    bool sliding = false;
    for (ContactMode mode : row.modes) {
      sliding = sliding || mode == kSlidePositive || mode == kSlideNegative;
    }
    if (sliding) {
      // Sliding friction opposes the slip: it dissipates (lambda_N > 0 here).
      EXPECT_GT(e.s.friction_power_W, 0.0);
    } else {
      EXPECT_NEAR(e.s.friction_power_W, 0.0, 1e-9);
    }
  }
}

// The closed contacts' kinematics alone give the same forces and accelerations, bit for bit.
TEST(ActiveForces, ClosedContactsKinematicsGiveTheSameBits) {
  const model::Model m = FreeDeck(0.4, model::AbutmentSet::kBoth);
  ContactModes modes(m.n_contacts());
  modes.Set(0, ContactMode::kSlideNegative);
  const VectorXd q = Touching(m, 0, -0.01);
  const VectorXd u = ConsistentVelocity(m, modes, q, 0.3);
  const Vector2d a_g(-1.0, 0.7);
  const Evaluation all(m, modes, a_g, q, u);
  const Evaluation closed(m, modes, a_g, q, u, KinematicsOf::kClosedContacts);
  EXPECT_EQ(all.du, closed.du);
  EXPECT_EQ(all.s.lambda_N, closed.s.lambda_N);
  EXPECT_EQ(all.s.lambda_T, closed.s.lambda_T);
  EXPECT_EQ(all.s.friction_power_W, closed.s.friction_power_W);
}

// A constant force added to the applied forces (AddedForces): -M r da.
class GroundShare final : public AddedForces {
 public:
  GroundShare(const model::Model& m, const Vector2d& da)
      : f_(-m.mass_diagonal().cwiseProduct(m.r() * da)) {}
  void AddTo(const Eigen::Ref<const VectorXd>&, const Eigen::Ref<const VectorXd>&,
             Eigen::Ref<VectorXd> h) override {
    h += f_;
  }

 private:
  VectorXd f_;
};

// Forces added through the hook act as the model's own: -M r da added to h gives the forces and
// accelerations of the ground acceleration a_g + da without it (to rounding), for a free deck,
// a corner sliding and a corner sticking; the same evaluation without the hook differs.
TEST(ActiveForces, AddedForcesActAsTheModelsAppliedForces) {
  const model::Model m = FreeDeck(0.4);
  const Vector2d a_g(-1.0, 0.7), da(-1.5, 0.4);
  for (const ContactMode mode :
       {ContactMode::kOpen, ContactMode::kSlidePositive, ContactMode::kStick}) {
    SCOPED_TRACE(static_cast<int>(mode));
    ContactModes modes(m.n_contacts());
    modes.Set(0, mode);
    const VectorXd q = Touching(m, 0, -0.01);
    const VectorXd u = ConsistentVelocity(m, modes, q, mode == ContactMode::kStick ? 0.0 : 0.2);
    const Evaluation shifted(m, modes, a_g + da, q, u);
    GroundShare share(m, da);
    ActiveForcesStorage s(m, EventPolicy{}.rank_threshold);
    VectorXd du = VectorXd::Zero(m.n_dof());
    EvaluateActiveForces(m, modes, EventPolicy{}, 1e-6 * kMass, a_g, q, u,
                         KinematicsOf::kAllContacts, du, s, &share);
    const Evaluation plain(m, modes, a_g, q, u);
    const double a_scale = shifted.du.cwiseAbs().maxCoeff() + 1.0;
    for (int i = 0; i < m.n_dof(); ++i) {
      EXPECT_NEAR(du[i], shifted.du[i], 1e-13 * a_scale) << "dof " << i;
      EXPECT_NEAR(s.h[i], shifted.s.h[i], 1e-13 * kMass * a_scale) << "dof " << i;
    }
    EXPECT_NEAR(s.lambda_N[0], shifted.s.lambda_N[0], 1e-12 * kMass);
    EXPECT_NEAR(s.lambda_T[0], shifted.s.lambda_T[0], 1e-12 * kMass);
    EXPECT_GT((du - plain.du).cwiseAbs().maxCoeff(), 0.1) << "the hook adds its force";
  }
}

// The postconditions of a singular set's answer, whatever the split: the accelerations are
// the oracle's (A = R M^-1 R^T, so the kernel of A carries no generalized force: R^T x and du
// are unique), every constraint acceleration vanishes, du is M^-1 (h + W_N lambda_N + W_T
// lambda_T) of the reported forces, and every normal force pushes.
void ExpectSingularPostconditions(const model::Model& m, const ContactModes& modes,
                                  const testing::OracleForces& o, const Evaluation& e) {
  ASSERT_TRUE(e.s.sys.rank_deficient());
  ASSERT_LT(o.rank, o.A.rows());
  const double f_scale = o.lambda_N.cwiseAbs().maxCoeff() + o.lambda_T.cwiseAbs().maxCoeff();
  const double a_scale = AccelerationScale(m, o);
  VectorXd force = o.h;
  for (int c = 0; c < m.n_contacts(); ++c) {
    force += o.kin.W_N.col(c) * e.s.lambda_N[c] + o.kin.W_T.col(c) * e.s.lambda_T[c];
  }
  const VectorXd du_of_lambda = m.inverse_mass_diagonal().cwiseProduct(force);
  for (int i = 0; i < m.n_dof(); ++i) {
    EXPECT_NEAR(e.du[i], o.du[i], 1e-10 * a_scale) << "dof " << i;
    EXPECT_NEAR(e.du[i], du_of_lambda[i], 1e-10 * a_scale) << "dof " << i;
  }
  for (int c = 0; c < m.n_contacts(); ++c) {
    if (!modes.closed(c)) {
      continue;
    }
    EXPECT_NEAR(o.kin.W_N.col(c).dot(e.du) + o.kin.what_N[c], 0.0, 1e-10 * a_scale)
        << "contact " << c;
    EXPECT_NEAR(o.kin.W_T.col(c).dot(e.du) + o.kin.what_T[c], 0.0, 1e-10 * a_scale)
        << "contact " << c;
    EXPECT_GE(e.s.lambda_N[c], -1e-9 * f_scale) << "contact " << c;
  }
}

// Two corners sticking on one face: their tangential forces are indeterminate (only the sum is
// fixed); the split keeps both corners inside their cones, the pair carries the deck's
// tangential load, and the friction power is zero (no slip).
TEST(ActiveForces, TwoCornersStickingOnOneFaceSplitInsideTheCones) {
  const double mu = 0.5;
  const model::Model m = FreeDeck(mu);
  ContactModes modes(m.n_contacts());
  modes.Set(0, ContactMode::kStick);
  modes.Set(1, ContactMode::kStick);
  const VectorXd q = Touching(m, 0, 0.0);
  const VectorXd u = VectorXd::Zero(3);
  const Vector2d a_g(-2.0, 0.5);  // m/s^2: into the face, and a quarter of it along
  const testing::OracleForces o = testing::OracleActiveForces(m, modes, a_g, q, u);
  const Evaluation e(m, modes, a_g, q, u);
  ExpectSingularPostconditions(m, modes, o, e);
  for (int c = 0; c < 2; ++c) {
    EXPECT_LE(std::abs(e.s.lambda_T[c]), mu * e.s.lambda_N[c]) << "contact " << c;
  }
  // The face's resultant is the deck's inertial load along the face (M a_g . t).
  const Vector2d t = m.contact(0).face.tangent;
  EXPECT_NEAR(e.s.lambda_T[0] + e.s.lambda_T[1], kMass * a_g.dot(t), 1e-9 * kMass);
  EXPECT_EQ(e.s.friction_power_W, 0.0);
}

// A skew deck clamped between both faces, four corners sticking, pressed into the +x face: the
// -x face is unloaded (no squeeze) and the +x face carries the push.
TEST(ActiveForces, ClampedDeckStickingPushesWithoutSqueeze) {
  const model::Model m = ClampedDeck(0.5);
  ASSERT_EQ(m.n_contacts(), 4);
  ContactModes modes(4);
  for (int c = 0; c < 4; ++c) {
    modes.Set(c, ContactMode::kStick);
  }
  const VectorXd q = VectorXd::Zero(3), u = VectorXd::Zero(3);
  const Vector2d a_g(-2.0, 0.2);
  const testing::OracleForces o = testing::OracleActiveForces(m, modes, a_g, q, u);
  const Evaluation e(m, modes, a_g, q, u);
  ExpectSingularPostconditions(m, modes, o, e);
  const double f_scale = e.s.lambda_N.cwiseAbs().maxCoeff();
  EXPECT_NEAR(e.s.lambda_N[2] + e.s.lambda_N[3], 0.0, 1e-9 * f_scale);
  EXPECT_GT(e.s.lambda_N[0] + e.s.lambda_N[1], 0.1 * kMass);
}

}  // namespace
}  // namespace skewbridge::dynamics::active_forces_test
