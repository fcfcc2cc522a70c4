// Counts heap allocations to check that a reused LemkeSolver and LcpSolution allocate nothing
// in steady state. Eigen allocates through std::malloc (not operator new), so the malloc
// family itself is interposed for this executable (glibc lets the program define them and
// forward to the __libc_* entry points); operator new goes through malloc as well.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <atomic>
#include <cstddef>
#include <random>
#include <vector>

#include "solver/lcp/lemke.h"
#include "tests/lcp/lcp_oracles.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* p, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);
void __libc_free(void* p);

void* malloc(std::size_t size) {
  ++g_allocations;
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  ++g_allocations;
  return __libc_calloc(count, size);
}
void* realloc(void* p, std::size_t size) {
  ++g_allocations;
  return __libc_realloc(p, size);
}
void* memalign(std::size_t alignment, std::size_t size) {
  ++g_allocations;
  return __libc_memalign(alignment, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) {
  ++g_allocations;
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) {
  ++g_allocations;
  *out = __libc_memalign(alignment, size);
  return *out == nullptr ? 12 : 0;  // ENOMEM
}
void free(void* p) { __libc_free(p); }
}

namespace skewbridge::lcp {
namespace {

TEST(LemkeSolverAllocation, SteadyStateSolvesDoNotAllocate) {
  std::mt19937 rng(5);
  std::vector<Eigen::MatrixXd> matrices;
  std::vector<Eigen::VectorXd> vectors;
  for (int n : {24, 6, 12, 2, 24, 6}) {
    matrices.push_back(testing::RandomSpd(n, rng));
    vectors.push_back(testing::RandomVector(n, rng));
  }
  LemkeSolver solver;
  // One solution object per size, as a caller with a few fixed contact counts would hold.
  std::vector<LcpSolution> solutions(matrices.size());
  for (size_t k = 0; k < matrices.size(); ++k) {
    ASSERT_EQ(solver.Solve(matrices[k], vectors[k], solutions[k]), LcpStatus::kSolved);
  }
  // The workspace now holds n = 24; smaller and equal sizes must not allocate.
  const long before = g_allocations.load();
  int solved = 0;
  for (int repeat = 0; repeat < 10; ++repeat) {
    for (size_t k = 0; k < matrices.size(); ++k) {
      solved += solver.Solve(matrices[k], vectors[k], solutions[k]) == LcpStatus::kSolved;
    }
  }
  const long after = g_allocations.load();
  EXPECT_EQ(solved, 10 * static_cast<int>(matrices.size()));
  EXPECT_EQ(after - before, 0) << "allocations in steady state";
}

TEST(LemkeSolverAllocation, PreparedSolverDoesNotAllocateFromItsFirstSolve) {
  // The contact and impact problems Prepare their solver once per model, before the time loop:
  // the first impact of a run, which pivots, must find the pivoting's buffers already there.
  std::mt19937 rng(11);
  std::vector<Eigen::MatrixXd> matrices;
  std::vector<Eigen::VectorXd> vectors;
  for (int n : {12, 3, 6, 9}) {
    matrices.push_back(testing::RandomSpd(n, rng));
    Eigen::VectorXd q = testing::RandomVector(n, rng);
    q(0) = -1.0;  // at least one negative entry: the solve pivots
    vectors.push_back(q);
  }
  LemkeSolver solver;
  std::vector<LcpSolution> solutions;
  solver.Prepare(12, solutions);
  const long before = g_allocations.load();
  int pivoted = 0;
  for (size_t k = 0; k < matrices.size(); ++k) {
    LcpSolution& solution = solutions[static_cast<std::size_t>(matrices[k].rows())];
    ASSERT_EQ(solver.Solve(matrices[k], vectors[k], solution), LcpStatus::kSolved);
    pivoted += solution.pivots > 0;
  }
  const long after = g_allocations.load();
  EXPECT_EQ(pivoted, static_cast<int>(matrices.size()));
  EXPECT_EQ(after - before, 0) << "allocations in the first solves after Prepare";
}

TEST(LemkeSolverAllocation, CounterSeesEigenAllocations) {
  // The counter sees the allocations Eigen and the solver make: a fresh solver allocates.
  const Eigen::MatrixXd M = Eigen::MatrixXd::Identity(4, 4);
  const Eigen::VectorXd q = -Eigen::VectorXd::Ones(4);
  LcpSolution s;
  const long before = g_allocations.load();
  LemkeSolver fresh;
  fresh.Solve(M, q, s);
  EXPECT_GT(g_allocations.load() - before, 0);
  EXPECT_EQ(s.z, Eigen::VectorXd::Ones(4));
}

}  // namespace
}  // namespace skewbridge::lcp
