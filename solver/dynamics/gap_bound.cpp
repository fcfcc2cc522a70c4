#include "solver/dynamics/gap_bound.h"

#include <utility>

namespace skewbridge::dynamics {

ModalGapBound::ModalGapBound(const model::Model& model, const ModalFlow& modal) {
  const int n = modal.n_modes();
  const int nc = model.n_contacts();
  if ((modal.c().array() < 0.0).any()) {
    return;
  }
  std::vector<double> W(static_cast<std::size_t>(nc) * static_cast<std::size_t>(n));
  const Eigen::MatrixXd& Phi = modal.Phi();
  for (int c = 0; c < nc; ++c) {
    const model::Contact& contact = model.contact(c);
    if (contact.face.body != model::kGround) {
      return;
    }
    const int i = 3 * contact.body;
    const Eigen::Vector2d& normal = contact.face.normal;
    const double arm = normal.norm() * contact.point_m.norm();
    for (int k = 0; k < n; ++k) {
      W[static_cast<std::size_t>(c * n + k)] =
          std::abs(normal.x() * Phi(i, k) + normal.y() * Phi(i + 1, k)) +
          arm * std::abs(Phi(i + 2, k));
    }
  }
  weights = std::move(W);
  w_radps.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) w_radps[static_cast<std::size_t>(k)] = std::sqrt(modal.w2()[k]);
  n_modes = n;
  n_contacts = nc;
}

}  // namespace skewbridge::dynamics
