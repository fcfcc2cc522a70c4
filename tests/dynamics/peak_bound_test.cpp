/// The free step's peak bound (solver/dynamics/peak_bound.h) [docs/theory.md §3.20] against a
/// dense evaluation of every coordinate along the exact flow, propagated on the augmented path
/// (the matrix exponential, no modal code): random states and inputs, steps around a velocity
/// root, resonant harmonics, an undamped deck and long steps, where the interpolation error
/// term carries the bound. The bound must hold everywhere and stay close to the true peak where
/// a velocity changes sign (a loose bound would skip no search).

#include "solver/dynamics/peak_bound.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "solver/dynamics/linear_flow.h"
#include "tests/dynamics/eccentric_deck.h"

namespace skewbridge::dynamics::peak_bound_test {
namespace {

TEST(HermiteAbsBound, BoundsRandomCubicsAndIsTightAtTheirPeaks) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> ratios;  // (bound - max |H|) / (the unhalved hull - max |H|)
  for (int s = 0; s < 2000; ++s) {
    const double h = 0.01 * (1.0 + unit(rng));
    const double q0 = unit(rng), q1 = unit(rng);
    const double u0 = 400.0 * unit(rng), u1 = 400.0 * unit(rng);
    double peak = 0.0;
    for (int j = 0; j <= 4000; ++j) {
      const double x = j / 4000.0;
      const double H = q0 * (2 * x * x * x - 3 * x * x + 1) + h * u0 * (x * x * x - 2 * x * x + x) +
                       q1 * (-2 * x * x * x + 3 * x * x) + h * u1 * (x * x * x - x * x);
      peak = std::max(peak, std::abs(H));
    }
    const double bound = HermiteAbsBound(q0, u0, q1, u1, h);
    ASSERT_GE(bound, peak) << "cubic " << s;
    const double b[4] = {q0, q0 + h * u0 / 3.0, q1 - h * u1 / 3.0, q1};
    const double hull = BernsteinAbsBound(b, 0);
    if (hull - peak > 1e-3 * peak) ratios.push_back((bound - peak) / (hull - peak));
  }
  ASSERT_GT(ratios.size(), 500u);
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  // Each halving cuts the hull's excess by about four: two leave about a sixteenth (one would
  // leave about a quarter).
  EXPECT_LT(ratios[ratios.size() / 2], 0.15);
}

// BernsteinAbsBound with every piece halved (no piece left whole below what the curve reaches).
double FullHull(const double b[4], int depth) {
  if (depth == 0) return std::max({std::abs(b[0]), std::abs(b[1]), std::abs(b[2]), std::abs(b[3])});
  const double m01 = 0.5 * (b[0] + b[1]), m12 = 0.5 * (b[1] + b[2]), m23 = 0.5 * (b[2] + b[3]);
  const double m012 = 0.5 * (m01 + m12), m123 = 0.5 * (m12 + m23);
  const double mid = 0.5 * (m012 + m123);
  const double left[4] = {b[0], m01, m012, mid};
  const double right[4] = {mid, m123, m23, b[3]};
  return std::max(FullHull(left, depth - 1), FullHull(right, depth - 1));
}

TEST(BernsteinAbsBound, HalvesOnlyAroundThePeakAndBoundsRandomCubics) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> ratios;  // four halvings: (bound - max |H|) / (the unhalved hull - max |H|)
  for (int s = 0; s < 2000; ++s) {
    const double h = 0.01 * (1.0 + unit(rng));
    const double q0 = unit(rng), q1 = unit(rng);
    const double u0 = 400.0 * unit(rng), u1 = 400.0 * unit(rng);
    const double b[4] = {q0, q0 + h * u0 / 3.0, q1 - h * u1 / 3.0, q1};
    double peak = 0.0;  // max |H| by dense evaluation of the Hermite form
    for (int j = 0; j <= 4000; ++j) {
      const double x = j / 4000.0;
      const double H = q0 * (2 * x * x * x - 3 * x * x + 1) + h * u0 * (x * x * x - 2 * x * x + x) +
                       q1 * (-2 * x * x * x + 3 * x * x) + h * u1 * (x * x * x - x * x);
      peak = std::max(peak, std::abs(H));
    }
    for (int depth = 0; depth <= 6; ++depth) {
      const double bound = BernsteinAbsBound(b, depth), full = FullHull(b, depth);
      // Rounding of the midpoints: a few ulps of the control points.
      ASSERT_GE(bound, peak * (1.0 - 1e-14)) << "cubic " << s << " depth " << depth;
      // Never looser than halving every piece.
      ASSERT_LE(bound, full) << "cubic " << s << " depth " << depth;
    }
    const double full = FullHull(b, 0), bound = HermiteAbsBound(q0, u0, q1, u1, h, 4);
    ASSERT_GE(bound, peak) << "cubic " << s;
    if (full - peak > 1e-3 * peak) ratios.push_back((bound - peak) / (full - peak));
  }
  ASSERT_GT(ratios.size(), 500u);
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  // Four halvings leave about 1/256 of the hull's excess (two, about 1/16).
  EXPECT_LT(ratios[ratios.size() / 2], 0.01);
}

struct Step {
  Eigen::VectorXd z;  // (q, u, a, slope, p, k) at the step's start
  double tau_s = 0.01;
  double omega_radps = 0.0;
};

// The dense maximum of |q_i| over 1024 points of the step along the augmented flow, and the
// state at the step's end.
void Dense(LinearFlow& augmented, const Step& step, int n, Eigen::VectorXd& peak,
           Eigen::VectorXd& z_end) {
  constexpr int kPoints = 1024;
  const FreePropagator& p = augmented.Propagator(step.tau_s / kPoints, step.omega_radps, false);
  Eigen::VectorXd z = step.z, z_next = z;
  peak = z.head(n).cwiseAbs();
  for (int j = 1; j <= kPoints; ++j) {
    augmented.Apply(p, z, z_next);
    z.swap(z_next);
    peak = peak.cwiseMax(z.head(n).cwiseAbs());
  }
  z_end = z;
}

// Over the coordinates whose velocity changes sign in a step (a peak inside it): (bound - peak)
// / (peak - max end), the bound's excess over the true peak per unit of the peak's rise.
struct Stats {
  std::vector<double> gaps;
  int roots() const { return static_cast<int>(gaps.size()); }
  double median() {
    std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
    return gaps[gaps.size() / 2];
  }
};

// Random steps of one kind: every coordinate's dense peak must lie within the bound.
Stats CheckSteps(double xi, int count, unsigned seed, double q_scale, double u_scale,
                 double a_scale, double tau_s, bool resonant) {
  const model::Model model = testing::EccentricDeck(xi);
  LinearFlow modal(model.M(), model.K(), model.C(), model.r());
  LinearFlow augmented(model.M(), model.K(), model.C(), model.r(), FlowPath::kAugmented);
  EXPECT_TRUE(modal.modal());
  ModalPeakBound bound(modal.modal_flow());
  EXPECT_TRUE(bound.applies());
  const int n = model.n_dof();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Stats stats;
  for (int s = 0; s < count; ++s) {
    Step step;
    step.tau_s = tau_s;
    step.z = Eigen::VectorXd::Zero(modal.augmented_size());
    for (int i = 0; i < n; ++i) {
      const double length = i % 3 == 2 ? 1.0 / 15.0 : 1.0;  // theta in rad, x and y in m
      step.z[i] = q_scale * length * unit(rng);
      step.z[n + i] = u_scale * length * unit(rng);
    }
    for (int j = 0; j < 8; ++j) step.z[2 * n + j] = a_scale * unit(rng);
    step.z[2 * n + 2] *= 50.0;  // slopes of a record: the acceleration changes by 0.5 a per 0.01 s
    step.z[2 * n + 3] *= 50.0;
    if (resonant) {
      step.omega_radps = std::sqrt(modal.modal_flow().w2()[s % n]);
    } else {
      step.omega_radps = s % 2 == 0 ? 0.0 : 40.0 * std::abs(unit(rng));
    }
    if (step.omega_radps == 0.0) step.z.tail(4).setZero();  // a record's piece: no harmonic part
    Eigen::VectorXd peak, z_end;
    Dense(augmented, step, n, peak, z_end);
    Eigen::VectorXd z_modal_end = step.z;
    modal.Apply(modal.Propagator(step.tau_s, step.omega_radps, false), step.z, z_modal_end);
    bound.Step(modal.modal_coordinates().data(), step.tau_s, step.omega_radps);
    for (int i = 0; i < n; ++i) {
      const double q0 = step.z[i], u0 = step.z[n + i];
      const double q1 = z_modal_end[i], u1 = z_modal_end[n + i];
      const double b = bound.PeakBound(i, q0, u0, q1, u1, step.tau_s);
      EXPECT_LE(peak[i], b) << "step " << s << " coordinate " << i;
      const double ends = std::max(std::abs(q0), std::abs(q1));
      if (u0 * u1 < 0.0 && peak[i] - ends > 1e-6 * peak[i]) {
        stats.gaps.push_back((b - peak[i]) / (peak[i] - ends));
      }
    }
  }
  return stats;
}

// Random steps of the deck: every corner's dense largest travel must lie within CornerPeakBound.
void CheckCorners(double xi, int count, unsigned seed, double q_scale, double u_scale,
                  double a_scale, double tau_s) {
  const model::Model model = testing::EccentricDeck(xi);
  LinearFlow modal(model.M(), model.K(), model.C(), model.r());
  LinearFlow augmented(model.M(), model.K(), model.C(), model.r(), FlowPath::kAugmented);
  ModalPeakBound bound(modal.modal_flow());
  const model::Body& body = model.bodies()[0];
  const double nx = std::cos(body.geometry.skew_rad), ny = -std::sin(body.geometry.skew_rad);
  double A[2], B[2], radius = 0.0;
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector2d P = model::Corner(body.geometry, k + 1);
    A[k] = nx * P.x() + ny * P.y();
    B[k] = -nx * P.y() + ny * P.x();
    radius = std::max(radius, P.norm());
  }
  // Corner k's travel and rate at the state z (P_3 = -P_1, P_4 = -P_2).
  const auto travel = [&](const Eigen::VectorXd& z, int k, double& rate) {
    const double sign = k < 2 ? 1.0 : -1.0;
    const int j = k % 2;
    const double th = z[2], uth = z[5];
    rate = nx * z[3] + ny * z[4] + sign * uth * (-std::sin(th) * A[j] + std::cos(th) * B[j]);
    return nx * z[0] + ny * z[1] + sign * ((std::cos(th) - 1.0) * A[j] + std::sin(th) * B[j]);
  };
  const int n = model.n_dof();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int roots = 0;
  for (int s = 0; s < count; ++s) {
    Eigen::VectorXd z = Eigen::VectorXd::Zero(modal.augmented_size());
    for (int i = 0; i < n; ++i) {
      const double length = i % 3 == 2 ? 1.0 / 15.0 : 1.0;
      z[i] = q_scale * length * unit(rng);
      z[n + i] = u_scale * length * unit(rng);
    }
    z[2 * n] = a_scale * unit(rng);
    z[2 * n + 1] = a_scale * unit(rng);
    z[2 * n + 2] = 50.0 * a_scale * unit(rng);
    z[2 * n + 3] = 50.0 * a_scale * unit(rng);
    constexpr int kPoints = 1024;
    const FreePropagator& p = augmented.Propagator(tau_s / kPoints, 0.0, false);
    double peak[4], f0[4], r0[4], f1[4], r1[4];
    for (int k = 0; k < 4; ++k) peak[k] = std::abs(f0[k] = travel(z, k, r0[k]));
    Eigen::VectorXd y = z, y_next = z;
    for (int j = 1; j <= kPoints; ++j) {
      augmented.Apply(p, y, y_next);
      y.swap(y_next);
      double rate;
      for (int k = 0; k < 4; ++k) peak[k] = std::max(peak[k], std::abs(travel(y, k, rate)));
    }
    Eigen::VectorXd z1 = z;
    modal.Apply(modal.Propagator(tau_s, 0.0, false), z, z1);
    bound.Step(modal.modal_coordinates().data(), tau_s, 0.0);
    double dx[4], dy[4], dth[4];
    const double size = std::abs(nx) * bound.Derivatives(0, dx) +
                        std::abs(ny) * bound.Derivatives(1, dy) +
                        radius * bound.Derivatives(2, dth);
    for (int k = 0; k < 4; ++k) {
      f1[k] = travel(z1, k, r1[k]);
      const double b =
          CornerPeakBound(nx, ny, radius, dx, dy, dth, size, f0[k], r0[k], f1[k], r1[k], tau_s);
      EXPECT_LE(peak[k], b) << "step " << s << " corner " << k;
      if (r0[k] * r1[k] < 0.0) ++roots;
    }
  }
  EXPECT_GT(roots, 10);
}

TEST(CornerPeakBound, HoldsOnRandomStepsOfADampedDeck) {
  CheckCorners(0.05, 300, 7, 0.05, 0.5, 5.0, 0.01);
}

TEST(CornerPeakBound, HoldsOnLargeTurnsAndLongSteps) {
  // Rotations of a few tenths of a radian: the turn's products in the fourth derivative count.
  CheckCorners(0.0, 300, 8, 0.3, 3.0, 5.0, 0.08);
}

// A random record step of the deck's flow: its length tau_s (returned, s), the start z (positions
// up to 0.05 of each coordinate's length, velocities up to 0.5, the generator's accelerations
// and slopes) and the end z1 along the flow.
double DrawRecordStep(LinearFlow& modal, std::mt19937& rng, Eigen::VectorXd& z,
                      Eigen::VectorXd& z1) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const int n = modal.n_dof();
  const double tau_s = 0.01 * (1.0 + 0.5 * unit(rng));
  z = Eigen::VectorXd::Zero(modal.augmented_size());
  for (int i = 0; i < n; ++i) {
    const double length = i % 3 == 2 ? 1.0 / 15.0 : 1.0;
    z[i] = 0.05 * length * unit(rng);
    z[n + i] = 0.5 * length * unit(rng);
  }
  for (int j = 0; j < 4; ++j) z[2 * n + j] = 5.0 * unit(rng) * (j >= 2 ? 50.0 : 1.0);
  z1 = z;
  modal.Apply(modal.Propagator(tau_s, 0.0, false), z, z1);
  return tau_s;
}

// Running maxima to test a bound `whole` against: at it and one double either side, at the ends'
// `hull` and either side, at the larger end `ends`, a random one above and below it, and zero.
std::array<double, 10> MaximaAround(double whole, double hull, double ends, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double inf = std::numeric_limits<double>::infinity();
  return {whole, std::nextafter(whole, inf),          std::nextafter(whole, 0.0),
          hull,  std::nextafter(hull, inf),           std::nextafter(hull, 0.0),
          ends,  whole * (1.0 + std::abs(unit(rng))), whole * std::abs(unit(rng)),
          0.0};
}

// FreeStepPeaks::PeakBelow against its definition, the whole bound written out from
// ModalPeakBound::Derivatives (HermiteAbsBound + M4 h^4 / 384, rounded up) compared with the
// running maximum, on random steps and maxima at, just around and far from the bound and the
// ends' hull.
TEST(FreeStepPeaks, PeakBelowIsTheWholeBoundBelowTheMaximum) {
  const model::Model model = testing::EccentricDeck(0.05);
  LinearFlow modal(model.M(), model.K(), model.C(), model.r());
  ModalPeakBound bound(modal.modal_flow());
  FreeStepPeaks peaks(&modal.modal_flow());
  const int n = model.n_dof();
  std::mt19937 rng(21);
  long below = 0, not_below = 0;
  for (int s = 0; s < 400; ++s) {
    Eigen::VectorXd z, z1;
    const double tau_s = DrawRecordStep(modal, rng, z, z1);
    const double* Y = modal.modal_coordinates().data();
    bound.Step(Y, tau_s, 0.0);
    peaks.Arm(true, Y, tau_s, 0.0);
    for (int i = 0; i < n; ++i) {
      const double q0 = z[i], u0 = z[n + i], q1 = z1[i], u1 = z1[n + i];
      double d[4];
      const double size = bound.Derivatives(i, d);
      const double h2 = tau_s * tau_s;
      const double hull = HermiteAbsBound(q0, u0, q1, u1, tau_s);
      const double whole = (hull + d[3] * (h2 * h2 / 384.0)) * (1.0 + 1e-12) + 1e-12 * size;
      for (const double best :
           MaximaAround(whole, hull, std::max(std::abs(q0), std::abs(q1)), rng)) {
        const bool expected = whole < best;
        ASSERT_EQ(peaks.PeakBelow(i, q0, u0, q1, u1, tau_s, best), expected)
            << "step " << s << " coordinate " << i << " best " << best;
        (expected ? below : not_below) += 1;
      }
    }
    peaks.Disarm();
    // Unarmed, nothing is proved.
    ASSERT_FALSE(peaks.PeakBelow(0, z[0], z[n], z1[0], z1[n], tau_s, 1e300));
  }
  EXPECT_GT(below, 1000);
  EXPECT_GT(not_below, 1000);
}

// FreeStepPeaks' travel bound armed with the decks' running maxima against CornerPeakBound
// written out from ModalPeakBound::Derivatives: compared with the deck's maximum it gives the
// same answer for maxima at, just around and far from the bound and the ends' hull, and where it
// is finite it is CornerPeakBound's value.
TEST(FreeStepPeaks, TheTravelBoundAgainstTheMaximumIsCornerPeakBounds) {
  const model::Model model = testing::EccentricDeck(0.05);
  LinearFlow modal(model.M(), model.K(), model.C(), model.r());
  ModalPeakBound bound(modal.modal_flow());
  FreeStepPeaks peaks(&modal.modal_flow());
  const model::Body& body = model.bodies()[0];
  const double nx = std::cos(body.geometry.skew_rad), ny = -std::sin(body.geometry.skew_rad);
  const Eigen::Vector2d P = model::Corner(body.geometry, 1);
  const double A = nx * P.x() + ny * P.y(), B = -nx * P.y() + ny * P.x(), radius = P.norm();
  // Corner 1's travel and rate at the state z.
  const auto travel = [&](const Eigen::VectorXd& z, double& rate) {
    const double th = z[2], uth = z[5];
    rate = nx * z[3] + ny * z[4] + uth * (-std::sin(th) * A + std::cos(th) * B);
    return nx * z[0] + ny * z[1] + (std::cos(th) - 1.0) * A + std::sin(th) * B;
  };
  std::mt19937 rng(22);
  long below = 0, not_below = 0;
  for (int s = 0; s < 400; ++s) {
    Eigen::VectorXd z, z1;
    const double tau_s = DrawRecordStep(modal, rng, z, z1);
    const double* Y = modal.modal_coordinates().data();
    bound.Step(Y, tau_s, 0.0);
    double r0, r1;
    const double f0 = travel(z, r0), f1 = travel(z1, r1);
    double dx[4], dy[4], dth[4];
    const double size = std::abs(nx) * bound.Derivatives(0, dx) +
                        std::abs(ny) * bound.Derivatives(1, dy) +
                        radius * bound.Derivatives(2, dth);
    const double whole = CornerPeakBound(nx, ny, radius, dx, dy, dth, size, f0, r0, f1, r1, tau_s);
    const double hull = HermiteAbsBound(f0, r0, f1, r1, tau_s, kCornerHalvings);
    const double inf = std::numeric_limits<double>::infinity();
    for (const double best : MaximaAround(whole, hull, std::max(std::abs(f0), std::abs(f1)), rng)) {
      peaks.Arm(true, Y, tau_s, 0.0, &best);
      const double b = peaks(0, nx, ny, radius, f0, r0, f1, r1, tau_s);
      ASSERT_EQ(b < best, whole < best) << "step " << s << " maximum " << best;
      if (b < inf) {
        ASSERT_EQ(b, whole) << "step " << s;
      }
      (whole < best ? below : not_below) += 1;
      peaks.Disarm();
    }
    // Without the maxima, and unarmed.
    peaks.Arm(true, Y, tau_s, 0.0);
    ASSERT_EQ(peaks(0, nx, ny, radius, f0, r0, f1, r1, tau_s), whole);
    peaks.Disarm();
    ASSERT_EQ(peaks(0, nx, ny, radius, f0, r0, f1, r1, tau_s), inf);
  }
  EXPECT_GT(below, 500);
  EXPECT_GT(not_below, 500);
}

TEST(ModalPeakBound, HoldsOnRandomStepsOfADampedDeck) {
  Stats stats = CheckSteps(0.05, 400, 1, 0.05, 0.5, 5.0, 0.01, false);
  ASSERT_GT(stats.roots(), 20);
  // Tight at the peaks of a record's steps: the median excess is a fraction of the peak's rise
  // over its ends (the end values plus h max |u| / 2 exceed it by about ten rises).
  EXPECT_LT(stats.median(), 0.5);
}

TEST(ModalPeakBound, HoldsOnAnUndampedDeckAndLongSteps) {
  // omega tau up to 3: the interpolation error's term carries the bound.
  const Stats stats = CheckSteps(0.0, 300, 2, 0.05, 0.5, 5.0, 0.1, false);
  EXPECT_GT(stats.roots(), 20);
}

TEST(ModalPeakBound, HoldsUnderForcingAloneFromRest) {
  CheckSteps(0.05, 200, 3, 0.0, 0.0, 5.0, 0.05, false);
}

TEST(ModalPeakBound, HoldsAtResonance) { CheckSteps(0.02, 200, 4, 0.01, 0.1, 5.0, 0.08, true); }

TEST(ModalPeakBound, HoldsOnHeavilyDampedLongSteps) {
  CheckSteps(0.9, 200, 5, 0.05, 0.5, 5.0, 0.12, false);
}

}  // namespace
}  // namespace skewbridge::dynamics::peak_bound_test
