/// DecideModes (solver/dynamics/mode_decision.h), each rule of the mode decision at an instant
/// on its own [docs/theory.md §3.1-§3.11], on a free rectangular deck (K = C = 0, so the applied
/// forces are the ground's alone, h = -M r a_g) against a ground face. The expected values are
/// closed forms built from the deck's geometry by hand: a corner p (body frame) against a face
/// with normal n and tangent t has g = n . ((x, y) + R(theta) p - A), so
///     w_N = (n_x, n_y, n . R(theta) (-p_y, p_x)),   w_T = (t_x, t_y, t . R(theta) (-p_y, p_x)),
/// and G = w_N^T M^-1 w_N is the inverse of the corner's effective mass. A Newton impact at
/// approach speed v gives the normal impulse (1 + e) v / G and leaves at e v [Pfeiffer and
/// Glocker 1996, ch. 7]; a resting corner sticks while its sticking forces, the solution of
/// [w_N w_T]^T M^-1 (h + [w_N w_T] lambda) = 0, lie inside the cone |lambda_T| <= mu lambda_N.
/// The constrained forces the decision asks for (cone sign, tie fallback) come from an
/// independent active-set solve by Eigen's full-pivot LU (tests/dynamics/active_set_oracle.h).

#include "solver/dynamics/mode_decision.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "solver/model/builders.h"
#include "tests/contact/test_models.h"
#include "tests/dynamics/active_set_oracle.h"

namespace skewbridge::dynamics::mode_decision_test {
namespace {

using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr double kMass = 1.0e5;    // kg
constexpr double kLength = 30.0;   // m
constexpr double kWidth = 10.0;    // m
constexpr double kTheta0 = -0.01;  // rad: P1 at the +x face, P2 clear of it
constexpr double kT = 2.0;         // s: the instant of the decisions

// A free rectangular deck (no substructure, no damping) against the abutments `set`.
model::Model FreeDeck(double eps, double mu, model::AbutmentSet set = model::AbutmentSet::kPlusX) {
  model::DeckSpec spec;
  spec.mass_kg = kMass;
  spec.geometry = {kLength, kWidth, 0.0};
  spec.stiffness = model::DeckSpec::StiffnessKind::kUncoupled;
  spec.xi = 0.0;
  spec.abutments = set;
  spec.gap_plus_m = spec.gap_minus_m = 0.01;
  spec.restitution = eps;
  spec.friction = mu;
  return model::BuildDeckModel(spec);
}

// d g / d q of contact c at rotation theta along the face direction d (n: w_N, t: w_T).
Vector3d HandRow(const model::Contact& k, double theta, const Vector2d& d) {
  const Vector2d dp = Eigen::Rotation2Dd(theta) * Vector2d(-k.point_m.y(), k.point_m.x());
  return {d.x(), d.y(), d.dot(dp)};
}

// The gap of contact c at q by hand.
double HandGap(const model::Model& m, int c, const Vector3d& q) {
  const model::Contact& k = m.contact(c);
  const Vector2d x = q.head<2>() + Eigen::Rotation2Dd(q.z()) * k.point_m;
  return k.face.normal.dot(x - k.face.point_m);
}

// The position with rotation theta at which contact c touches its face (g = 0, y = 0).
Vector3d Touching(const model::Model& m, int c, double theta) {
  Vector3d q(0.0, 0.0, theta);
  q.x() -= HandGap(m, c, q) / m.contact(c).face.normal.x();
  return q;
}

Vector3d InverseMass(const model::Model& m) { return m.inverse_mass_diagonal(); }

// The constrained forces of the closed contacts by the independent active-set solve of
// tests/dynamics/active_set_oracle.h at the ground acceleration a_g. `lambda_N_shift` (N) is
// added to every closed contact's lambda_N: a caller that wants the tie fallback to fire.
class ActiveSetForces : public ConstrainedForces {
 public:
  explicit ActiveSetForces(const model::Model& m) : model_(m) {}
  void Forces(const ContactModes& modes, double, const Eigen::Ref<const VectorXd>& q,
              const Eigen::Ref<const VectorXd>& u, Eigen::Ref<VectorXd> lambda_N,
              Eigen::Ref<VectorXd> lambda_T) override {
    ++calls;
    const testing::OracleForces o = testing::OracleActiveForces(model_, modes, a_g, q, u);
    for (int c = 0; c < modes.size(); ++c) {
      lambda_N[c] = lambda_T[c] = 0.0;
      if (!modes.closed(c)) {
        continue;
      }
      lambda_N[c] = o.lambda_N[c] + lambda_N_shift;
      const double mu = model_.contact(c).friction;
      lambda_T[c] =
          modes[c] == ContactMode::kStick ? o.lambda_T[c] : -mu * SlipSign(modes[c]) * lambda_N[c];
      if (modes[c] == ContactMode::kStick && cone_side != 0) {
        lambda_T[c] = cone_side * (mu * lambda_N[c] + cone_excess_N);
      }
    }
  }

  Vector2d a_g = Vector2d::Zero();  ///< the ground acceleration of h (m/s^2)
  double lambda_N_shift = 0.0;      ///< N, added to every closed contact's lambda_N
  /// When not 0: a sticking contact's lambda_T is reported as cone_side (mu lambda_N +
  /// cone_excess_N), beyond its cone (a caller that wants the stick-slip event's state).
  int cone_side = 0;
  double cone_excess_N = 0.0;  ///< N
  int calls = 0;               ///< Forces calls so far

 private:
  const model::Model& model_;
};

// The decision's inputs and storage for one model, at the scales of a response with v_ref =
// 1 m/s and omega_ref = 1 rad/s (docs/theory.md §3.2) and a shortest period of 1 s.
struct Decision {
  explicit Decision(const model::Model& m)
      : model(m),
        modes(m.n_contacts()),
        memory(m.n_contacts()),
        forces(m),
        ws(m, EventPolicy{}.rank_threshold) {
    scales.v_tol_mps = 1e-10;
    scales.v_acc_mps = 1e-6;
    scales.gap_tol_m = 1e-12;
    scales.force_tol_N = 1e-7 * kMass;
    scales.a_detach_mps2 = 1e-7;
    scales.period_min_s = 1.0;
    scales.length_scale_m = kLength;
    scales.simultaneity_s = 1e-9;
  }

  // One decision at t_s (kT unless a test sets it) with ground acceleration a_g (also the
  // forces' a_g).
  DecisionOutcome Decide(const Vector2d& a_g, VectorXd& q, VectorXd& u,
                         const std::vector<int>& forced = {}) {
    forces.a_g = a_g;
    return DecideModes(model, policy, scales, {t_s, a_g, forced}, q, u, modes, memory, forces, ws,
                       log);
  }

  const model::Model& model;
  double t_s = kT;  // the instant of the decisions
  EventPolicy policy;
  DecisionScales scales;
  ContactModes modes;
  DecisionMemory memory;
  DecisionLog log;
  ActiveSetForces forces;
  DecisionWorkspace ws;
};

// gamma_N of contact c at (q, u) by hand.
double NormalRate(const model::Model& m, int c, const VectorXd& q, const VectorXd& u) {
  return HandRow(m.contact(c), q[2], m.contact(c).face.normal).dot(u);
}

// --- Newton impacts [§3.3] -----------------------------------------------------------------

struct NewtonRow {
  double eps;    // restitution
  double v_mps;  // approach speed
};

// A single corner (P1, frictionless) striking its face at v leaves at e v; one impact event
// with the normal impulse (1 + e) v / G, the kinetic energy lost (1 - e^2) v^2 / (2 G), and the
// corner opens (nothing presses it back).
TEST(ModeDecision, KineticEnergyIsTheBitsOfEigensDotProduct) {
  // KineticEnergy sums a deck's three terms on scalars: the same bits as
  // 0.5 * u.dot(M u) at random velocities, with exact zeros of either sign.
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const model::Model deck = contact::testing::FreeDeck(30.0, 1.5, 25.0, 0.02, 0.5, 0.3,
                                                       model::AbutmentSet::kBoth, 1234.5);
  for (int trial = 0; trial < 1000; ++trial) {
    Eigen::VectorXd u(3);
    u << 3.0 * unit(rng), 3.0 * unit(rng), unit(rng);
    if (trial % 10 == 0) u(trial % 3) = trial % 20 == 0 ? -0.0 : 0.0;
    const double eigen = 0.5 * u.dot(deck.mass_diagonal().cwiseProduct(u));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(KineticEnergy(deck, u)),
              std::bit_cast<std::uint64_t>(eigen))
        << "trial " << trial;
  }
}

TEST(ModeDecision, NewtonImpactOfOneCornerLeavesAtRestitutionTimesApproach) {
  for (const NewtonRow row : {NewtonRow{0.3, 0.1}, NewtonRow{0.5, 1e-3}, NewtonRow{0.8, 2.0}}) {
    SCOPED_TRACE("eps " + std::to_string(row.eps) + " v " + std::to_string(row.v_mps));
    const model::Model m = FreeDeck(row.eps, 0.0);
    Decision d(m);
    VectorXd q = Touching(m, 0, kTheta0);
    ASSERT_GT(HandGap(m, 1, q), 0.05);
    const Vector3d w = HandRow(m.contact(0), kTheta0, m.contact(0).face.normal);
    const double G = w.dot(InverseMass(m).cwiseProduct(w));
    // Along w M^-1 (a pure approach of P1): gamma_N = -v.
    VectorXd u = -row.v_mps / G * InverseMass(m).cwiseProduct(w);
    ASSERT_NEAR(NormalRate(m, 0, q, u), -row.v_mps, 1e-14 * row.v_mps);
    const VectorXd u0 = u;
    const DecisionOutcome r = d.Decide(Vector2d::Zero(), q, u);
    ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
    const double Lambda = (1.0 + row.eps) * row.v_mps / G;
    EXPECT_NEAR(NormalRate(m, 0, q, u), row.eps * row.v_mps, 1e-12 * row.v_mps);
    const VectorXd u_expected = u0 + Lambda * InverseMass(m).cwiseProduct(w);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(u[i], u_expected[i], 1e-12 * u_expected.cwiseAbs().maxCoeff()) << "dof " << i;
    }
    ASSERT_EQ(d.log.events.size(), 1u);
    const EventRecord& e = d.log.events[0];
    EXPECT_EQ(e.kind, EventKind::kImpact);
    EXPECT_EQ(e.contact, 0);
    EXPECT_EQ(e.t_s, kT);
    EXPECT_NEAR(e.impulse_N_Ns, Lambda, 1e-12 * Lambda);
    EXPECT_NEAR(e.gamma_N_before_mps, -row.v_mps, 1e-13 * row.v_mps);
    EXPECT_NEAR(e.gamma_N_after_mps, row.eps * row.v_mps, 1e-12 * row.v_mps);
    const double loss = 0.5 * (1.0 - row.eps * row.eps) * row.v_mps * row.v_mps / G;
    EXPECT_NEAR(e.kinetic_loss_J, loss, 1e-11 * loss);
    EXPECT_NEAR(d.log.impact_J, loss, 1e-11 * loss);
    EXPECT_EQ(d.log.impacts, 1);
    EXPECT_EQ(d.log.plastic_closures, 0);
    EXPECT_FALSE(d.modes.any_closed());
    // The history of the corner: this impact, and that it left.
    EXPECT_EQ(d.memory.history[0].bounce_seq, 1);
    EXPECT_NEAR(d.memory.history[0].bounce_v_mps, row.v_mps, 1e-13 * row.v_mps);
    EXPECT_EQ(d.memory.history[0].left_t_s, kT);
  }
}

// A closed corner that an impact opens takes no tie with it: a tie left behind (here one kept
// from an earlier instant's detachment band) would make every later decision evaluate the
// constrained forces for a contact that is not in the contact problem. The corner (closed,
// frictionless) is struck at v and leaves at e v > v_acc: open, with no tie, and the decision
// asked the constrained forces nothing (no sticking contact, no contact problem).
TEST(ModeDecision, AContactThatLeavesAtAnImpactKeepsNoTie) {
  const double eps = 0.5, v = 0.1;
  const model::Model m = FreeDeck(eps, 0.0);
  Decision d(m);
  d.modes.Set(0, ContactMode::kFrictionless);
  d.memory.tie[0] = ContactMode::kOpen;
  VectorXd q = Touching(m, 0, kTheta0);
  const Vector3d w = HandRow(m.contact(0), kTheta0, m.contact(0).face.normal);
  const double G = w.dot(InverseMass(m).cwiseProduct(w));
  VectorXd u = -v / G * InverseMass(m).cwiseProduct(w);
  const DecisionOutcome r = d.Decide(Vector2d::Zero(), q, u);
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  EXPECT_NEAR(NormalRate(m, 0, q, u), eps * v, 1e-12 * v);
  EXPECT_EQ(d.modes[0], ContactMode::kOpen);
  EXPECT_EQ(d.log.detachments, 1);
  EXPECT_FALSE(d.memory.tie[0].has_value());
  EXPECT_EQ(d.forces.calls, 0);
}

// A full edge (P1 and P2, theta = 0) striking its face in translation: the two corners take the
// impulse m (1 + e) v between them, half each by symmetry, and leave at e v.
TEST(ModeDecision, FullEdgeImpactTakesTheDeckMomentumTimesOnePlusRestitution) {
  const double eps = 0.5, v = 0.2;
  const model::Model m = FreeDeck(eps, 0.0);
  Decision d(m);
  VectorXd q = Touching(m, 0, 0.0);
  ASSERT_NEAR(HandGap(m, 1, q), 0.0, 1e-15);
  const Vector2d n = m.contact(0).face.normal;
  VectorXd u(3);
  u << -v * n.x(), -v * n.y(), 0.0;
  const DecisionOutcome r = d.Decide(Vector2d::Zero(), q, u, {0, 1});
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  ASSERT_EQ(d.log.events.size(), 2u);
  const double total = d.log.events[0].impulse_N_Ns + d.log.events[1].impulse_N_Ns;
  EXPECT_NEAR(total, kMass * (1.0 + eps) * v, 1e-12 * kMass * v);
  EXPECT_NEAR(d.log.events[0].impulse_N_Ns, d.log.events[1].impulse_N_Ns, 1e-10 * kMass * v);
  EXPECT_NEAR(NormalRate(m, 0, q, u), eps * v, 1e-12 * v);
  EXPECT_NEAR(NormalRate(m, 1, q, u), eps * v, 1e-12 * v);
  EXPECT_EQ(d.log.impacts, 1);  // one impact instant, two contacts
}

// --- Plastic closures and the accumulation threshold [§3.3] --------------------------------

// Closing slower than v_acc is a plastic closure: the approach is stopped (gamma_N after = 0)
// with the impulse v / G, logged as such, and the corner stays closed (sticking with friction,
// frictionless without). Above v_acc the same approach is a Newton impact with the impulse
// (1 + e) v / G; its rebound e v opens the corner when faster than v_acc, and when slower the
// corner stays a candidate (where an accumulation converges) and the projection stops it.
TEST(ModeDecision, ClosureSlowerThanTheAccumulationThresholdIsPlastic) {
  struct Row {
    double v_over_vacc;
    double mu;
    bool plastic;
    ContactMode mode;
  };
  for (const Row row :
       {Row{0.5, 0.0, true, ContactMode::kFrictionless}, Row{0.5, 0.3, true, ContactMode::kStick},
        Row{0.999, 0.0, true, ContactMode::kFrictionless},
        Row{1.5, 0.0, false, ContactMode::kFrictionless},
        Row{3.0, 0.0, false, ContactMode::kOpen}}) {
    SCOPED_TRACE("v/v_acc " + std::to_string(row.v_over_vacc) + " mu " + std::to_string(row.mu));
    const double eps = 0.5;
    const model::Model m = FreeDeck(eps, row.mu);
    Decision d(m);
    const double v = row.v_over_vacc * d.scales.v_acc_mps;
    VectorXd q = Touching(m, 0, kTheta0);
    const Vector3d w = HandRow(m.contact(0), kTheta0, m.contact(0).face.normal);
    const double G = w.dot(InverseMass(m).cwiseProduct(w));
    VectorXd u = -v / G * InverseMass(m).cwiseProduct(w);
    const DecisionOutcome r = d.Decide(Vector2d::Zero(), q, u);
    ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
    ASSERT_EQ(d.log.events.size(), 1u);
    const EventRecord& e = d.log.events[0];
    if (row.plastic) {
      EXPECT_EQ(e.kind, EventKind::kPlasticClosure);
      EXPECT_EQ(d.log.plastic_closures, 1);
      EXPECT_EQ(d.log.impacts, 0);
      EXPECT_NEAR(e.impulse_N_Ns, v / G, 1e-12 * v / G);
      EXPECT_NEAR(e.gamma_N_after_mps, 0.0, 1e-12 * v);
    } else {
      EXPECT_EQ(e.kind, EventKind::kImpact);
      EXPECT_EQ(d.log.impacts, 1);
      EXPECT_NEAR(e.impulse_N_Ns, (1.0 + eps) * v / G, 1e-12 * v / G);
      EXPECT_NEAR(e.gamma_N_after_mps, eps * v, 1e-12 * v);
    }
    EXPECT_EQ(d.modes[0], row.mode);
    EXPECT_NEAR(NormalRate(m, 0, q, u), d.modes.closed(0) ? 0.0 : eps * v, 1e-12 * v);
  }
}

// --- Stick and slip of a resting corner [§3.7] ---------------------------------------------

// A resting corner (u = 0) loaded into its face by the ground. Its sticking forces are the
// solution of [w_N w_T]^T M^-1 (h + [w_N w_T] lambda) = 0 with h = -M r a_g: with the load's
// tangential part scaled so that |lambda_T| = ratio mu lambda_N, it sticks for ratio < 1 and
// slides for ratio > 1, against lambda_T (slip sign -sign(lambda_T)), with the friction
// lambda_T = -mu s lambda_N. Entered open (touching) or sticking, the answer is the same; from
// sticking, the slip is a slip transition.
TEST(ModeDecision, RestingCornerSticksInsideTheConeAndSlidesAgainstItsFrictionBeyond) {
  const double mu = 0.3;
  const model::Model m = FreeDeck(0.5, mu);
  const Vector3d q0 = Touching(m, 0, kTheta0);
  const model::Contact& k = m.contact(0);
  const Vector3d wN = HandRow(k, kTheta0, k.face.normal), wT = HandRow(k, kTheta0, k.face.tangent);
  const Vector3d inv_m = InverseMass(m);
  Eigen::Matrix<double, 3, 2> W;
  W << wN, wT;
  const Eigen::Matrix2d A = W.transpose() * inv_m.asDiagonal() * W;
  // The sticking forces of a ground acceleration a_g (free deck: h = (-m a_x, -m a_y, 0)).
  const auto sticking = [&](const Vector2d& a_g) {
    const Vector3d h(-kMass * a_g.x(), -kMass * a_g.y(), 0.0);
    return Eigen::Vector2d(A.fullPivLu().solve(-W.transpose() * inv_m.asDiagonal() * h));
  };
  const Vector2d press = 2.0 * k.face.normal;  // a_N = -n . a_g = -2 m/s^2
  // Per unit tangential load: its own lambda; the ratio |lambda_T| / (mu lambda_N) is linear in
  // the tangential part a_t of a_g = press - a_t t.
  for (const double ratio : {0.5, 0.9, 1.1, 2.0}) {
    for (const double side : {1.0, -1.0}) {
      for (const ContactMode before : {ContactMode::kOpen, ContactMode::kStick}) {
        SCOPED_TRACE("ratio " + std::to_string(ratio) + " side " + std::to_string(side) +
                     " entered " + (before == ContactMode::kOpen ? "open" : "sticking"));
        // Find a_t with lambda_T = side ratio mu lambda_N (lambda is affine in a_t).
        const Vector2d l0 = sticking(press);
        const Vector2d l1 = sticking(press + k.face.tangent);
        const double target_slope = side * ratio * mu;
        const double a_t = (target_slope * l0.x() - l0.y()) /
                           ((l1.y() - l0.y()) - target_slope * (l1.x() - l0.x()));
        const Vector2d a_g = press + a_t * k.face.tangent;
        const Vector2d lambda = sticking(a_g);
        ASSERT_GT(lambda.x(), 0.0) << "the load must press the corner into its face";
        ASSERT_NEAR(std::abs(lambda.y()) / (mu * lambda.x()), ratio, 1e-9);
        Decision d(m);
        d.modes.Set(0, before);
        VectorXd q = q0, u = VectorXd::Zero(3);
        const DecisionOutcome r = d.Decide(a_g, q, u);
        ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
        const int s = lambda.y() > 0.0 ? -1 : 1;
        const ContactMode expected = ratio < 1.0 ? ContactMode::kStick : SlideOrStick(s);
        EXPECT_EQ(d.modes[0], expected);
        // A check of the test's own force oracle, not of the decision: the forces it reports
        // for the chosen mode are the closed form when sticking, and press the corner when
        // sliding (no Painleve answer).
        VectorXd lN(m.n_contacts()), lT(m.n_contacts());
        d.forces.Forces(d.modes, kT, q, u, lN, lT);
        if (ratio < 1.0) {
          ASSERT_NEAR(lN[0], lambda.x(), 1e-9 * lambda.x());
          ASSERT_NEAR(lT[0], lambda.y(), 1e-9 * lambda.x());
        } else {
          ASSERT_GT(lN[0], 0.0);
        }
        const bool slip_event = before == ContactMode::kStick && ratio > 1.0;
        EXPECT_EQ(d.log.slip_transitions, slip_event ? 1 : 0);
        EXPECT_EQ(d.log.events.size(), slip_event ? 1u : 0u);
        EXPECT_EQ(d.log.impacts + d.log.plastic_closures, 0);
      }
    }
  }
}

// The cone sign [§3.8]: a sticking corner whose friction, as the constrained forces report it,
// has reached its cone (mu lambda_N + force_tol - |lambda_T| <= 0: the stick-slip event) enters
// the contact problem sliding against that friction, slip sign -sign(lambda_T), and slides (a
// slip transition), whatever the contact problem over a sticking candidate would say. Here the
// loads keep it inside the cone (its closed-form sticking forces have |lambda_T| < mu
// lambda_N), so with the rule off, or with a friction reported beyond the cone by less than
// force_tol (the event's band: excess 0.5 force_tol, the event function still positive), the
// contact problem keeps it sticking.
TEST(ModeDecision, ConeSignSlidesAStickingCornerAgainstTheFrictionAtItsCone) {
  const double mu = 0.3;
  const model::Model m = FreeDeck(0.5, mu);
  const model::Contact& k = m.contact(0);
  // Pressed into the face with a tangential load inside the cone.
  const Vector2d a_g = 2.0 * k.face.normal + 0.1 * k.face.tangent;
  Eigen::Matrix<double, 3, 2> W;
  W << HandRow(k, kTheta0, k.face.normal), HandRow(k, kTheta0, k.face.tangent);
  const Vector3d inv_m = InverseMass(m);
  const Vector3d h(-kMass * a_g.x(), -kMass * a_g.y(), 0.0);
  const Eigen::Matrix2d A = W.transpose() * inv_m.asDiagonal() * W;
  const Vector2d lambda = A.fullPivLu().solve(-W.transpose() * inv_m.asDiagonal() * h);
  ASSERT_GT(lambda.x(), 0.0);
  ASSERT_LT(std::abs(lambda.y()), 0.9 * mu * lambda.x());
  struct Row {
    double excess_of_force_tol;  // |lambda_T| reported beyond mu lambda_N, of force_tol
    bool rule;
    bool slides;
  };
  for (const int side : {1, -1}) {
    for (const Row row : {Row{2.0, true, true}, Row{0.5, true, false}, Row{2.0, false, false}}) {
      SCOPED_TRACE(std::string("lambda_T side ") + (side > 0 ? "+" : "-") + ", excess " +
                   std::to_string(row.excess_of_force_tol) +
                   (row.rule ? " force_tol, rule on" : " force_tol, rule off"));
      Decision d(m);
      d.policy.cone_sign = row.rule;
      d.forces.cone_side = side;
      d.forces.cone_excess_N = row.excess_of_force_tol * d.scales.force_tol_N;
      d.modes.Set(0, ContactMode::kStick);
      VectorXd q = Touching(m, 0, kTheta0), u = VectorXd::Zero(3);
      const DecisionOutcome r = d.Decide(a_g, q, u);
      ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
      EXPECT_EQ(d.modes[0], row.slides ? SlideOrStick(-side) : ContactMode::kStick);
      EXPECT_EQ(d.log.slip_transitions, row.slides ? 1 : 0);
      // The rule asks the constrained forces once (a sticking contact); no tie to check.
      EXPECT_EQ(d.forces.calls, row.rule ? 1 : 0);
    }
  }
}

// The decision's kinematics are its own: after a decision that asked the constrained forces
// (the cone sign, the tie fallback), ws.projection.kin holds the kinematics of every contact at
// the final (q, u), what the integrator takes as the next step's start, bit for bit those of a
// fresh evaluation there, and the gaps and normal rates of the hand formulas.
TEST(ModeDecision, LeavesItsOwnKinematicsAtTheFinalState) {
  const double mu = 0.3;
  const model::Model m = FreeDeck(0.5, mu);
  const model::Contact& k = m.contact(0);
  struct Row {
    ContactMode start;
    int cone_side;
    Vector2d a_g;
    const char* why;
  };
  const Row rows[] = {
      {ContactMode::kStick, 1, 2.0 * k.face.normal + 0.1 * k.face.tangent, "cone sign: slides"},
      {ContactMode::kStick, 0, 2.0 * k.face.normal + 0.1 * k.face.tangent, "sticks"},
      {ContactMode::kStick, 0, -5e-8 * k.face.normal, "detachment tie"},
  };
  for (const Row& row : rows) {
    SCOPED_TRACE(row.why);
    Decision d(m);
    d.forces.cone_side = row.cone_side;
    d.forces.cone_excess_N = 2.0 * d.scales.force_tol_N;
    d.modes.Set(0, row.start);
    VectorXd q = Touching(m, 0, kTheta0), u = VectorXd::Zero(3);
    u[1] = 1e-3;  // sliding along the face (and the unit's tangent) on the way
    const DecisionOutcome r = d.Decide(row.a_g, q, u);
    ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
    ASSERT_GT(d.forces.calls, 0) << "the decision must have asked the constrained forces";
    contact::ContactKinematics fresh;
    fresh.Resize(m);
    contact::Evaluate(m, q, u, fresh);
    const contact::ContactKinematics& kin = d.ws.projection.kin;
    for (int c = 0; c < m.n_contacts(); ++c) {
      EXPECT_EQ(kin.gap_m[c], fresh.gap_m[c]) << "contact " << c;
      EXPECT_EQ(kin.gamma_N[c], fresh.gamma_N[c]) << "contact " << c;
      EXPECT_EQ(kin.gamma_T[c], fresh.gamma_T[c]) << "contact " << c;
      EXPECT_NEAR(kin.gap_m[c], HandGap(m, c, q), 1e-12) << "contact " << c;
      EXPECT_NEAR(kin.gamma_N[c], NormalRate(m, c, q, u), 1e-14) << "contact " << c;
    }
  }
}

// --- Accumulation rules [§3.4, §3.6] --------------------------------------------------------

// A corner pressed into its face (a_N = -1 m/s^2) strikes at v = 0.01 m/s, after a flight of
// 1 ms since its previous impact at 2 v with no other impact in between: a Zeno sequence
// (ratio 0.5 <= 0.9, flight <= 0.01 T_min). The impact closes it at once: gamma_N after = 0,
// impulse v / G, and the contact problem keeps it closed. Without the rule (zeno_extrapolation
// off) the same approach bounces at e v and the corner opens.
TEST(ModeDecision, ZenoSequenceClosesTheContactAtOnce) {
  for (const bool zeno : {true, false}) {
    SCOPED_TRACE(zeno ? "zeno on" : "zeno off");
    const double eps = 0.5, v = 0.01;
    const model::Model m = FreeDeck(eps, 0.0);
    Decision d(m);
    d.policy.zeno_extrapolation = zeno;
    d.memory.impact_sequence = 7;
    d.memory.last_impact_t_s = kT - 1e-3;
    d.memory.history[0] = {kT - 1e-3, 2.0 * v, 7, kT - 1e-3};
    VectorXd q = Touching(m, 0, kTheta0);
    const Vector3d w = HandRow(m.contact(0), kTheta0, m.contact(0).face.normal);
    const double G = w.dot(InverseMass(m).cwiseProduct(w));
    VectorXd u = -v / G * InverseMass(m).cwiseProduct(w);
    const Vector2d a_g = m.contact(0).face.normal;  // a_N = -n . a_g = -1 m/s^2
    const DecisionOutcome r = d.Decide(a_g, q, u);
    ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
    ASSERT_EQ(d.log.events.size(), 1u);
    EXPECT_EQ(d.log.events[0].kind, EventKind::kImpact);
    EXPECT_EQ(d.log.impacts, 1);
    EXPECT_NEAR(d.log.min_impact_separation_s, 1e-3, 1e-12);
    if (zeno) {
      EXPECT_NEAR(d.log.events[0].impulse_N_Ns, v / G, 1e-12 * v / G);
      EXPECT_NEAR(NormalRate(m, 0, q, u), 0.0, 1e-12 * v);
      EXPECT_EQ(d.modes[0], ContactMode::kFrictionless);
    } else {
      EXPECT_NEAR(d.log.events[0].impulse_N_Ns, (1.0 + eps) * v / G, 1e-12 * v / G);
      EXPECT_NEAR(NormalRate(m, 0, q, u), eps * v, 1e-12 * v);
      EXPECT_EQ(d.modes[0], ContactMode::kOpen);
    }
  }
}

// The predicted bounce [§3.6]: a first impact at v leaving at e v under a pressing normal
// acceleration a returns after 2 e v / a. Within zeno_flight_at_once T_min (1 ms) the corner is
// kept closed (the projection puts its rebound to zero) although the impact itself had
// restitution; beyond it, or with the rule off, the corner leaves.
TEST(ModeDecision, ReboundReturningWithinAnAccumulationsFlightIsClosedAtOnce) {
  struct Row {
    double a_mps2;  // pressing normal acceleration
    bool rule;
    bool closed;
  };
  const double eps = 0.5, v = 0.01;  // return after 0.01 / a s
  for (const Row row : {Row{20.0, true, true}, Row{20.0, false, false}, Row{5.0, true, false}}) {
    SCOPED_TRACE("a " + std::to_string(row.a_mps2) + (row.rule ? " rule on" : " rule off"));
    const model::Model m = FreeDeck(eps, 0.0);
    Decision d(m);
    d.policy.bounce_at_once = row.rule;
    VectorXd q = Touching(m, 0, kTheta0);
    const Vector3d w = HandRow(m.contact(0), kTheta0, m.contact(0).face.normal);
    const double G = w.dot(InverseMass(m).cwiseProduct(w));
    VectorXd u = -v / G * InverseMass(m).cwiseProduct(w);
    // The free normal acceleration w_N^T M^-1 h with h = -M a_g: -(n . a_g) - its rotational
    // part, none here (h has no moment): a_N = -a.
    const Vector2d a_g = row.a_mps2 * m.contact(0).face.normal;
    const DecisionOutcome r = d.Decide(a_g, q, u);
    ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
    ASSERT_EQ(d.log.events.size(), 1u);
    EXPECT_NEAR(d.log.events[0].gamma_N_after_mps, eps * v, 1e-12 * v);
    EXPECT_EQ(d.modes.closed(0), row.closed);
    EXPECT_NEAR(NormalRate(m, 0, q, u), row.closed ? 0.0 : eps * v, 1e-12 * v);
  }
}

// --- Tie bands and the tie fallback [§3.7] --------------------------------------------------

// A closed corner at rest whose free normal acceleration separates it by a fraction of a_detach
// is a detachment tie: it stays closed (lambda_N = 0 within force_tol) with the contact
// problem's answer, open, kept to fall back on. When the constrained forces say its detachment
// function lambda_N + force_tol is not positive, the tie falls back: open, a detachment. With
// the tie bands off, or beyond the band, it opens at once.
TEST(ModeDecision, TieBandKeepsTheContactClosedAndFallsBackWhenItsEventFunctionFires) {
  struct Row {
    double a_over_band;  // separating acceleration, of a_detach
    bool tie_bands;
    double shift_of_force_tol;  // lambda_N shift of the supplied forces, of force_tol
    bool closed;
  };
  for (const Row row : {Row{0.5, true, 0.0, true}, Row{0.5, true, -2.0, false},
                        Row{0.5, false, 0.0, false}, Row{2.0, true, 0.0, false}}) {
    SCOPED_TRACE("a/a_detach " + std::to_string(row.a_over_band) +
                 (row.tie_bands ? " bands on" : " bands off") + " shift " +
                 std::to_string(row.shift_of_force_tol));
    const model::Model m = FreeDeck(0.5, 0.0);
    Decision d(m);
    d.policy.tie_bands = row.tie_bands;
    d.forces.lambda_N_shift = row.shift_of_force_tol * d.scales.force_tol_N;
    d.modes.Set(0, ContactMode::kFrictionless);
    VectorXd q = Touching(m, 0, kTheta0), u = VectorXd::Zero(3);
    // a_N = -(n . a_g) = row.a_over_band a_detach.
    const Vector2d a_g = -row.a_over_band * d.scales.a_detach_mps2 * m.contact(0).face.normal;
    const DecisionOutcome r = d.Decide(a_g, q, u);
    ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
    EXPECT_EQ(d.modes.closed(0), row.closed);
    if (row.closed) {
      ASSERT_TRUE(d.memory.tie[0].has_value());
      EXPECT_EQ(*d.memory.tie[0], ContactMode::kOpen);
      EXPECT_TRUE(d.log.events.empty());
      // A precondition on the test's own force oracle, not a claim about the decision: the
      // tie's forces are lambda_N = -a_N / G, inside the detachment band.
      const Vector3d w = HandRow(m.contact(0), kTheta0, m.contact(0).face.normal);
      const double G = w.dot(InverseMass(m).cwiseProduct(w));
      VectorXd lN(2), lT(2);
      d.forces.Forces(d.modes, kT, q, u, lN, lT);
      ASSERT_NEAR(lN[0], -row.a_over_band * d.scales.a_detach_mps2 / G, 1e-9 * kMass * 1e-7);
      ASSERT_GT(lN[0] + d.scales.force_tol_N, 0.0);
    } else {
      EXPECT_FALSE(d.memory.tie[0].has_value());
      ASSERT_EQ(d.log.events.size(), 1u);
      EXPECT_EQ(d.log.events[0].kind, EventKind::kDetachment);
      EXPECT_EQ(d.log.detachments, 1);
    }
    // The tie fallback asked the supplied forces only when there was a tie.
    EXPECT_EQ(d.forces.calls > 0, row.tie_bands && row.a_over_band < 1.0);
  }
}

// --- The jam of a wedged deck [§3.9] ---------------------------------------------------------

// A 45 deg skew deck (eta0 = 2.5, L = 20 m, m = 1000 kg, mu = 1.5) between both abutments with
// its acute corners P1 (+x face) and P3 (-x face) closed, both sliding with gamma_T > 0 (P3
// separating at 5e-7 m/s, below v_acc, so it stays a candidate), the ground pushing along x.
// The contact problem of the two sliding corners, A_ij = w_Ni^T M^-1 (w_Nj - mu s_j w_Tj),
// b_i = w_Ni^T M^-1 h, has no solution (checked by enumerating its four complementary bases):
// the deck wedges. The jam stops the sliding by a tangential impact, the projection onto
// gamma_N = gamma_T = 0 of both corners (here u = 0: four rows on three degrees of freedom), one
// impact instant with the kinetic energy lost 1/2 u^T M u, and the decision is made again from
// rest; a second jam at the same instant is a Painleve situation, and so is the first with the
// rule off.
TEST(ModeDecision, JamOfAWedgedDeckStopsTheSlidingOncePerInstant) {
  const double mu = 1.5, eps_speed = 5e-7;
  const model::Model m =
      contact::testing::FreeDeck(45.0, 2.5, 20.0, 0.05, 0.5, mu, model::AbutmentSet::kBoth, 1000.0);
  // P1 and P3 at their faces: Newton on (x, theta) with y = 0.
  Vector3d q0 = Vector3d::Zero();
  for (int it = 0; it < 30; ++it) {
    const Vector2d r(HandGap(m, 0, q0), HandGap(m, 2, q0));
    Eigen::Matrix2d J;
    J << HandRow(m.contact(0), q0.z(), m.contact(0).face.normal)[0],
        HandRow(m.contact(0), q0.z(), m.contact(0).face.normal)[2],
        HandRow(m.contact(2), q0.z(), m.contact(2).face.normal)[0],
        HandRow(m.contact(2), q0.z(), m.contact(2).face.normal)[2];
    const Vector2d d = J.fullPivLu().solve(r);
    q0.x() -= d.x();
    q0.z() -= d.y();
  }
  ASSERT_NEAR(HandGap(m, 0, q0), 0.0, 1e-13);
  ASSERT_NEAR(HandGap(m, 2, q0), 0.0, 1e-13);
  ASSERT_GT(HandGap(m, 1, q0), 1e-3);
  ASSERT_GT(HandGap(m, 3, q0), 1e-3);
  const double th = q0.z();
  const Vector3d wN1 = HandRow(m.contact(0), th, m.contact(0).face.normal);
  const Vector3d wN3 = HandRow(m.contact(2), th, m.contact(2).face.normal);
  const Vector3d wT1 = HandRow(m.contact(0), th, m.contact(0).face.tangent);
  const Vector3d wT3 = HandRow(m.contact(2), th, m.contact(2).face.tangent);
  // u with gamma_N1 = 0, gamma_N3 = eps_speed and no component along the common null direction.
  Eigen::Matrix3d rows;
  rows << wN1.transpose(), wN3.transpose(), wN1.cross(wN3).transpose();
  const Vector3d u0 = rows.fullPivLu().solve(Vector3d(0.0, eps_speed, 0.0));
  ASSERT_GT(wT1.dot(u0), 100.0 * 2e-10);  // both slide with s = +1, beyond the stick band
  ASSERT_GT(wT3.dot(u0), 100.0 * 2e-10);
  // The contact problem of the two sliding corners has no solution.
  const Vector3d inv_m = InverseMass(m);
  const Vector2d a_g(2.0, 0.0);
  const Vector3d h(-1000.0 * a_g.x(), -1000.0 * a_g.y(), 0.0);
  const std::vector<Vector3d> wN = {wN1, wN3}, wT = {wT1, wT3};
  Eigen::Matrix2d A;
  Vector2d b;
  for (int i = 0; i < 2; ++i) {
    b[i] = wN[i].dot(inv_m.cwiseProduct(h));
    for (int j = 0; j < 2; ++j) {
      A(i, j) = wN[i].dot(inv_m.cwiseProduct(wN[j] - mu * wT[j]));
    }
  }
  int solutions = 0;
  for (int basis = 0; basis < 4; ++basis) {
    Vector2d lambda = Vector2d::Zero();
    if (basis == 1 || basis == 2) {
      const int i = basis - 1;
      lambda[i] = -b[i] / A(i, i);
    } else if (basis == 3) {
      lambda = A.fullPivLu().solve(-b);
    }
    const Vector2d w = A * lambda + b;
    solutions += (lambda.array() >= 0.0).all() && (w.array() >= -1e-15).all() ? 1 : 0;
  }
  ASSERT_EQ(solutions, 0) << "A = " << A << ", b = " << b.transpose();

  const auto wedged = [&](Decision& d, VectorXd& q, VectorXd& u) {
    q = q0;
    u = u0;
    d.modes.Set(0, ContactMode::kSlidePositive);
    d.modes.Set(2, ContactMode::kSlidePositive);
  };
  Decision d(m);
  VectorXd q, u;
  wedged(d, q, u);
  const double kinetic = 0.5 * u.dot(m.mass_diagonal().cwiseProduct(u));
  const DecisionOutcome r = d.Decide(a_g, q, u);
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  EXPECT_TRUE(d.memory.jammed_here);
  // Decided again from rest: the push along +x presses P3 into the -x face, which sticks, and
  // lifts P1 off the +x face.
  EXPECT_EQ(d.modes[2], ContactMode::kStick);
  EXPECT_EQ(d.modes[0], ContactMode::kOpen);
  for (const int c : {0, 2}) {
    EXPECT_NEAR(NormalRate(m, c, q, u), 0.0, 1e-9 * eps_speed) << "contact " << c;
    EXPECT_NEAR(HandRow(m.contact(c), q[2], m.contact(c).face.tangent).dot(u), 0.0,
                1e-9 * eps_speed)
        << "contact " << c;
  }
  EXPECT_EQ(d.log.impacts, 1);
  EXPECT_EQ(d.log.detachments, 1);
  ASSERT_EQ(d.log.events.size(), 3u);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(d.log.events[static_cast<std::size_t>(i)].kind, EventKind::kImpact);
    EXPECT_NEAR(d.log.events[static_cast<std::size_t>(i)].kinetic_loss_J, kinetic, 1e-9 * kinetic);
  }
  EXPECT_EQ(d.log.events[2].kind, EventKind::kDetachment);
  EXPECT_EQ(d.log.events[2].contact, 0);
  EXPECT_NEAR(d.log.impact_J, kinetic, 1e-9 * kinetic);

  // The same wedge again at the same instant: no second jam.
  wedged(d, q, u);
  const DecisionOutcome again = d.Decide(a_g, q, u);
  EXPECT_EQ(again.status, RunStatus::kPainleve);
  EXPECT_NE(again.message.find("Painleve"), std::string::npos) << again.message;
  EXPECT_EQ(d.log.impacts, 1);

  // The rule off: the first wedge is a Painleve situation.
  Decision off(m);
  off.policy.jam = false;
  wedged(off, q, u);
  EXPECT_EQ(off.Decide(a_g, q, u).status, RunStatus::kPainleve);
  EXPECT_EQ(off.log.impacts, 0);
  EXPECT_FALSE(off.memory.jammed_here);
}

// --- The event-cascade limit [§3.11] --------------------------------------------------------

// Decisions at one instant count against max_events_at_one_instant: that many further decisions
// at the same time pass, the next ends with kEventCascade and leaves the state alone; a
// decision at a later time starts a new count.
TEST(ModeDecision, MoreDecisionsAtOneInstantThanTheLimitIsAnEventCascade) {
  for (const int limit : {0, 3, 64}) {
    SCOPED_TRACE("limit " + std::to_string(limit));
    const model::Model m = FreeDeck(0.5, 0.3);
    Decision d(m);
    d.policy.max_events_at_one_instant = limit;
    VectorXd q = Vector3d(-0.005, 0.0, 0.0), u = Vector3d(0.1, 0.0, 0.0);  // open, free flight
    for (int k = 0; k <= limit; ++k) {
      ASSERT_EQ(d.Decide(Vector2d::Zero(), q, u).status, RunStatus::kOk) << "decision " << k;
    }
    const VectorXd q_before = q, u_before = u;
    const DecisionOutcome r = d.Decide(Vector2d::Zero(), q, u);
    EXPECT_EQ(r.status, RunStatus::kEventCascade);
    EXPECT_EQ(r.message,
              "event cascade: more than " + std::to_string(limit) + " events at t = 2 s");
    EXPECT_EQ(q, q_before);
    EXPECT_EQ(u, u_before);
    DecisionInstant later{kT + 1e-3, Vector2d::Zero(), {}};
    EXPECT_EQ(
        DecideModes(m, d.policy, d.scales, later, q, u, d.modes, d.memory, d.forces, d.ws, d.log)
            .status,
        RunStatus::kOk);
    EXPECT_EQ(d.memory.events_here, 0);
  }
}

// The instant in a message keeps its significant digits however early it is (a fixed six
// decimals would print 0.000000 here).
TEST(ModeDecision, AnEarlyCascadeNamesItsInstantWithItsSignificantDigits) {
  const model::Model m = FreeDeck(0.5, 0.3);
  Decision d(m);
  d.t_s = 2.5e-7;
  d.policy.max_events_at_one_instant = 0;
  VectorXd q = Vector3d(-0.005, 0.0, 0.0), u = Vector3d(0.1, 0.0, 0.0);
  ASSERT_EQ(d.Decide(Vector2d::Zero(), q, u).status, RunStatus::kOk);
  const DecisionOutcome r = d.Decide(Vector2d::Zero(), q, u);
  EXPECT_EQ(r.status, RunStatus::kEventCascade);
  EXPECT_EQ(r.message, "event cascade: more than 0 events at t = 2.5e-07 s");
}

}  // namespace
}  // namespace skewbridge::dynamics::mode_decision_test
