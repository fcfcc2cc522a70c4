#include "solver/dynamics/corner_travel.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <limits>

#include "solver/model/deck.h"

namespace skewbridge::dynamics {

void CornerTravelTracker::Assign(const model::Model& model) {
  n_ = model.n_dof();
  decks_.clear();
  decks_.reserve(model.bodies().size());
  // A deck's entry is a function of its geometry's bits alone: the last one this thread formed
  // is taken again for a deck of those bits (a sweep's cells that keep the geometry and differ
  // in their frequencies or excitation).
  struct Last {
    std::array<std::uint64_t, 3> key{};  // the bits of L, W and the skew
    bool valid = false;
    Deck deck;
  };
  thread_local Last last;
  for (const model::Body& body : model.bodies()) {
    const std::array<std::uint64_t, 3> key = {std::bit_cast<std::uint64_t>(body.geometry.length_m),
                                              std::bit_cast<std::uint64_t>(body.geometry.width_m),
                                              std::bit_cast<std::uint64_t>(body.geometry.skew_rad)};
    if (last.valid && last.key == key) {
      decks_.push_back(last.deck);
      continue;
    }
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
    last.deck = d;
    last.key = key;
    last.valid = true;
  }
  end_.resize(decks_.size());
}

void CornerTravelTracker::Start(const Eigen::Ref<const Eigen::VectorXd>& q,
                                Eigen::VectorXd& max_travel_m) {
  max_travel_m = Eigen::VectorXd::Zero(decks());
  for (DeckEnd& end : end_) {
    // Equal to no state: the first step evaluates.
    end.state.fill(std::numeric_limits<double>::quiet_NaN());
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

double CornerTravelTracker::Travel(const Deck& d, int k, double x, double y, double th) {
  const int j = k % 2;
  const double sign = k < 2 ? 1.0 : -1.0;
  double s = 0.0, c = 0.0;
  SinCosMinusOne(th, s, c);
  return d.nx * x + d.ny * y + sign * (c * d.A[j] + s * d.B[j]);
}

}  // namespace skewbridge::dynamics
