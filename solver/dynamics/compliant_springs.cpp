// The placement of compliant springs on a deck's abutments (WallSprings, AbutmentShearKeys) and the
// linear model they act on (WithoutContacts), declared in compliant_run.h.
#include <optional>
#include <string>
#include <vector>

#include "solver/common/error.h"
#include "solver/dynamics/compliant_run.h"

namespace skewbridge::dynamics {

std::vector<CompliantSpring> WallSprings(const model::Model& model, int first, int last,
                                         const joint::HyperbolicGap& wall, int n,
                                         const std::string& prefix) {
  const model::Contact& a = model.contact(first);
  const model::Contact& b = model.contact(last);
  SB_DEMAND(n >= 2 && a.body == b.body && a.face.body == b.face.body && a.face.body != a.body,
            "WallSprings: two corners of one deck against one face, n >= 2");
  joint::HyperbolicGap share = wall;
  share.k_max_N_per_m /= n;
  share.k_ur_N_per_m /= n;
  share.f_ult_N /= n;
  share.gap_m = 0.0;
  std::vector<CompliantSpring> springs;
  for (int i = 0; i < n; ++i) {
    CompliantSpring s;
    s.name = prefix + "." + std::to_string(i + 1);
    s.body = a.body;
    s.point_m = a.point_m + (b.point_m - a.point_m) * (static_cast<double>(i) / (n - 1));
    s.face = a.face;
    s.law = SpringLaw::kBackfill;
    s.backfill = share;
    springs.push_back(s);
  }
  return springs;
}

std::vector<CompliantSpring> SpringDashpots(const model::Model& model, int first, int last,
                                            double k_N_per_m, double c_Ns_per_m, int n,
                                            const std::string& prefix) {
  // WallSprings' points, each with an n-th of k and c in place of the backfill.
  std::vector<CompliantSpring> springs =
      WallSprings(model, first, last, joint::HyperbolicGap{1.0, 1.0, 1.0, 1.0, 0.0}, n, prefix);
  for (CompliantSpring& s : springs) {
    s.law = SpringLaw::kSpringDashpot;
    s.backfill = {};
    s.k_N_per_m = k_N_per_m / n;
    s.c_Ns_per_m = c_Ns_per_m / n;
  }
  return springs;
}

std::vector<CompliantSpring> AbutmentShearKeys(const model::Model& model, int first, int last,
                                               const joint::ShearKey& key,
                                               const std::string& prefix) {
  const model::Contact& a = model.contact(first);
  const model::Contact& b = model.contact(last);
  SB_DEMAND(a.body == b.body && a.point_m.y() * b.point_m.y() < 0.0,
            "AbutmentShearKeys: two corners of one deck end, on opposite sides");
  const Eigen::Vector2d& rest = model.body(a.body).rest_position_m;
  joint::ShearKey share = key;
  share.gap_m = 0.0;
  // The key of the side `side` (+1: y = W/2, -1: y = -W/2) on its corner c: the face
  // y = side (W/2 + gap) (rest frame), its normal -side y towards the deck.
  const auto one = [&](const model::Contact& c, double side) {
    CompliantSpring s;
    s.name = prefix + (side > 0.0 ? ".key+y" : ".key-y");
    s.body = c.body;
    s.point_m = c.point_m;
    s.face.body = model::kGround;
    s.face.normal = Eigen::Vector2d(0.0, -side);
    s.face.tangent = Eigen::Vector2d(-side, 0.0);
    s.face.point_m = rest + c.point_m + Eigen::Vector2d(0.0, side * key.gap_m);
    s.law = SpringLaw::kShearKey;
    s.key = share;
    return s;
  };
  const bool a_plus = a.point_m.y() > 0.0;
  return {one(a_plus ? a : b, 1.0), one(a_plus ? b : a, -1.0)};
}

model::Model WithoutContacts(const model::Model& model) {
  std::optional<model::Modes> modes;
  if (model.modes() != nullptr) modes = *model.modes();
  return model::Model(model.bodies(), model.K(), model.C(), model.r(), {}, model.source(),
                      std::move(modes));
}

}  // namespace skewbridge::dynamics
