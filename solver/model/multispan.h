#pragma once
/// @file
/// Multi-span bridges: N decks in a row along x, each a planar rigid body, separated by joints
/// at which consecutive decks pound against each other, with abutments at both ends and linear
/// supports (bearings, piers) to the ground or between decks [docs/theory.md §2, contacts (general
/// form): the face of a deck-to-deck contact moves with its deck]. docs/multispan.md derives the
/// contact geometry; docs/model-format.md gives the file form ([[deck]], [[joint]], [[support]]).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "solver/model/builders.h"
#include "solver/model/model.h"

namespace skewbridge::model {

/// A linear spring-dashpot of deck `deck` to the ground (other == kGround) or a link between
/// decks `deck` and `other`, acting on the deck's DOFs (x, y, theta) about its mass centre:
/// strain energy 1/2 d^T diag(k) d with d = q_deck (ground) or d = q_other - q_deck (link).
struct SupportSpec {
  int deck = 0;                                         ///< support.deck
  int other = kGround;                                  ///< support.between[1], or ground
  Eigen::Vector3d stiffness = Eigen::Vector3d::Zero();  ///< k_x, k_y (N/m), k_theta (N m/rad)
  std::optional<Eigen::Vector3d> damping;               ///< c_x, c_y (N s/m), c_theta (N m s)
  double xi = 0.05;  ///< when damping is empty: ratio of the deck's own modes on this support
};

/// A joint between decks i and i + 1: the gap (m, along x) and the contact laws of its corners.
struct JointSpec {
  double gap_m = 0.0;        ///< joint.gap_m >= 0
  double restitution = 0.5;  ///< joint.eps_N in [0, 1]
  double friction = 0.0;     ///< joint.mu >= 0
};

/// Plain data describing N decks in a row (the [[deck]] form of the model file), SI units.
struct MultiDeckSpec {
  std::vector<Body> decks;             ///< mass, inertia, geometry; rest positions are computed
  std::vector<JointSpec> joints;       ///< decks.size() - 1 joints, joint i after deck i
  double gap_minus_m = 0.0;            ///< -x abutment gap of deck 0 (m, along x)
  double gap_plus_m = 0.0;             ///< +x abutment gap of the last deck (m, along x)
  double restitution = 0.5;            ///< abutments.eps_N
  double friction = 0.0;               ///< abutments.mu
  std::vector<SupportSpec> supports;   ///< bearings, piers, links
  std::optional<double> seat_width_m;  ///< support seat width for unseating margins (m)
};

/// Rest positions X_i = (sum_{k < i} (L_k / 2 + delta_k + L_{k+1} / 2), 0) of the mass centres
/// (m): deck 0 at the origin, each joint gap delta_k measured along x between the end-edge
/// mid-points.
/// @pre joints.size() + 1 == decks.size().
std::vector<Eigen::Vector2d> RestPositions(const MultiDeckSpec& spec);

/// The two contacts of one joint between decks i and i + 1 of equal skew a: the corners of the
/// narrower end (P1, P2 of deck i when W_i <= W_{i+1}, else P3, P4 of deck i + 1) against the end
/// face of the other deck, which moves with that deck. The face of deck i + 1's -x end has
/// n = (-cos a, sin a), t = (sin a, cos a), A = (-L_{i+1} / 2, 0) in its frame; deck i's +x end
/// n = (cos a, -sin a), t = (-sin a, -cos a), A = (L_i / 2, 0). At rest each gap is delta cos a.
/// Names "D<i>.P<k>/D<j>": corner k of deck i against deck j.
/// @pre i + 1 < decks.size(); decks carry their rest positions.
std::vector<Contact> JointContacts(const std::vector<Body>& decks, int i, const JointSpec& joint);

/// Builds and validates the Model of N decks: bodies at their rest positions, M diagonal,
/// K and C assembled from the supports (ground supports on the deck's 3 x 3 diagonal block, links
/// as [[K, -K], [-K, K]] on the two decks' blocks; C from the given c or, for a ground support,
/// the deck's classical damping C = M Phi diag(2 xi w) Phi^T M on that support), contacts: deck
/// 0's P3, P4 against the -x abutment, the joints, the last deck's P1, P2 against the +x
/// abutment. With one deck and one ground support the result is the single-deck model of
/// BuildDeckModel (contacts P1..P4, the same K and C bit for bit).
/// @throws InputError naming the field (deck[2].W, joint[1].gap_m, support[0].k_x, ...) for a
/// value outside its range, a joint between decks of different skew, a wrong joint count or a
/// support deck index out of range.
Model BuildMultiDeckModel(const MultiDeckSpec& spec, const std::string& source = "model");

/// The handful of parameters of an N-span bridge with identical cross-sections.
struct MultiSpanSpec {
  int n_spans = 1;                     ///< N >= 1
  std::vector<double> span_lengths_m;  ///< one length for every span, or N lengths (m)
  double width_m = 0.0;                ///< W (m)
  double skew_rad = 0.0;               ///< a, 0 <= a < pi/2 (rad)
  double mass_per_length_kgpm = 0.0;   ///< m_i = mass_per_length L_i (kg/m)
  double w0x_radps = 0.0;              ///< bearing frequency along x per span: k_x = m_i w0x^2
  double w0y_radps = 0.0;              ///< along y: k_y = m_i w0y^2
  double W0_radps = 0.0;               ///< torsional: k_theta = I_m,i W0^2 (uniform deck I_m)
  double xi = 0.05;                    ///< damping ratio of every deck's own modes
  double abutment_gap_m = 0.0;         ///< both abutment gaps (m, along x)
  double joint_gap_m = 0.0;            ///< every joint gap (m, along x)
  double restitution = 0.5;            ///< eps_N of every contact
  double friction = 0.0;               ///< mu of every contact
  std::optional<double> seat_width_m;  ///< seat width at every support (m)
};

/// The MultiDeckSpec of an N-span bridge: deck i of length L_i, mass m_i = mass_per_length L_i,
/// uniform inertia, a ground support diag(m_i w0x^2, m_i w0y^2, I_m,i W0^2) with ratio xi.
/// @throws InputError naming the field (multispan.n_spans, multispan.width_m, ...).
MultiDeckSpec MultiSpanDecks(const MultiSpanSpec& spec, const std::string& source = "model");

/// BuildMultiDeckModel(MultiSpanDecks(spec)).
/// @throws InputError as MultiSpanDecks and BuildMultiDeckModel.
Model BuildMultiSpanBridge(const MultiSpanSpec& spec, const std::string& source = "model");

/// Unseating margin of a deck's end seats (m) from the maxima of its response: seat width minus
/// the largest displacement of a corner normal to its end line, CornerTravelBound (the maxima
/// need not coincide, so the margin is a lower bound). The sweeps store seat width minus the exact
/// travel that the integrators track (dynamics::RunResult::max_travel_m) instead.
/// @param max_abs_q (x_m, y_m, theta_m) = the deck's max |x|, |y| (m), |theta| (rad).
double UnseatingMargin(const Body& deck, double seat_width_m, const Eigen::Vector3d& max_abs_q);

}  // namespace skewbridge::model
