// The solver's full-edge impact at the +x abutment, one line per case, for
// tests/contact/check_full_edge_impact.py: reads "a_deg eta0 mu eps phi_deg" lines on stdin (a
// free deck of L = 30 m and unit mass translating at unit speed in the direction phi from +x,
// both corners P1 and P2 touching, theta = 0) and prints
// "Lambda_N1 Lambda_N2 Lambda_T1 Lambda_T2 vx_E vy_E omega_E" (N s, m/s, rad/s) per line.
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <vector>

#include "solver/contact/impact_problem.h"
#include "solver/contact/kinematics.h"
#include "tests/contact/test_models.h"

int main() {
  using namespace skewbridge;
  double a_deg = 0, eta0 = 0, mu = 0, eps = 0, phi_deg = 0;
  while (std::cin >> a_deg >> eta0 >> mu >> eps >> phi_deg) {
    const double delta_m = 0.05;
    const model::Model model = contact::testing::FreeDeck(a_deg, eta0, 30.0, delta_m, eps, mu);
    const double phi = phi_deg * contact::testing::kDeg;
    const Eigen::Vector3d u_A(std::cos(phi), std::sin(phi), 0.0);
    contact::ContactKinematics kin;
    kin.Resize(model);
    contact::Evaluate(model, Eigen::Vector3d(delta_m, 0.0, 0.0), u_A, kin);
    contact::ImpactProblem problem(model);
    contact::ImpactResult r = problem.MakeResult();
    const std::vector<int> both{0, 1};
    const lcp::LcpStatus status = problem.Solve(kin, both, u_A, r);
    if (status != lcp::LcpStatus::kSolved) {
      std::printf("nan nan nan nan nan nan nan\n");
      continue;
    }
    std::printf("%.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", r.Lambda_N(0), r.Lambda_N(1),
                r.Lambda_T(0), r.Lambda_T(1), r.u_E(0), r.u_E(1), r.u_E(2));
  }
  return 0;
}
