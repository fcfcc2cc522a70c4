// Time per solve of a reused LemkeSolver on random SPD problems (n = 2..24) and on the impact
// LCPs of docs/theory.md §3 for two contacts (n = 6) and four contacts (n = 12).
// Run: lemke_benchmark --benchmark_min_time=0.2

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <numbers>
#include <random>
#include <vector>

#include "solver/lcp/lemke.h"
#include "tests/lcp/impact_problem.h"
#include "tests/lcp/lcp_oracles.h"

namespace {

using skewbridge::lcp::LcpSolution;
using skewbridge::lcp::LcpStatus;
using skewbridge::lcp::LemkeSolver;
namespace t = skewbridge::lcp::testing;

constexpr int kProblems = 16;  // cycled through so branch history does not memorise one path

struct ProblemSet {
  std::vector<Eigen::MatrixXd> M;
  std::vector<Eigen::VectorXd> q;
};

void Run(benchmark::State& state, const ProblemSet& set) {
  LemkeSolver solver;
  LcpSolution solution;
  long pivots = 0;
  long solves = 0;
  size_t k = 0;
  for (auto _ : state) {
    const LcpStatus status = solver.Solve(set.M[k], set.q[k], solution);
    benchmark::DoNotOptimize(status);
    pivots += solution.pivots;
    ++solves;
    if (status != LcpStatus::kSolved) state.SkipWithError("not solved");
    k = (k + 1) % set.M.size();
  }
  state.counters["pivots"] = static_cast<double>(pivots) / static_cast<double>(solves);
}

void BM_RandomSpd(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::mt19937 rng(1000 + n);
  ProblemSet set;
  for (int i = 0; i < kProblems; ++i) {
    set.M.push_back(t::RandomSpd(n, rng));
    set.q.push_back(t::RandomVector(n, rng));
  }
  Run(state, set);
}
BENCHMARK(BM_RandomSpd)->Arg(2)->Arg(4)->Arg(6)->Arg(12)->Arg(24);

/// Impact problems of the pilot deck (a = 20 deg, eta0 = 1.48, m = 1547 t), eps = 0.5,
/// mu = 0.3: two contacts = a full-edge impact of the +x end with varied approach velocities;
/// four contacts = the deck spinning into both abutments with a small drift.
void BM_Impact(benchmark::State& state) {
  const int contacts = static_cast<int>(state.range(0));
  const t::Deck d = t::Deck::WithSkewRatio(89.14, 20 * std::numbers::pi / 180, 1.48, 1.547e6);
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ProblemSet set;
  for (int i = 0; i < kProblems; ++i) {
    Eigen::Vector3d u_A;
    std::vector<int> corners;
    if (contacts == 2) {
      u_A << 0.4 * (1.0 + 0.5 * u(rng)), 0.2 * u(rng), 0.002 * u(rng);
      corners = {1, 2};
    } else {
      u_A << 0.01 * u(rng), 0.01 * u(rng), -0.4 / d.Rho();
      corners = {1, 2, 3, 4};
    }
    const t::ImpactProblem p = t::BuildImpactProblem(d, corners, 0.0, u_A, 0.3, 0.5);
    set.M.push_back(p.A);
    set.q.push_back(p.b);
  }
  Run(state, set);
}
BENCHMARK(BM_Impact)->Arg(2)->Arg(4);

}  // namespace
