#include "solver/dynamics/indeterminate_split.h"

#include <algorithm>
#include <cmath>

#include "solver/common/error.h"

namespace skewbridge::dynamics {

void SplitIndeterminateForces(const model::Model& model, const ContactModes& modes,
                              const EventPolicy& policy, double force_tol_N, int k, int m,
                              ActiveSystem& sys, SplitWorkspace& ws) {
  using Vec = Eigen::VectorXd;
  const int nc = model.n_contacts();
  Eigen::MatrixXd& kernel = ws.kernel;
  std::vector<int>& normal_of = ws.normal_of;
  std::vector<int>& tangent_of = ws.tangent_of;
  Vec& x_bal = ws.x_bal;
  Vec& x_try = ws.x_try;
  lcp::SmallLp& lp = ws.lp;
  Eigen::MatrixXd& lp_G = ws.lp_G;
  Vec& lp_h = ws.lp_h;
  Vec& lp_c = ws.lp_c;
  Vec& lp_y = ws.lp_y;

  // A singular active set leaves the forces fixed only up to its kernel. Two corners of a deck
  // sticking on one face constrain its tangential motion twice (one corner's friction can be
  // traded against the other's); a deck clamped between two closed faces adds a squeeze (equal
  // normal forces on both faces) and a couple of the normal forces, and with sliding contacts
  // the squeeze also changes the friction drag. The minimum-norm solution can pull (a negative
  // normal force on the unloaded face) or put a lightly loaded corner beyond its cone while
  // another split keeps every contact inside, and the detachment or slip event would then fire
  // at the same instant although the contact problem says the contact stays. Of all solutions
  // x = x0 + K s, three small LPs over the kernel coordinates s choose
  //   1. the largest smallest normal force, capped at 0 (negative only if no split is
  //      compressive: the detachment event then fires, as it should);
  //   2. the least total normal force with every normal force at least that floor: no squeeze,
  //      since a joint closed at zero gap carries no prestress;
  //   3. with that total (to rounding), the split deepest inside the friction cones: the largest
  //      smallest margin mu lambda_N - |lambda_T| of the sticking contacts.
  // A clamped deck thus sticks while the friction of its non-squeeze normal forces suffices, and
  // the slip event fires when it no longer does.
  const int d = sys.Kernel(kernel, static_cast<int>(kernel.cols()));
  if (d == 0 || d + 1 > lcp::SmallLp::kMaxVariables) {
    return;
  }
  // Unknown j < k: lambda_N of the j-th closed contact; k + i: lambda_T of the i-th sticking one.
  int j = 0, i = k;
  for (int c = 0; c < nc; ++c) {
    const ContactMode mode = modes[c];
    if (!IsClosed(mode)) {
      continue;
    }
    normal_of[static_cast<std::size_t>(j)] = c;
    tangent_of[static_cast<std::size_t>(j)] = mode == ContactMode::kStick ? i++ : -1;
    ++j;
  }
  SB_DEMAND(i == m && j == k, "SplitIndeterminateForces: active set layout changed");
  // Order-one data for the LP tolerances.
  double scale = force_tol_N;
  for (int r = 0; r < m; ++r) {
    scale = std::max(scale, std::abs(sys.x(r)));
  }
  for (int r = 0; r < m; ++r) {
    x_bal[r] = sys.x(r) / scale;
  }
  const auto K = kernel.topLeftCorner(m, d);
  bool normal_kernel = false;
  for (int jj = 0; jj < k && !normal_kernel; ++jj) {
    normal_kernel = K.row(jj).norm() > policy.kernel_normal_threshold;
  }
  if (!normal_kernel && m == k) {
    return;
  }
  Eigen::Ref<Vec> s = lp_y.head(d + 1);
  s.setZero();
  double floor = 0.0, total = 0.0;
  // Rows jj < k: -K_j s <= x0_j - floor (lambda_N_j >= floor).
  const auto normal_rows = [&](int cols) {
    for (int jj = 0; jj < k; ++jj) {
      lp_G.row(jj).head(cols).setZero();
      lp_G.row(jj).head(d) = -K.row(jj);
      lp_h[jj] = x_bal[jj] - floor;
    }
  };
  if (normal_kernel) {
    // 1. max tau, tau <= lambda_N_j, tau <= 0.
    normal_rows(d + 1);
    for (int jj = 0; jj < k; ++jj) {
      lp_G(jj, d) = 1.0;
      lp_h[jj] = x_bal[jj];
    }
    lp_G.row(k).head(d + 1).setZero();
    lp_G(k, d) = 1.0;
    lp_h[k] = 0.0;
    lp_c.head(d + 1).setZero();
    lp_c[d] = 1.0;
    if (lp.Maximize(lp_G.topLeftCorner(k + 1, d + 1), lp_h.head(k + 1), lp_c.head(d + 1),
                    lp_y.head(d + 1)) != lcp::LpStatus::kOptimal) {
      return;
    }
    floor = std::min(0.0, lp_y[d]);
    // 2. min sum lambda_N_j with lambda_N_j >= floor.
    normal_rows(d);
    for (int e = 0; e < d; ++e) {
      lp_c[e] = -K.col(e).head(k).sum();
    }
    if (lp.Maximize(lp_G.topLeftCorner(k, d), lp_h.head(k), lp_c.head(d), lp_y.head(d)) !=
        lcp::LpStatus::kOptimal) {
      return;
    }
    total = x_bal.head(k).sum();
    for (int jj = 0; jj < k; ++jj) {
      total += K.row(jj).dot(s.head(d));
    }
  }
  x_try.head(d) = s.head(d);  // the split of steps 1 and 2, should step 3 fail
  if (m > k) {
    // 3. max tau, tau <= mu lambda_N_j -+ lambda_T_j, lambda_N_j >= floor, sum lambda_N <= total.
    int rows = 0;
    if (normal_kernel) {
      normal_rows(d + 1);
      for (int jj = 0; jj < k; ++jj) {
        lp_G(jj, d) = 0.0;
      }
      rows = k;
      lp_G.row(rows).head(d + 1).setZero();
      lp_G.row(rows).head(d) = K.topRows(k).colwise().sum();
      lp_h[rows] =
          total * (1.0 + policy.split_total_slack) + policy.split_total_slack - x_bal.head(k).sum();
      ++rows;
    }
    for (int jj = 0; jj < k; ++jj) {
      const int t = tangent_of[static_cast<std::size_t>(jj)];
      if (t < 0) {
        continue;
      }
      const double mu = model.contact(normal_of[static_cast<std::size_t>(jj)]).friction;
      for (const double sign : {1.0, -1.0}) {
        lp_G.row(rows).head(d) = -mu * K.row(jj) + sign * K.row(t);
        lp_G(rows, d) = 1.0;
        lp_h[rows] = mu * x_bal[jj] - sign * x_bal[t];
        ++rows;
      }
    }
    lp_c.head(d + 1).setZero();
    lp_c[d] = 1.0;
    if (lp.Maximize(lp_G.topLeftCorner(rows, d + 1), lp_h.head(rows), lp_c.head(d + 1),
                    lp_y.head(d + 1)) != lcp::LpStatus::kOptimal) {
      s.head(d) = x_try.head(d);
    }
  }
  x_bal.head(m) += K * s.head(d);
  for (int r = 0; r < m; ++r) {
    sys.x_mutable(r) = x_bal[r] * scale;
  }
}

}  // namespace skewbridge::dynamics
