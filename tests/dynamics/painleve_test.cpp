// A Painleve situation reached through the event-driven integrator [docs/theory.md §3; Pfeiffer and
// Glocker 1996, ch. 6]: a free deck slides with its obtuse corner P2 along the +x abutment while
// the ground pushes it into the face. For a single sliding contact the acceleration-level
// problem is the scalar LCP w = A lambda_N + b with A = w_N^T M^-1 (w_N - mu s w_T) and
// b = w_N^T M^-1 h; with A < 0 and b < 0 it has no solution, and the run must end there with the
// Painleve status instead of returning forces.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "records/excitations.h"
#include "solver/contact/kinematics.h"
#include "solver/dynamics/simulate.h"
#include "tests/contact/test_models.h"

namespace skewbridge::dynamics::painleve_test {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(Simulate, SlidingCornerWithNegativeContactMassEndsInPainleveAtClosure) {
  // Free deck (K = C = 0), a = 45 deg, eta0 = 2.5, L = 20 m, m = 1000 kg, mu = 5.
  const double a = 45.0 * kDeg, mu = 5.0, delta = 0.05, a_g = -1.0;
  const model::Model m = contact::testing::FreeDeck(45.0, 2.5, 20.0, delta, 0.5, mu,
                                                    model::AbutmentSet::kPlusX, 1000.0);
  // A small rotation brings P2 (contact 1) nearer to the face than P1: with no torque before
  // contact, theta stays theta0 and P1 keeps a gap of (W / cos a) sin(theta0) when P2 closes.
  const double theta0 = 0.01;
  Eigen::Vector3d q0(0.0, 0.0, theta0);
  const double g2_at_x0 = contact::Gap(m, 1, q0);
  // Place the deck so that P2's gap is g0 = 0.1 mm; the ground's push a_g < 0 along x closes it
  // at g0 = (1/2) |a_g| cos(a) t^2 (the relative acceleration is -a_g along x).
  const double g0 = 1e-4;
  q0.x() = (g2_at_x0 - g0) / std::cos(a);
  ASSERT_NEAR(contact::Gap(m, 1, q0), g0, 1e-15);
  ASSERT_GT(contact::Gap(m, 0, q0), 0.05);
  const double t_close = std::sqrt(2.0 * g0 / (std::abs(a_g) * std::cos(a)));

  // The contact problem at closure: choose the slip sign s that makes A negative.
  contact::ContactKinematics kin;
  kin.Resize(m);
  contact::Evaluate(m, q0, Eigen::Vector3d::Zero(), kin);
  const Eigen::Vector3d Minv = m.inverse_mass_diagonal();
  const Eigen::Vector3d w_N = kin.W_N.col(1), w_T = kin.W_T.col(1);
  const int s = w_N.dot(Minv.asDiagonal() * w_T) > 0.0 ? 1 : -1;
  const double A = w_N.dot(Minv.asDiagonal() * (w_N - mu * s * w_T));
  ASSERT_LT(A, 0.0) << "not a Painleve configuration";
  const Eigen::Vector3d h(-m.body(0).mass_kg * a_g, 0.0, 0.0);  // -M r a_g
  const double b = w_N.dot(Minv.asDiagonal() * h);
  ASSERT_LT(b, 0.0) << "the ground must push the corner into the face";

  // Sliding at 1 m/s along s t; the approach speed at closure, sqrt(2 g0 |a_g| cos a) = 0.012
  // m/s, is below the accumulation threshold 0.05 |a_g| / (1 rad/s), so the corner closes
  // plastically and keeps sliding in the direction s.
  const Eigen::Vector2d t_face = m.contact(1).face.tangent;
  InitialState initial;
  initial.q = q0;
  initial.u = Eigen::Vector3d(s * t_face.x(), s * t_face.y(), 0.0);
  const double slip_at_close = s * 1.0 - a_g * std::sin(a) * t_close;  // t . (-a_g, 0) = -a_g sin a
  ASSERT_EQ(slip_at_close > 0.0 ? 1 : -1, s);
  const records::SampledExcitation push(1.0, {a_g, a_g});
  model::RunControl control;
  control.end_time_s = 1.0;
  control.accumulation_threshold = 0.05;
  SimulationWorkspace ws(m);
  const RunResult r = Simulate(m, push, control, ws, initial);

  EXPECT_EQ(r.status, RunStatus::kPainleve);
  EXPECT_STREQ(ToString(r.status), "painleve");
  EXPECT_NEAR(r.end_time_s, t_close, 1e-9 * t_close);
  EXPECT_NE(r.message.find("Painleve"), std::string::npos) << r.message;
  EXPECT_EQ(r.impacts, 0);
  EXPECT_EQ(r.plastic_closures, 1);
}

}  // namespace
}  // namespace skewbridge::dynamics::painleve_test
