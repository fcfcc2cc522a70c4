// A compliant deck-deck joint (springs between one deck's corners and its neighbour's end face,
// solver/dynamics/compliant_run.h) against what the integrator does not compute: the momentum of
// two free decks (conserved: the joint's forces are internal), the closed-form strike of two masses
// on a linear spring-dashpot (duration and restitution from the damping ratio of the reduced
// mass), and the abutment as the limit of a neighbour ever heavier.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "records/excitations.h"
#include "solver/dynamics/compliant_run.h"
#include "solver/model/builders.h"
#include "solver/model/multispan.h"

namespace skewbridge::dynamics::compliant_joint_test {
namespace {

constexpr double kPi = std::numbers::pi;

// Two free decks (no support) of masses m0, m1 at skew a, the joint gap `gap_m` between them.
model::Model TwoFreeDecks(double m0, double m1, double skew_deg, double gap_m) {
  model::MultiDeckSpec spec;
  for (const double m : {m0, m1}) {
    model::Body b;
    b.mass_kg = m;
    b.geometry = {30.0, 10.0, skew_deg * kPi / 180.0};
    b.inertia_kgm2 = model::UniformDeckInertia(m, b.geometry);
    spec.decks.push_back(b);
  }
  spec.joints = {model::JointSpec{gap_m, 0.5, 0.0}};
  spec.gap_minus_m = spec.gap_plus_m = 1.0;
  return model::BuildMultiDeckModel(spec, "two decks");
}

// The restitution and duration of a linear spring-dashpot that pulls on nothing, for a mass on
// it with damping ratio zeta < 1/sqrt(2) and natural frequency w0 [Schwager and Poeschel 2007;
// docs/compliant.md §3].
struct Strike {
  double restitution = 0.0;
  double duration_s = 0.0;
};
Strike SpringDashpotStrike(double zeta, double w0) {
  const double root = std::sqrt(1.0 - zeta * zeta);
  const double wt = kPi - std::atan2(2.0 * zeta * root, 1.0 - 2.0 * zeta * zeta);
  return {std::exp(-zeta * wt / root) * std::abs(std::cos(wt) - zeta / root * std::sin(wt)),
          wt / (w0 * root)};
}

// Linear momentum (x, y) and angular momentum about the world origin of the decks at (q, u).
Eigen::Vector3d Momentum(const model::Model& m, const Eigen::VectorXd& q,
                         const Eigen::VectorXd& u) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int b = 0; b < m.n_bodies(); ++b) {
    const model::Body& body = m.body(b);
    const Eigen::Vector2d x = body.rest_position_m + q.segment<2>(3 * b);
    const Eigen::Vector2d v = u.segment<2>(3 * b);
    p.head<2>() += body.mass_kg * v;
    p[2] += body.inertia_kgm2 * u[3 * b + 2] + body.mass_kg * (x.x() * v.y() - x.y() * v.x());
  }
  return p;
}

TEST(CompliantJoint, TwoDecksOnASpringDashpotMeetTheTwoMassClosedForm) {
  // Square ends (a = 0): the five springs along the joint act as one spring-dashpot k, c on the
  // relative displacement x0 - x1, so the strike is the point mass's with the reduced mass
  // m0 m1 / (m0 + m1). Deck 0 arrives at v0, deck 1 at rest.
  const double m0 = 1.0e6, m1 = 2.0e6, gap = 0.05, v0 = 0.5, k = 4.0e8, zeta = 0.2;
  const model::Model rigid = TwoFreeDecks(m0, m1, 0.0, gap);
  ASSERT_EQ(rigid.contact(2).name, "D0.P1/D1");
  ASSERT_EQ(rigid.contact(3).name, "D0.P2/D1");
  const double mu = m0 * m1 / (m0 + m1), w0 = std::sqrt(k / mu);
  const double c = 2.0 * zeta * std::sqrt(k * mu);
  const std::vector<CompliantSpring> springs = SpringDashpots(rigid, 2, 3, k, c, 5, "J0");
  ASSERT_EQ(springs.size(), 5u);
  InitialState initial;
  initial.q = Eigen::VectorXd::Zero(6);
  initial.u = Eigen::VectorXd::Zero(6);
  initial.u[0] = v0;
  records::PulseExcitation still(records::PulseShape::kSine, 0.0, 2.0 * kPi);
  model::RunControl control;
  control.end_time_s = gap / v0 + 1.0;
  const CompliantRunResult out =
      SimulateCompliant(WithoutContacts(rigid), springs, still, control, initial);
  const RunResult& r = out.run;
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  EXPECT_EQ(r.impacts, 1);
  // Momentum: the joint's forces are internal.
  const Eigen::Vector3d p0 = Momentum(rigid, initial.q, initial.u);
  const Eigen::Vector3d p1 = Momentum(rigid, r.q_end, r.u_end);
  EXPECT_LT(std::abs(p1[0] - p0[0]), 1e-10 * m0 * v0);
  EXPECT_LT(std::abs(p1[1]), 1e-10 * m0 * v0);
  // Restitution: the separation speed over the approach speed.
  const Strike closed = SpringDashpotStrike(zeta, w0);
  const double separation = r.u_end[3] - r.u_end[0];
  EXPECT_NEAR(separation / v0, closed.restitution, 1e-7) << "closed form " << closed.restitution;
  // Duration: the decks part where k d + c d' = 0, at d = c e v0 / k beyond the gap; after it the
  // gap opens at e v0, so the end state dates the parting; the strike began at gap / v0.
  const double e = closed.restitution;
  const double d_end = r.q_end[0] - r.q_end[3] - gap;  // the deformation at the end (< 0: open)
  const double d_part = c * e * v0 / k;
  const double t_part = *control.end_time_s - (d_part - d_end) / (e * v0);
  EXPECT_NEAR(t_part - gap / v0, closed.duration_s, 1e-7 * closed.duration_s)
      << "closed form " << closed.duration_s;
  EXPECT_LT(std::abs(r.u_end[2]) + std::abs(r.u_end[5]), 1e-12);
  // The ledger: the kinetic energy left plus the dashpot's dissipation is the initial one.
  EXPECT_LT(std::abs(r.energy.balance_error_J), 1e-8 * 0.5 * m0 * v0 * v0);
  EXPECT_NEAR(out.joint_dissipated_J / (0.5 * mu * v0 * v0), 1.0 - e * e, 1e-7);
}

TEST(CompliantJoint, ASkewJointOfBackfillSpringsConservesMomentum) {
  // Skew decks (a = 30 deg), deck 0 turned by 0.01 rad and moving at 0.6 m/s along x and
  // 0.1 m/s along y: one corner strikes first and the hysteresis turns both decks. The linear and
  // angular momenta stay the initial ones, and the ledger closes with the hysteresis.
  const double m0 = 1.0e6, m1 = 1.5e6, gap = 0.05;
  const model::Model rigid = TwoFreeDecks(m0, m1, 30.0, gap);
  const double wall = 10.0 / std::cos(30.0 * kPi / 180.0);
  const joint::HyperbolicGap law{20.3e6 * wall, 20.3e6 * wall, 0.7, 326e3 * wall, 0.0};
  const std::vector<CompliantSpring> springs = WallSprings(rigid, 2, 3, law, 5, "J0");
  InitialState initial;
  initial.q = Eigen::VectorXd::Zero(6);
  initial.q[2] = 0.01;
  initial.u = Eigen::VectorXd::Zero(6);
  initial.u[0] = 0.6;
  initial.u[1] = 0.1;
  records::PulseExcitation still(records::PulseShape::kSine, 0.0, 2.0 * kPi);
  model::RunControl control;
  control.end_time_s = 2.0;
  const CompliantRunResult out =
      SimulateCompliant(WithoutContacts(rigid), springs, still, control, initial);
  const RunResult& r = out.run;
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  EXPECT_GE(r.impacts, 1);
  EXPECT_GT(out.max_spring_force_N.maxCoeff(), 1e5);
  EXPECT_GT(std::abs(r.u_end[5]), 1e-4) << "the skew joint turns deck 1";
  const Eigen::Vector3d p0 = Momentum(rigid, initial.q, initial.u);
  const Eigen::Vector3d p1 = Momentum(rigid, r.q_end, r.u_end);
  const double scale = m0 * 0.6;
  EXPECT_LT(std::abs(p1[0] - p0[0]), 1e-10 * scale);
  EXPECT_LT(std::abs(p1[1] - p0[1]), 1e-10 * scale);
  EXPECT_LT(std::abs(p1[2] - p0[2]), 1e-10 * scale * 60.0) << p0[2] << " -> " << p1[2];
  const double input = 0.5 * m0 * (0.6 * 0.6 + 0.1 * 0.1);
  EXPECT_GT(out.joint_dissipated_J, 1e-3 * input);
  EXPECT_LT(std::abs(r.energy.balance_error_J), 1e-6 * input);
}

TEST(CompliantJoint, AgainstAnEverHeavierNeighbourItIsTheAbutment) {
  // Deck 0 strikes a neighbour at rest whose mass and inertia grow by 100 each time; the same
  // springs on a ground face where the neighbour's end face rests give the abutment's strike.
  // Deck 0's end velocities tend to the abutment's, the difference falling as the mass ratio.
  const double m0 = 1.0e6, gap = 0.05;
  InitialState initial;
  initial.q = Eigen::VectorXd::Zero(6);
  initial.q[2] = 0.01;
  initial.u = Eigen::VectorXd::Zero(6);
  initial.u[0] = 0.6;
  records::PulseExcitation still(records::PulseShape::kSine, 0.0, 2.0 * kPi);
  model::RunControl control;
  control.end_time_s = 1.5;
  const double wall = 10.0 / std::cos(30.0 * kPi / 180.0);
  const joint::HyperbolicGap law{20.3e6 * wall, 20.3e6 * wall, 0.7, 326e3 * wall, 0.0};
  // The abutment: deck 0 alone, the springs on the ground face at the neighbour's face at rest.
  const model::Model pair = TwoFreeDecks(m0, m0, 30.0, gap);
  std::vector<CompliantSpring> ground = WallSprings(pair, 2, 3, law, 5, "+x");
  for (CompliantSpring& s : ground) {
    s.face.point_m += pair.body(1).rest_position_m;
    s.face.body = model::kGround;
  }
  const model::Model alone({pair.body(0)}, Eigen::MatrixXd::Zero(3, 3), Eigen::MatrixXd::Zero(3, 3),
                           model::GroundInfluence(1), {}, "deck 0");
  InitialState one;
  one.q = initial.q.head(3);
  one.u = initial.u.head(3);
  const CompliantRunResult abutment = SimulateCompliant(alone, ground, still, control, one);
  ASSERT_EQ(abutment.run.status, RunStatus::kOk) << abutment.run.message;
  ASSERT_GE(abutment.run.impacts, 1);
  const Eigen::Vector3d u_abutment = abutment.run.u_end;
  std::vector<double> errors;
  for (const double ratio : {1e2, 1e4, 1e6}) {
    const model::Model rigid = TwoFreeDecks(m0, m0 * ratio, 30.0, gap);
    const CompliantRunResult out = SimulateCompliant(
        WithoutContacts(rigid), WallSprings(rigid, 2, 3, law, 5, "J0"), still, control, initial);
    ASSERT_EQ(out.run.status, RunStatus::kOk) << out.run.message;
    const Eigen::Vector3d du = out.run.u_end.head(3) - u_abutment;
    errors.push_back(std::hypot(du[0], du[1], du[2] * 15.0) / 0.6);
  }
  for (std::size_t i = 1; i < errors.size(); ++i) {
    EXPECT_GT(errors[i - 1] / errors[i], 30.0) << errors[i - 1] << " -> " << errors[i];
  }
  EXPECT_LT(errors.back(), 1e-5);
}

TEST(CompliantJoint, FrictionAndKeysStayOnTheAbutments) {
  // Wall friction and shear keys belong to a ground face: on a joint they are refused.
  const model::Model rigid = TwoFreeDecks(1e6, 1e6, 30.0, 0.05);
  const joint::HyperbolicGap law{1e8, 1e8, 0.7, 1e6, 0.0};
  std::vector<CompliantSpring> springs = WallSprings(rigid, 2, 3, law, 2, "J0");
  springs[0].mu = 0.3;
  records::PulseExcitation still(records::PulseShape::kSine, 0.0, 2.0 * kPi);
  model::RunControl control;
  control.end_time_s = 0.1;
  EXPECT_THROW(SimulateCompliant(WithoutContacts(rigid), springs, still, control), InputError);
}

}  // namespace
}  // namespace skewbridge::dynamics::compliant_joint_test
