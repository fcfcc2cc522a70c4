#include "solver/dynamics/simulate.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

// The workspace of the event-driven runs of one model: the flow, the dense outputs, the contact
// problems, the gap bound, and the model's frequency and length scales, built once.

namespace skewbridge::dynamics {

SimulationWorkspace::SimulationWorkspace(const model::Model& model)
    : model_(model),
      flow_(model.M(), model.K(), model.C(), model.r(), FlowPath::kAuto, model.modes()),
      free_dense_(flow_.augmented_size()),
      rk_(2 * model.n_dof() + 3),
      forces_(model, EventPolicy{}.rank_threshold),
      decision_(model, EventPolicy{}.rank_threshold) {
  ComputeScales();
}

void SimulationWorkspace::ComputeScales() {
  const model::Model& model = model_;
  gap_bound_.Clear();
  omega_max_radps_ = omega_min_radps_ = 0.0;
  length_scale_m_ = 1.0;
  if (flow_.modal()) {
    gap_bound_.Assign(model, flow_.modal_flow());
    // The modal flow's w_k^2 are the eigenvalues below, clamped at 0: one solve, same bits.
    const Eigen::VectorXd& w2 = flow_.modal_flow().w2();
    omega_max_radps_ = std::sqrt(w2.maxCoeff());
    omega_min_radps_ = std::sqrt(w2.minCoeff());
  } else {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(model.K(), model.M(),
                                                                        Eigen::EigenvaluesOnly);
    const Eigen::VectorXd w2 = eig.eigenvalues();
    omega_max_radps_ = std::sqrt(std::max(w2.maxCoeff(), 0.0));
    omega_min_radps_ = std::sqrt(std::max(w2.minCoeff(), 0.0));
  }
  for (const model::Body& body : model.bodies()) {
    length_scale_m_ = std::max({length_scale_m_, body.geometry.length_m, body.geometry.width_m,
                                body.rest_position_m.norm() + body.geometry.length_m});
  }
}

bool SimulationWorkspace::SameShape(const model::Model& other) const {
  const model::Model& own = model_;
  if (own.n_bodies() != other.n_bodies() || own.n_dof() != other.n_dof() ||
      own.n_contacts() != other.n_contacts()) {
    return false;
  }
  for (int c = 0; c < own.n_contacts(); ++c) {
    const model::Contact& a = own.contact(c);
    const model::Contact& b = other.contact(c);
    if (a.body != b.body || a.face.body != b.face.body) return false;
  }
  return true;
}

void SimulationWorkspace::Refit() {
  const model::Model& model = model_;
  flow_.Refit(model.M(), model.K(), model.C(), model.r(), model.modes());
  // A new workspace's kinematics start at zero, and their evaluation writes only the entries of
  // each contact's bodies: zeroed again (no allocation at the same size), every entry is what it
  // would be in a new workspace. The rest of the storage is written before it is read in a run.
  forces_.kin.Resize(model);
  decision_.projection.kin.Resize(model);
  travel_.Assign(model);
  ComputeScales();
}

}  // namespace skewbridge::dynamics
