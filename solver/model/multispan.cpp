#include "solver/model/multispan.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "solver/common/error.h"
#include "solver/model/checks.h"

namespace skewbridge::model {

using detail::CheckNonNegative;
using detail::CheckPositive;
using detail::CheckRange;
using detail::Fail;
using detail::Where;

namespace {

std::string Indexed(std::string_view table, std::size_t i, std::string_view key) {
  return std::string(table) + "[" + std::to_string(i) + "]." + std::string(key);
}

std::string ContactName(int deck, int corner, int face_deck) {
  // append() rather than operator+ on temporaries: g++ 12 reports a false -Wrestrict there.
  std::string name = "D";
  name.append(std::to_string(deck)).append(".P").append(std::to_string(corner));
  if (face_deck != kGround) {
    name.append("/D").append(std::to_string(face_deck));
  }
  return name;
}

}  // namespace

std::vector<Eigen::Vector2d> RestPositions(const MultiDeckSpec& spec) {
  SB_DEMAND(spec.joints.size() + 1 == spec.decks.size(), "one joint between consecutive decks");
  std::vector<Eigen::Vector2d> X(spec.decks.size(), Eigen::Vector2d::Zero());
  for (std::size_t i = 1; i < spec.decks.size(); ++i) {
    X[i].x() = X[i - 1].x() + 0.5 * spec.decks[i - 1].geometry.length_m + spec.joints[i - 1].gap_m +
               0.5 * spec.decks[i].geometry.length_m;
  }
  return X;
}

std::vector<Contact> JointContacts(const std::vector<Body>& decks, int i, const JointSpec& joint) {
  SB_DEMAND(i >= 0 && i + 1 < static_cast<int>(decks.size()), "joint index out of range");
  const Body& left = decks[static_cast<std::size_t>(i)];
  const Body& right = decks[static_cast<std::size_t>(i + 1)];
  const double a = left.geometry.skew_rad;
  const double s = std::sin(a);
  const double c = std::cos(a);
  // Equal widths: both ends coincide, so corners of either end against the other's face
  // describe the same two contact points; one pair avoids duplicate constraints
  // (docs/multispan.md).
  const bool left_strikes = left.geometry.width_m <= right.geometry.width_m;
  std::vector<Contact> contacts;
  for (int k : left_strikes ? std::vector<int>{1, 2} : std::vector<int>{3, 4}) {
    Contact contact;
    contact.restitution = joint.restitution;
    contact.friction = joint.friction;
    if (left_strikes) {
      contact.body = i;
      contact.point_m = Corner(left.geometry, k);
      contact.face.body = i + 1;
      contact.face.point_m = {-0.5 * right.geometry.length_m, 0.0};
      contact.face.normal = {-c, s};
      contact.face.tangent = {s, c};
    } else {
      contact.body = i + 1;
      contact.point_m = Corner(right.geometry, k);
      contact.face.body = i;
      contact.face.point_m = {0.5 * left.geometry.length_m, 0.0};
      contact.face.normal = {c, -s};
      contact.face.tangent = {-s, -c};
    }
    contact.name = ContactName(contact.body, k, contact.face.body);
    contacts.push_back(contact);
  }
  return contacts;
}

Model BuildMultiDeckModel(const MultiDeckSpec& spec, const std::string& source) {
  const Where where{source, 0};
  const std::size_t n_decks = spec.decks.size();
  if (n_decks == 0) {
    Fail(where, "deck", "at least one [[deck]] is required");
  }
  if (spec.joints.size() + 1 != n_decks) {
    Fail(where, "joint",
         "needs " + std::to_string(n_decks - 1) + " [[joint]] tables for " +
             std::to_string(n_decks) + " decks (got " + std::to_string(spec.joints.size()) + ")");
  }
  std::vector<Body> bodies = spec.decks;
  for (std::size_t i = 0; i < n_decks; ++i) {
    const Body& b = bodies[i];
    CheckPositive(b.mass_kg, Indexed("deck", i, "m"), where);
    CheckPositive(b.inertia_kgm2, Indexed("deck", i, "I_m"), where);
    CheckPositive(b.geometry.length_m, Indexed("deck", i, "L"), where);
    CheckPositive(b.geometry.width_m, Indexed("deck", i, "W"), where);
    CheckRange(b.geometry.skew_rad * 180.0 / std::numbers::pi, 0.0, 90.0, true,
               Indexed("deck", i, "skew_deg"), where, "deg");
  }
  for (std::size_t i = 0; i < spec.joints.size(); ++i) {
    const JointSpec& j = spec.joints[i];
    CheckNonNegative(j.gap_m, Indexed("joint", i, "gap_m"), where);
    CheckRange(j.restitution, 0.0, 1.0, false, Indexed("joint", i, "eps_N"), where);
    CheckNonNegative(j.friction, Indexed("joint", i, "mu"), where);
    if (bodies[i].geometry.skew_rad != bodies[i + 1].geometry.skew_rad) {
      Fail(where, Indexed("joint", i, "gap_m"),
           "decks " + std::to_string(i) + " and " + std::to_string(i + 1) +
               " must have the same skew_deg (their end faces are parallel)");
    }
  }
  CheckNonNegative(spec.gap_minus_m, "abutments.gap_m", where);
  CheckNonNegative(spec.gap_plus_m, "abutments.gap_m", where);
  CheckRange(spec.restitution, 0.0, 1.0, false, "abutments.eps_N", where);
  CheckNonNegative(spec.friction, "abutments.mu", where);
  const std::vector<Eigen::Vector2d> X = RestPositions(spec);
  for (std::size_t i = 0; i < n_decks; ++i) {
    bodies[i].rest_position_m = X[i];
    if (n_decks > 1) {
      bodies[i].name = std::string("D").append(std::to_string(i));
    }
  }

  const int n = 3 * static_cast<int>(n_decks);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t s = 0; s < spec.supports.size(); ++s) {
    const SupportSpec& support = spec.supports[s];
    if (support.deck < 0 || support.deck >= static_cast<int>(n_decks)) {
      Fail(where, Indexed("support", s, "deck"),
           "must be a deck index in [0, " + std::to_string(n_decks) + ")");
    }
    const bool link = support.other != kGround;
    if (link && (support.other < 0 || support.other >= static_cast<int>(n_decks) ||
                 support.other == support.deck)) {
      Fail(where, Indexed("support", s, "between"),
           "must name two different decks in [0, " + std::to_string(n_decks) + ")");
    }
    const char* keys[] = {"k_x", "k_y", "k_theta"};
    const char* damping_keys[] = {"c_x", "c_y", "c_theta"};
    for (int d = 0; d < 3; ++d) {
      CheckNonNegative(support.stiffness(d), Indexed("support", s, keys[d]), where);
      if (support.damping) {
        CheckNonNegative((*support.damping)(d), Indexed("support", s, damping_keys[d]), where);
      }
    }
    const Eigen::Matrix3d K_s = support.stiffness.asDiagonal();
    Eigen::Matrix3d C_s;
    if (support.damping) {
      C_s = support.damping->asDiagonal();
    } else if (link) {
      Fail(where, Indexed("support", s, "xi"),
           "a link between decks needs c_x, c_y, c_theta (xi applies to ground supports)");
    } else {
      CheckRange(support.xi, 0.0, 1.0, true, Indexed("support", s, "xi"), where);
      // The same call as BuildDeckModel's, so that one deck on one support is bit-identical.
      const std::vector<Body> one{bodies[static_cast<std::size_t>(support.deck)]};
      C_s = ClassicalDamping(MassMatrix(one), K_s, support.xi);
    }
    const int i = 3 * support.deck;
    K.block<3, 3>(i, i) += K_s;
    C.block<3, 3>(i, i) += C_s;
    if (link) {
      const int j = 3 * support.other;
      K.block<3, 3>(j, j) += K_s;
      C.block<3, 3>(j, j) += C_s;
      K.block<3, 3>(i, j) -= K_s;
      K.block<3, 3>(j, i) -= K_s;
      C.block<3, 3>(i, j) -= C_s;
      C.block<3, 3>(j, i) -= C_s;
    }
  }

  std::vector<Contact> contacts;
  if (n_decks == 1) {
    contacts = AbutmentContacts(bodies[0], 0, AbutmentSet::kBoth, spec.gap_plus_m, spec.gap_minus_m,
                                spec.restitution, spec.friction);
  } else {
    const auto abutment = [&](int deck, int corner, Face face) {
      const Body& b = bodies[static_cast<std::size_t>(deck)];
      face.point_m += b.rest_position_m;
      Contact contact;
      contact.name = ContactName(deck, corner, kGround);
      contact.body = deck;
      contact.point_m = Corner(b.geometry, corner);
      contact.face = face;
      contact.restitution = spec.restitution;
      contact.friction = spec.friction;
      contacts.push_back(contact);
    };
    const Face minus = MinusXAbutmentFace(bodies.front().geometry, spec.gap_minus_m);
    abutment(0, 3, minus);
    abutment(0, 4, minus);
    for (std::size_t i = 0; i < spec.joints.size(); ++i) {
      for (Contact& c : JointContacts(bodies, static_cast<int>(i), spec.joints[i])) {
        contacts.push_back(std::move(c));
      }
    }
    const int last = static_cast<int>(n_decks) - 1;
    const Face plus = PlusXAbutmentFace(bodies.back().geometry, spec.gap_plus_m);
    abutment(last, 1, plus);
    abutment(last, 2, plus);
  }
  return Model(std::move(bodies), K, C, GroundInfluence(static_cast<int>(n_decks)),
               std::move(contacts), source);
}

MultiDeckSpec MultiSpanDecks(const MultiSpanSpec& spec, const std::string& source) {
  const Where where{source, 0};
  if (spec.n_spans < 1) {
    Fail(where, "multispan.n_spans",
         "must be a whole number >= 1 (got " + std::to_string(spec.n_spans) + ")");
  }
  const std::size_t n = static_cast<std::size_t>(spec.n_spans);
  if (spec.span_lengths_m.size() != 1 && spec.span_lengths_m.size() != n) {
    Fail(where, "multispan.span_lengths_m",
         "must hold 1 or n_spans = " + std::to_string(n) + " lengths (got " +
             std::to_string(spec.span_lengths_m.size()) + ")");
  }
  CheckPositive(spec.width_m, "multispan.width_m", where);
  CheckRange(spec.skew_rad * 180.0 / std::numbers::pi, 0.0, 90.0, true, "multispan.skew_deg", where,
             "deg");
  CheckPositive(spec.mass_per_length_kgpm, "multispan.mass_per_length", where);
  CheckNonNegative(spec.w0x_radps, "multispan.w0x", where);
  CheckNonNegative(spec.w0y_radps, "multispan.w0y", where);
  CheckNonNegative(spec.W0_radps, "multispan.W0", where);
  CheckRange(spec.xi, 0.0, 1.0, true, "multispan.xi", where);
  if (spec.seat_width_m) {
    CheckPositive(*spec.seat_width_m, "multispan.seat_width_m", where);
  }
  MultiDeckSpec out;
  for (std::size_t i = 0; i < n; ++i) {
    const double L =
        spec.span_lengths_m.size() == 1 ? spec.span_lengths_m[0] : spec.span_lengths_m[i];
    CheckPositive(L, "multispan.span_lengths_m", where);
    Body b;
    b.geometry = {L, spec.width_m, spec.skew_rad};
    b.mass_kg = spec.mass_per_length_kgpm * L;
    b.inertia_kgm2 = UniformDeckInertia(b.mass_kg, b.geometry);
    SupportSpec support;
    support.deck = static_cast<int>(i);
    // UncoupledStiffness: the same products as the single-deck builder.
    support.stiffness =
        UncoupledStiffness(b, spec.w0x_radps, spec.w0y_radps, spec.W0_radps).diagonal();
    support.xi = spec.xi;
    out.decks.push_back(b);
    out.supports.push_back(support);
    if (i + 1 < n) {
      out.joints.push_back({spec.joint_gap_m, spec.restitution, spec.friction});
    }
  }
  out.gap_minus_m = spec.abutment_gap_m;
  out.gap_plus_m = spec.abutment_gap_m;
  out.restitution = spec.restitution;
  out.friction = spec.friction;
  out.seat_width_m = spec.seat_width_m;
  return out;
}

Model BuildMultiSpanBridge(const MultiSpanSpec& spec, const std::string& source) {
  return BuildMultiDeckModel(MultiSpanDecks(spec, source), source);
}

double UnseatingMargin(const Body& deck, double seat_width_m, const Eigen::Vector3d& max_abs_q) {
  return seat_width_m - CornerTravelBound(deck.geometry, max_abs_q);
}

}  // namespace skewbridge::model
