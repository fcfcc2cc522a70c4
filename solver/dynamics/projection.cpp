#include "solver/dynamics/projection.h"

#include <algorithm>
#include <cmath>

namespace skewbridge::dynamics {

ProjectionWorkspace::ProjectionWorkspace(const model::Model& model, double rank_threshold)
    : sys(2 * model.n_contacts(), rank_threshold),
      rows(Eigen::MatrixXd::Zero(model.n_dof(), sys.capacity())),
      projection_rows(static_cast<std::size_t>(model.n_contacts()), 0),
      u_in(Eigen::VectorXd::Zero(model.n_dof())),
      u_out(Eigen::VectorXd::Zero(model.n_dof())) {
  kin.Resize(model);
}

void ProjectOntoContacts(const model::Model& model, const ContactModes& modes,
                         const EventPolicy& policy, const ProjectionTolerances& tol,
                         Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> u,
                         ProjectionWorkspace& ws) {
  // Gauss-Newton in the M^-1 metric: positions onto g = 0 of the closed contacts, velocities
  // onto gamma_N = 0 (and gamma_T = 0 when sticking) [docs/theory.md §3.10]. Only the closed
  // contacts' kinematics are needed for the positions; the velocity pass evaluates all.
  const int nc = model.n_contacts();
  const Eigen::VectorXd& inv_m = model.inverse_mass_diagonal();
  contact::ContactKinematics& kin = ws.kin;
  ActiveSystem& sys = ws.sys;
  Eigen::MatrixXd& rows = ws.rows;
  for (int pass = 0; pass < policy.position_passes; ++pass) {
    contact::EvaluateContacts(model, q, u, modes.closed_ids(), kin);
    int m = 0;
    double largest_gap_m = 0.0;
    for (int c = 0; c < nc; ++c) {
      if (modes.closed(c)) {
        rows.col(m) = kin.W_N.col(c);
        sys.b(m) = -kin.gap_m[c];
        largest_gap_m = std::max(largest_gap_m, std::abs(kin.gap_m[c]));
        ++m;
      }
    }
    if (m == 0) {
      return;
    }
    // The gap is linear in the translations and its curvature in the rotation is the arm, at
    // most the deck's size: after one pass from gaps below sqrt(eps) of that size, the residual
    // is below rounding and a second pass changes nothing that a gap resolves (§3.10).
    const bool last_pass = largest_gap_m <= policy.one_pass_gap * tol.length_scale_m;
    sys.Start(m);
    for (int i = 0; i < m; ++i) {
      for (int j = 0; j < m; ++j) {
        sys.A(i, j) = rows.col(i).dot(inv_m.cwiseProduct(rows.col(j)));
      }
    }
    sys.SolveSymmetric();
    for (int j = 0; j < m; ++j) {
      q += inv_m.cwiseProduct(rows.col(j)) * sys.x(j);
    }
    if (last_pass) {
      break;
    }
  }
  // Velocities: onto gamma_N = 0 of the closed contacts (gamma_T = 0 of the sticking ones), and
  // gamma_N >= 0 of the open contacts at the face. The projection of the closed contacts alone can
  // drive an open contact at the face into the face (a deck rocking between two corners: putting
  // one corner's slow separation to zero swings the other into its face), and the next step would
  // find that contact closing at once, at the same instant. The inequality rows enter as an active
  // set: an open contact at the face is added while the projection makes it approach, and dropped
  // again if it would have to pull (a negative multiplier) [docs/theory.md §3.10].
  contact::Evaluate(model, q, u, kin);
  std::vector<int>& joined = ws.projection_rows;
  std::fill(joined.begin(), joined.end(), 0);
  Eigen::VectorXd& u_in = ws.u_in;
  Eigen::VectorXd& u_out = ws.u_out;
  u_in = u;
  for (int pass = 0; pass <= nc; ++pass) {
    int m = 0;
    for (int c = 0; c < nc; ++c) {
      const ContactMode mode = modes[c];
      if (IsClosed(mode) || joined[static_cast<std::size_t>(c)] != 0) {
        rows.col(m++) = kin.W_N.col(c);
        if (mode == ContactMode::kStick) {
          rows.col(m++) = kin.W_T.col(c);
        }
      }
    }
    sys.Start(m);
    for (int i = 0; i < m; ++i) {
      sys.b(i) = -rows.col(i).dot(u_in);
      for (int j = 0; j < m; ++j) {
        sys.A(i, j) = rows.col(i).dot(inv_m.cwiseProduct(rows.col(j)));
      }
    }
    if (m > 0) {
      sys.SolveSymmetric();
    }
    u_out = u_in;
    for (int j = 0; j < m; ++j) {
      u_out += inv_m.cwiseProduct(rows.col(j)) * sys.x(j);
    }
    // Active-set update of the open contacts at the face.
    bool changed = false;
    int row = 0;
    for (int c = 0; c < nc; ++c) {
      const ContactMode mode = modes[c];
      const bool in_set = IsClosed(mode) || joined[static_cast<std::size_t>(c)] != 0;
      if (in_set && !IsClosed(mode) && sys.x(row) < 0.0) {
        joined[static_cast<std::size_t>(c)] = 0;
        changed = true;
      } else if (policy.open_contacts_in_projection && !in_set && kin.gap_m[c] <= tol.gap_tol_m &&
                 kin.W_N.col(c).dot(u_out) < -tol.v_tol_mps) {
        joined[static_cast<std::size_t>(c)] = 1;
        changed = true;
      }
      if (in_set) {
        row += mode == ContactMode::kStick ? 2 : 1;
      }
    }
    if (!changed) {
      break;
    }
  }
  u = u_out;
}

}  // namespace skewbridge::dynamics
