#include "solver/dynamics/gap_bound.h"

#include <utility>

namespace skewbridge::dynamics {

ModalGapBound::ModalGapBound(const model::Model& model, const ModalFlow& modal) {
  Assign(model, modal);
}

void ModalGapBound::Clear() {
  weights.clear();
  w_radps.clear();
  n_modes = 0;
  n_contacts = 0;
}

void ModalGapBound::Assign(const model::Model& model, const ModalFlow& modal) {
  Clear();
  const int n = modal.n_modes();
  const int nc = model.n_contacts();
  if ((modal.c().array() < 0.0).any()) {
    return;
  }
  weights.resize(static_cast<std::size_t>(nc) * static_cast<std::size_t>(n));
  const Eigen::MatrixXd& Phi = modal.Phi();
  for (int c = 0; c < nc; ++c) {
    const model::Contact& contact = model.contact(c);
    if (contact.face.body != model::kGround) {
      weights.clear();
      return;
    }
    CornerGapWeights(Phi, 3 * contact.body, contact.face.normal, contact.point_m,
                     weights.data() + static_cast<std::size_t>(c) * static_cast<std::size_t>(n));
  }
  w_radps.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) w_radps[static_cast<std::size_t>(k)] = std::sqrt(modal.w2()[k]);
  n_modes = n;
  n_contacts = nc;
}

void ModalGapBound::Set(const ModalFlow& modal, std::vector<double> W, int count) {
  const int n = modal.n_modes();
  weights = std::move(W);
  w_radps.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) w_radps[static_cast<std::size_t>(k)] = std::sqrt(modal.w2()[k]);
  n_modes = n;
  n_contacts = count;
}

void CornerGapWeights(const Eigen::MatrixXd& Phi, int row, const Eigen::Vector2d& normal,
                      const Eigen::Vector2d& point_m, double* W) {
  const double arm = normal.norm() * point_m.norm();
  for (int k = 0; k < Phi.cols(); ++k) {
    W[k] = std::abs(normal.x() * Phi(row, k) + normal.y() * Phi(row + 1, k)) +
           arm * std::abs(Phi(row + 2, k));
  }
}

}  // namespace skewbridge::dynamics
