#include "solver/dynamics/active_forces.h"

namespace skewbridge::dynamics {

ActiveForcesStorage::ActiveForcesStorage(const model::Model& model, double rank_threshold)
    : sys(2 * model.n_contacts(), rank_threshold), split{kernel, normal_of, tangent_of, x_bal,
                                                         x_try,  lp,        lp_G,       lp_h,
                                                         lp_c,   lp_y} {
  const int n = model.n_dof(), nc = model.n_contacts();
  const int capacity = sys.capacity();
  kin.Resize(model);
  h = mh = Eigen::VectorXd::Zero(n);
  lambda_N = lambda_T = Eigen::VectorXd::Zero(nc);
  cols = m_cols = Eigen::MatrixXd::Zero(n, capacity);
  row_of.assign(static_cast<std::size_t>(capacity), nullptr);
  kernel = Eigen::MatrixXd::Zero(capacity, capacity);
  lp_G = Eigen::MatrixXd::Zero(3 * nc + 2, capacity + 1);
  lp_h = Eigen::VectorXd::Zero(3 * nc + 2);
  lp_c = lp_y = Eigen::VectorXd::Zero(capacity + 1);
  normal_of.assign(static_cast<std::size_t>(nc), 0);
  tangent_of.assign(static_cast<std::size_t>(nc), -1);
  x_bal = x_try = Eigen::VectorXd::Zero(capacity);
}

void EvaluateActiveForces(const model::Model& model, const ContactModes& modes,
                          const EventPolicy& policy, double force_tol_N,
                          const Eigen::Vector2d& a_g_mps2,
                          const Eigen::Ref<const Eigen::VectorXd>& q,
                          const Eigen::Ref<const Eigen::VectorXd>& u, KinematicsOf which,
                          Eigen::Ref<Eigen::VectorXd> du, ActiveForcesStorage& s,
                          AddedForces* added) {
  AppliedForces(model, added, q, u, a_g_mps2, s.h);
  if (which == KinematicsOf::kClosedContacts) {
    contact::EvaluateContacts(model, q, u, modes.closed_ids(), s.kin);
  } else {
    contact::Evaluate(model, q, u, s.kin);
  }
  const contact::ContactKinematics& kin = s.kin;
  ActiveSystem& sys = s.sys;
  // Raw loops over the n entries (a single deck: n = 3, one or two rows): the set-up of a
  // dynamic-size Eigen expression costs more than its arithmetic at that size, and this runs in
  // every Runge-Kutta stage of a constrained phase. The arithmetic is the same, element for
  // element: M^-1 h and M^-1 times each force direction are formed once (not inside every dot
  // product), and each dot product is still Eigen's, so the results keep their bits.
  const int n = model.n_dof();
  const int nc = model.n_contacts();
  const double* inv_m = model.inverse_mass_diagonal().data();
  const double* h = s.h.data();
  double* mh = s.mh.data();
  for (int i = 0; i < n; ++i) {
    mh[i] = inv_m[i] * h[i];
  }
  const auto dot = [n](const double* a, const double* b) {
    return Eigen::Map<const Eigen::VectorXd>(a, n).dot(Eigen::Map<const Eigen::VectorXd>(b, n));
  };
  // Unknowns: lambda_N of every closed contact, then lambda_T of every sticking one; rows: the
  // matching d gamma_N/dt = 0 and d gamma_T/dt = 0 [docs/theory.md §3, contact problem, with the
  // active set fixed].
  int m = 0;
  bool symmetric = true;  // no sliding contact: force directions = constraint rows
  for (int c = 0; c < nc; ++c) {
    const ContactMode mode = modes[c];
    if (!IsClosed(mode)) {
      continue;
    }
    const double mu = model.contact(c).friction;
    const double* w_n = kin.W_N.col(c).data();
    const double* w_t = kin.W_T.col(c).data();
    s.row_of[static_cast<std::size_t>(m)] = w_n;
    sys.b(m) = -(dot(w_n, mh) + kin.what_N[c]);
    double* col = s.cols.col(m).data();
    if (mode == ContactMode::kSlidePositive) {
      symmetric = false;
      for (int i = 0; i < n; ++i) {
        col[i] = w_n[i] - mu * w_t[i];
      }
    } else if (mode == ContactMode::kSlideNegative) {
      symmetric = false;
      for (int i = 0; i < n; ++i) {
        col[i] = w_n[i] + mu * w_t[i];
      }
    } else {
      for (int i = 0; i < n; ++i) {
        col[i] = w_n[i];
      }
    }
    ++m;
  }
  const int k = m;
  for (int c = 0; c < nc; ++c) {
    if (modes[c] == ContactMode::kStick) {
      const double* w_t = kin.W_T.col(c).data();
      s.row_of[static_cast<std::size_t>(m)] = w_t;
      double* col = s.cols.col(m).data();
      for (int i = 0; i < n; ++i) {
        col[i] = w_t[i];
      }
      sys.b(m) = -(dot(w_t, mh) + kin.what_T[c]);
      ++m;
    }
  }
  for (int j = 0; j < m; ++j) {
    const double* col = s.cols.col(j).data();
    double* m_col = s.m_cols.col(j).data();
    for (int i = 0; i < n; ++i) {
      m_col[i] = inv_m[i] * col[i];
    }
  }
  sys.Start(m);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      sys.A(i, j) = dot(s.row_of[static_cast<std::size_t>(i)], s.m_cols.col(j).data());
    }
  }
  if (symmetric) {
    sys.SolveSymmetric();
  } else {
    sys.Solve();
  }
  if (sys.rank_deficient()) {
    // The three-LP split of statically indeterminate forces [docs/theory.md §3.13].
    SplitIndeterminateForces(model, modes, policy, force_tol_N, k, m, sys, s.split);
  }
  // du = M^-1 (h + sum_j cols_j x_j), summed in that order.
  double* d = du.data();
  for (int i = 0; i < n; ++i) {
    double v = h[i];
    for (int j = 0; j < m; ++j) {
      v += s.cols(i, j) * sys.x(j);
    }
    d[i] = inv_m[i] * v;
  }
  // Forces per contact and the friction power.
  s.friction_power_W = 0.0;
  int j = 0, js = k;
  for (int c = 0; c < nc; ++c) {
    const ContactMode mode = modes[c];
    if (!IsClosed(mode)) {
      s.lambda_N[c] = s.lambda_T[c] = 0.0;
      continue;
    }
    const double mu = model.contact(c).friction;
    s.lambda_N[c] = sys.x(j);
    if (mode == ContactMode::kSlidePositive) {
      s.lambda_T[c] = -mu * sys.x(j);
    } else if (mode == ContactMode::kSlideNegative) {
      s.lambda_T[c] = mu * sys.x(j);
    } else if (mode == ContactMode::kStick) {
      s.lambda_T[c] = sys.x(js++);
    } else {
      s.lambda_T[c] = 0.0;
    }
    s.friction_power_W -= s.lambda_T[c] * kin.gamma_T[c];
    ++j;
  }
}

}  // namespace skewbridge::dynamics
