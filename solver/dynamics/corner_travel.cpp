#include "solver/dynamics/corner_travel.h"

#include <algorithm>
#include <limits>

#include "solver/model/deck.h"

namespace skewbridge::dynamics {

CornerTravelTracker::CornerTravelTracker(const model::Model& model) : n_(model.n_dof()) {
  for (const model::Body& body : model.bodies()) {
    Deck d;
    const double a = body.geometry.skew_rad;
    d.nx = std::cos(a);
    d.ny = -std::sin(a);
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d P = model::Corner(body.geometry, k + 1);
      d.A[k] = d.nx * P.x() + d.ny * P.y();
      d.B[k] = -d.nx * P.y() + d.ny * P.x();
      d.radius = std::max(d.radius, P.norm());  // |P_3| = |P_1|, |P_4| = |P_2|
    }
    decks_.push_back(d);
  }
  end_.resize(decks_.size());
  end_state_.assign(decks_.size(), {});
}

void CornerTravelTracker::Start(const Eigen::Ref<const Eigen::VectorXd>& q,
                                Eigen::VectorXd& max_travel_m) {
  max_travel_m = Eigen::VectorXd::Zero(decks());
  for (std::array<double, 6>& s : end_state_) {
    s.fill(
        std::numeric_limits<double>::quiet_NaN());  // equal to no state: the first step evaluates
  }
  Update(q, max_travel_m);
}

void CornerTravelTracker::Update(const Eigen::Ref<const Eigen::VectorXd>& q,
                                 Eigen::VectorXd& max_travel_m) const {
  for (int d = 0; d < decks(); ++d) {
    const Deck& deck = decks_[static_cast<std::size_t>(d)];
    const double x = q[3 * d], y = q[3 * d + 1], th = q[3 * d + 2];
    double s = 0.0, c = 0.0;
    SinCosMinusOne(th, s, c);
    const double T = deck.nx * x + deck.ny * y;
    const double g =
        std::max(std::abs(c * deck.A[0] + s * deck.B[0]), std::abs(c * deck.A[1] + s * deck.B[1]));
    max_travel_m[d] = std::max(max_travel_m[d], std::abs(T) + g);
  }
}

void CornerTravelTracker::Evaluate(const Deck& d, double x, double y, double th, double ux,
                                   double uy, double uth, CornerState& out) {
  double s = 0.0, c = 0.0;
  SinCosMinusOne(th, s, c);
  const double cos_th = 1.0 + c;
  const double T = d.nx * x + d.ny * y;
  const double T_rate = d.nx * ux + d.ny * uy;
  for (int k = 0; k < 2; ++k) {
    const double g = c * d.A[k] + s * d.B[k];
    const double g_rate = uth * (-s * d.A[k] + cos_th * d.B[k]);
    // Corners k and k + 2 are opposite: P_{k+2} = -P_k.
    out.f[static_cast<std::size_t>(k)] = T + g;
    out.f[static_cast<std::size_t>(k + 2)] = T - g;
    out.rate[static_cast<std::size_t>(k)] = T_rate + g_rate;
    out.rate[static_cast<std::size_t>(k + 2)] = T_rate - g_rate;
  }
}

double CornerTravelTracker::Rate(const Deck& d, int k, double ux, double uy, double th,
                                 double uth) {
  const int j = k % 2;
  const double sign = k < 2 ? 1.0 : -1.0;
  double s = 0.0, c = 0.0;
  SinCosMinusOne(th, s, c);
  return d.nx * ux + d.ny * uy + sign * uth * (-s * d.A[j] + (1.0 + c) * d.B[j]);
}

double CornerTravelTracker::Travel(const Deck& d, int k, double x, double y, double th) {
  const int j = k % 2;
  const double sign = k < 2 ? 1.0 : -1.0;
  double s = 0.0, c = 0.0;
  SinCosMinusOne(th, s, c);
  return d.nx * x + d.ny * y + sign * (c * d.A[j] + s * d.B[j]);
}

}  // namespace skewbridge::dynamics
