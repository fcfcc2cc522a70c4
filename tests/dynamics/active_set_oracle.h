#pragma once
// Independent oracle for the constrained forces of a fixed active set: the system of
// solver/dynamics/active_forces.h assembled from whole vectors and solved by Eigen's full-pivot
// LU (no kernel split: a singular system gets LU's particular solution).

#include <Eigen/Core>
#include <Eigen/LU>
#include <vector>

#include "solver/contact/kinematics.h"
#include "solver/dynamics/contact_modes.h"
#include "solver/model/model.h"

namespace skewbridge::dynamics::testing {

// The oracle's answer: the system A x = b, its solution, and what follows from it.
struct OracleForces {
  Eigen::MatrixXd A;               // m x m: rows^T M^-1 cols
  Eigen::VectorXd b;               // -(rows^T M^-1 h + what)
  Eigen::VectorXd x;               // lambda_N of the closed contacts, then lambda_T of the sticking
  Eigen::VectorXd lambda_N;        // per contact (N); 0 when open
  Eigen::VectorXd lambda_T;        // per contact (N); 0 when open
  Eigen::VectorXd du;              // M^-1 (h + W_N lambda_N + W_T lambda_T)
  Eigen::VectorXd h;               // the applied forces
  contact::ContactKinematics kin;  // every contact's kinematics at (q, u)
  int rank = 0;                    // of A (full-pivot LU)
};

// Unknowns lambda_N per closed contact (force direction w_N - mu s w_T when sliding with sign
// s, w_N otherwise) and lambda_T per sticking one (direction w_T); rows d gamma_N/dt = 0 per
// closed contact and d gamma_T/dt = 0 per sticking one, with the contact layer's kinematics and
// the applied forces at the ground acceleration a_g.
inline OracleForces OracleActiveForces(const model::Model& model, const ContactModes& modes,
                                       const Eigen::Vector2d& a_g,
                                       const Eigen::Ref<const Eigen::VectorXd>& q,
                                       const Eigen::Ref<const Eigen::VectorXd>& u) {
  OracleForces o;
  o.kin.Resize(model);
  contact::Evaluate(model, q, u, o.kin);
  o.h.resize(model.n_dof());
  model.AppliedForces(q, u, a_g, o.h);
  const Eigen::VectorXd inv_m = model.inverse_mass_diagonal();
  std::vector<Eigen::VectorXd> rows, cols;
  std::vector<double> rhs;
  for (int c = 0; c < modes.size(); ++c) {
    if (!modes.closed(c)) {
      continue;
    }
    const double mu = model.contact(c).friction;
    rows.push_back(o.kin.W_N.col(c));
    cols.push_back(o.kin.W_N.col(c) - mu * SlipSign(modes[c]) * o.kin.W_T.col(c));
    rhs.push_back(-(o.kin.W_N.col(c).dot(inv_m.cwiseProduct(o.h)) + o.kin.what_N[c]));
  }
  const int k = static_cast<int>(rows.size());
  for (int c = 0; c < modes.size(); ++c) {
    if (modes[c] == ContactMode::kStick) {
      rows.push_back(o.kin.W_T.col(c));
      cols.push_back(o.kin.W_T.col(c));
      rhs.push_back(-(o.kin.W_T.col(c).dot(inv_m.cwiseProduct(o.h)) + o.kin.what_T[c]));
    }
  }
  const int m = static_cast<int>(rows.size());
  o.A.resize(m, m);
  o.b.resize(m);
  for (int i = 0; i < m; ++i) {
    o.b[i] = rhs[static_cast<std::size_t>(i)];
    for (int j = 0; j < m; ++j) {
      o.A(i, j) = rows[static_cast<std::size_t>(i)].dot(
          inv_m.cwiseProduct(cols[static_cast<std::size_t>(j)]));
    }
  }
  o.x = Eigen::VectorXd::Zero(m);
  if (m > 0) {
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(o.A);
    o.x = lu.solve(o.b);
    o.rank = static_cast<int>(lu.rank());
  }
  o.lambda_N = o.lambda_T = Eigen::VectorXd::Zero(modes.size());
  Eigen::VectorXd force = o.h;
  int j = 0, js = k;
  for (int c = 0; c < modes.size(); ++c) {
    if (!modes.closed(c)) {
      continue;
    }
    const double mu = model.contact(c).friction;
    o.lambda_N[c] = o.x[j++];
    o.lambda_T[c] =
        modes[c] == ContactMode::kStick ? o.x[js++] : -mu * SlipSign(modes[c]) * o.lambda_N[c];
    force += o.kin.W_N.col(c) * o.lambda_N[c] + o.kin.W_T.col(c) * o.lambda_T[c];
  }
  o.du = inv_m.cwiseProduct(force);
  return o;
}

}  // namespace skewbridge::dynamics::testing
