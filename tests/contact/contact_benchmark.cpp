// Cost of the contact layer's hot-path calls on the pilot bridge (4 contacts): kinematics of all
// contacts, a two-corner impact and the contact problem with two sticking corners.
#include <benchmark/benchmark.h>

#include <vector>

#include "solver/contact/contact_problem.h"
#include "solver/contact/impact_problem.h"
#include "solver/contact/kinematics.h"
#include "tests/contact/test_models.h"

namespace skewbridge::contact {
namespace {

model::Model Pilot() {
  return testing::FreeDeck(20.0, 1.48, 89.14, 0.03, 0.5, 0.3, model::AbutmentSet::kBoth, 1547e3);
}

void BM_EvaluateKinematics(benchmark::State& state) {
  const model::Model model = Pilot();
  ContactKinematics kin;
  kin.Resize(model);
  Eigen::VectorXd q(3), u(3);
  q << 0.03, 0.001, 1e-4;
  u << 0.4, 0.1, 0.01;
  for (auto _ : state) {
    Evaluate(model, q, u, kin);
    benchmark::DoNotOptimize(kin.gap_m.data());
  }
}
BENCHMARK(BM_EvaluateKinematics);

void BM_TwoCornerImpact(benchmark::State& state) {
  const model::Model model = Pilot();
  ContactKinematics kin;
  kin.Resize(model);
  Eigen::VectorXd q(3), u(3);
  q << 0.03, 0.0, 0.0;
  u << 0.4, 0.0, 0.0;
  Evaluate(model, q, u, kin);
  ImpactProblem problem(model);
  ImpactResult result = problem.MakeResult();
  const std::vector<int> set{0, 1};
  for (auto _ : state) {
    problem.Solve(kin, set, u, result);
    benchmark::DoNotOptimize(result.u_E.data());
  }
}
BENCHMARK(BM_TwoCornerImpact);

void BM_TwoCornerContactForces(benchmark::State& state) {
  const model::Model model = Pilot();
  ContactKinematics kin;
  kin.Resize(model);
  Eigen::VectorXd q(3), u(3), h(3);
  q << 0.03, 0.0, 0.0;
  u.setZero();
  Evaluate(model, q, u, kin);
  h << 1e6, -2e5, 0.0;
  ContactProblem problem(model);
  ContactResult result = problem.MakeResult();
  const std::vector<ClosedContact> closed{{0, 0}, {1, 0}};
  for (auto _ : state) {
    problem.Solve(kin, closed, h, result);
    benchmark::DoNotOptimize(result.du_dt.data());
  }
}
BENCHMARK(BM_TwoCornerContactForces);

}  // namespace
}  // namespace skewbridge::contact
