#pragma once
// A test deck whose every mode moves x, y and theta together, for the bounds' tests.

#include <numbers>

#include "solver/model/builders.h"
#include "solver/model/deck.h"

namespace skewbridge::dynamics::testing {

/// A 30 m x 12 m deck skewed 40 deg on a principal-axes substructure (18, 26, 31 rad/s, axes
/// turned 0.4 rad) with its centre of rigidity 2.5 m, -1.5 m off the centre of mass, damping
/// ratio xi, both abutments (four corners) behind 50 mm gaps.
inline model::Model EccentricDeck(double xi) {
  model::DeckSpec spec;
  spec.mass_kg = 1.5e6;
  spec.geometry = {30.0, 12.0, 40.0 * std::numbers::pi / 180.0};
  spec.stiffness = model::DeckSpec::StiffnessKind::kPrincipal;
  spec.w1_radps = 18.0;
  spec.w2_radps = 26.0;
  spec.w_theta_radps = 31.0;
  spec.axis_rad = 0.4;
  spec.centre_of_rigidity_m = {2.5, -1.5};
  spec.xi = xi;
  spec.abutments = model::AbutmentSet::kBoth;
  spec.gap_plus_m = spec.gap_minus_m = 0.05;
  return model::BuildDeckModel(spec);
}

}  // namespace skewbridge::dynamics::testing
