#pragma once
// Small models shared by the contact tests.
#include <cmath>
#include <numbers>
#include <vector>

#include "solver/model/builders.h"
#include "solver/model/model.h"

namespace skewbridge::contact::testing {

inline constexpr double kDeg = std::numbers::pi / 180.0;

/// A free deck (no substructure) of length L_m, skew a_deg and skew ratio eta0, unit mass,
/// uniform inertia, against the abutments `set` with gap delta, eps_N and mu.
inline model::Model FreeDeck(double a_deg, double eta0, double L_m, double delta_m, double eps,
                             double mu, model::AbutmentSet set = model::AbutmentSet::kPlusX,
                             double mass_kg = 1.0) {
  model::DeckSpec spec;
  spec.mass_kg = mass_kg;
  spec.geometry = {L_m, model::WidthFromEta0(eta0, a_deg * kDeg, L_m), a_deg * kDeg};
  spec.stiffness = model::DeckSpec::StiffnessKind::kUncoupled;
  spec.xi = 0.0;
  spec.abutments = set;
  spec.gap_plus_m = spec.gap_minus_m = delta_m;
  spec.restitution = eps;
  spec.friction = mu;
  return model::BuildDeckModel(spec);
}

/// Two decks: corner P1 of deck 0 against the -x end face of deck 1 (a deck-to-deck joint),
/// deck 1 resting 12 m further along x (a gap of about 1.8 m at rest). K = C = 0.
inline model::Model TwoDecks() {
  model::Body a;
  a.name = "span1";
  a.mass_kg = 2.0;
  a.inertia_kgm2 = 3.0;
  a.geometry = {10.0, 4.0, 25.0 * kDeg};
  model::Body b = a;
  b.name = "span2";
  b.mass_kg = 1.5;
  b.inertia_kgm2 = 2.5;
  b.rest_position_m = {12.0, 0.0};
  model::Contact joint;
  joint.name = "J1";
  joint.body = 0;
  joint.point_m = model::Corner(a.geometry, 1);
  joint.face.body = 1;
  // The -x end face of deck 1 in its own frame; deck 0's corner lies on its free (-x) side.
  model::Face face;
  face.body = 1;
  face.point_m = {-5.0, 0.0};
  face.normal = {-std::cos(25.0 * kDeg), std::sin(25.0 * kDeg)};
  face.tangent = {std::sin(25.0 * kDeg), std::cos(25.0 * kDeg)};
  joint.face = face;
  joint.restitution = 0.4;
  joint.friction = 0.3;
  std::vector<model::Contact> contacts{joint};
  const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(6, 6);
  return model::Model({a, b}, zero, zero, model::GroundInfluence(2), contacts, "two-decks");
}

}  // namespace skewbridge::contact::testing
