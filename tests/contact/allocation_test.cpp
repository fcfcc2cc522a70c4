// The contact layer's hot path allocates nothing once its workspaces exist: every global
// operator new is counted while kinematics, impacts and contact forces are evaluated for a
// sequence of states and index sets of changing size.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <vector>

#include "solver/contact/contact_problem.h"
#include "solver/contact/impact_problem.h"
#include "solver/contact/kinematics.h"
#include "tests/contact/test_models.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) {
    return p;
  }
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace skewbridge::contact {
namespace {

TEST(ContactAllocation, KinematicsImpactsAndContactForcesDoNotAllocateInTheLoop) {
  const model::Model model =
      testing::FreeDeck(20.0, 1.48, 89.14, 0.03, 0.5, 0.3, model::AbutmentSet::kBoth, 1547e3);
  ContactKinematics kin;
  kin.Resize(model);
  ImpactProblem impact(model);
  ImpactResult impact_result = impact.MakeResult();
  ContactProblem contact(model);
  ContactResult contact_result = contact.MakeResult();
  Eigen::VectorXd q(3), u(3), h(3);
  const std::vector<std::vector<int>> index_sets = {{0}, {0, 1}, {1}, {2, 3}, {0, 1, 2, 3}, {3}};
  const std::vector<std::vector<ClosedContact>> closed_sets = {
      {{0, 0}}, {{0, 0}, {1, 1}}, {{1, -1}}, {{2, 0}, {3, 0}}, {{0, 0}, {1, 0}, {2, 0}, {3, 0}}};
  const auto step = [&](int i) {
    q << 0.03 + 1e-3 * i, 1e-3 * (i % 7), 1e-4 * (i % 5);
    u << 0.5 - 0.1 * (i % 3), 0.2, 0.01 * (i % 4);
    Evaluate(model, q, u, kin);
    const std::vector<int>& set = index_sets[static_cast<std::size_t>(i) % index_sets.size()];
    impact.Solve(kin, set, u, impact_result);
    model.AppliedForces(q, u, Eigen::Vector2d(1.0, 0.5), h);
    const std::vector<ClosedContact>& closed =
        closed_sets[static_cast<std::size_t>(i) % closed_sets.size()];
    contact.Solve(kin, closed, h, contact_result);
    return impact_result.u_E.sum() + contact_result.du_dt.sum();
  };
  double checksum = 0.0;
  for (int i = 0; i < 60; ++i) {  // warm-up: every size once
    checksum += step(i);
  }
  const long before = g_allocations.load();
  ASSERT_GT(before, 0) << "the counting operator new is not in use";
  for (int i = 0; i < 600; ++i) {
    checksum += step(i);
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_TRUE(std::isfinite(checksum));
}

}  // namespace
}  // namespace skewbridge::contact
