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
  if (flow_.modal()) {
    gap_bound_ = ModalGapBound(model, flow_.modal_flow());
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

}  // namespace skewbridge::dynamics
