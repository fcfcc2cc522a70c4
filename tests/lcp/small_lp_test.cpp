// lcp::SmallLp against brute force: the optimum of a bounded LP max c^T y, G y <= h is attained
// at a vertex (p linearly independent active rows), so the best feasible vertex over all p-subsets
// of the rows is an independent oracle for small problems; plus the infeasible and unbounded
// answers and a degenerate vertex (more active rows than variables).

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include <Eigen/LU>

#include "solver/lcp/small_lp.h"

namespace skewbridge::lcp::small_lp_test {
namespace {

// The best objective over the feasible vertices, -inf if none (brute force over p-subsets).
double BestVertex(const Eigen::MatrixXd& G, const Eigen::VectorXd& h, const Eigen::VectorXd& c) {
  const int r = static_cast<int>(G.rows()), p = static_cast<int>(G.cols());
  double best = -std::numeric_limits<double>::infinity();
  std::vector<int> pick(static_cast<std::size_t>(p));
  for (int i = 0; i < p; ++i) {
    pick[static_cast<std::size_t>(i)] = i;
  }
  while (true) {
    Eigen::MatrixXd Gs(p, p);
    Eigen::VectorXd hs(p);
    for (int i = 0; i < p; ++i) {
      Gs.row(i) = G.row(pick[static_cast<std::size_t>(i)]);
      hs[i] = h[pick[static_cast<std::size_t>(i)]];
    }
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(Gs);
    if (lu.isInvertible()) {
      const Eigen::VectorXd y = lu.solve(hs);
      if (((G * y - h).array() <= 1e-9).all()) {
        best = std::max(best, c.dot(y));
      }
    }
    int i = p - 1;
    while (i >= 0 && pick[static_cast<std::size_t>(i)] == r - p + i) {
      --i;
    }
    if (i < 0) {
      break;
    }
    ++pick[static_cast<std::size_t>(i)];
    for (int j = i + 1; j < p; ++j) {
      pick[static_cast<std::size_t>(j)] = pick[static_cast<std::size_t>(j - 1)] + 1;
    }
  }
  return best;
}

TEST(SmallLp, MatchesTheBestVertexOnRandomBoundedProblems) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  SmallLp lp;
  int checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int p = 1 + trial % 4;
    const int r = 2 * p + 1 + trial % 5;
    // Rows of a bounding box (|y_i| <= 3) plus random rows: always bounded, feasible at y = 0
    // when h > 0 on the random rows.
    Eigen::MatrixXd G(r + 2 * p, p);
    Eigen::VectorXd h(r + 2 * p), c(p), y(p);
    for (int i = 0; i < r; ++i) {
      for (int j = 0; j < p; ++j) {
        G(i, j) = normal(rng);
      }
      h[i] = trial % 3 == 0 ? normal(rng) : std::abs(normal(rng));
    }
    G.bottomRows(2 * p).setZero();
    for (int j = 0; j < p; ++j) {
      G(r + 2 * j, j) = 1.0;
      G(r + 2 * j + 1, j) = -1.0;
      h[r + 2 * j] = h[r + 2 * j + 1] = 3.0;
      c[j] = normal(rng);
    }
    const double oracle = BestVertex(G, h, c);
    const LpStatus status = lp.Maximize(G, h, c, y);
    if (!std::isfinite(oracle)) {
      EXPECT_EQ(status, LpStatus::kInfeasible) << "trial " << trial;
      continue;
    }
    ASSERT_EQ(status, LpStatus::kOptimal) << "trial " << trial;
    EXPECT_NEAR(c.dot(y), oracle, 1e-9 * (1.0 + std::abs(oracle))) << "trial " << trial;
    EXPECT_LE((G * y - h).maxCoeff(), 1e-9) << "trial " << trial;
    ++checked;
  }
  EXPECT_GT(checked, 150);  // most problems are feasible: the oracle comparison did run
}

TEST(SmallLp, ReportsUnboundedAndInfeasible) {
  SmallLp lp;
  Eigen::VectorXd y(2);
  // max y0 + y1 with y0 <= 1 only: unbounded along y1.
  Eigen::MatrixXd G(1, 2);
  G << 1.0, 0.0;
  EXPECT_EQ(lp.Maximize(G, Eigen::VectorXd::Ones(1), Eigen::VectorXd::Ones(2), y),
            LpStatus::kUnbounded);
  // y0 <= -1 and -y0 <= -1 (y0 >= 1): empty.
  Eigen::MatrixXd G2(2, 2);
  G2 << 1.0, 0.0, -1.0, 0.0;
  Eigen::VectorXd h2(2);
  h2 << -1.0, -1.0;
  Eigen::VectorXd c2(2);
  c2 << 1.0, 0.0;
  EXPECT_EQ(lp.Maximize(G2, h2, c2, y), LpStatus::kInfeasible);
}

TEST(SmallLp, DegenerateVertexOfTheMaxMinMargin) {
  // max tau subject to tau <= y, tau <= 1 - y, tau <= 0.5, tau <= 2 y - 0.5: the optimum
  // (y, tau) = (0.5, 0.5) has all four rows active on two variables (Bland's rule must not
  // cycle there).
  Eigen::MatrixXd G(4, 2);
  G << -1.0, 1.0, 1.0, 1.0, 0.0, 1.0, -2.0, 1.0;
  Eigen::VectorXd h(4);
  h << 0.0, 1.0, 0.5, -0.5;
  Eigen::VectorXd c(2), y(2);
  c << 0.0, 1.0;
  SmallLp lp;
  ASSERT_EQ(lp.Maximize(G, h, c, y), LpStatus::kOptimal);
  EXPECT_NEAR(y[0], 0.5, 1e-12);
  EXPECT_NEAR(y[1], 0.5, 1e-12);
}

}  // namespace
}  // namespace skewbridge::lcp::small_lp_test
