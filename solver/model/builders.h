#pragma once
/// @file
/// Builders of the substructure matrices and abutment contacts, and the plain-data description
/// of a single-deck bridge (DeckSpec) that the model file and the spectra both turn into a Model
/// [docs/theory.md §2, §6].

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "solver/model/model.h"
#include "solver/model/substructure.h"

namespace skewbridge::model {

/// K = diag(m w0x^2, m w0y^2, I_m W0^2) (N/m, N/m, N m/rad) [docs/theory.md §6, subsystem].
Eigen::Matrix3d UncoupledStiffness(const Body& body, double w0x_radps, double w0y_radps,
                                   double W0_radps);

/// The pilot bridge's stiffness K = T^T K_cr T [docs/theory.md §6] with
/// K_cr = blockdiag(R(phi) diag(m w1^2, m w2^2) R(phi)^T, I_m w_theta^2) about the centre of
/// rigidity (e_x, e_y) and T = [[1, 0, -e_y], [0, 1, e_x], [0, 0, 1]].
/// @param axis_rad phi, the angle of principal axis 1 from x (CCW positive).
Eigen::Matrix3d PrincipalAxesStiffness(const Body& body, double w1_radps, double w2_radps,
                                       double w_theta_radps, double axis_rad,
                                       const Eigen::Vector2d& centre_of_rigidity_m);

/// M = blockdiag(m, m, I_m) over the bodies.
Eigen::MatrixXd MassMatrix(const std::vector<Body>& bodies);

/// Ground influence r (n_dof x 2): unit entries mapping (a_gx, a_gy) to each body's (x, y).
Eigen::MatrixXd GroundInfluence(int n_bodies);

/// Solves the generalised eigenproblem K phi = w^2 M phi (Modes: solver/model/model.h).
/// @pre M symmetric positive definite, K symmetric positive semi-definite.
Modes ComputeModes(const Eigen::Ref<const Eigen::MatrixXd>& M,
                   const Eigen::Ref<const Eigen::MatrixXd>& K);

/// The lowest and highest natural frequency of a model (rad/s).
struct FrequencyRange {
  double lowest_radps = 0.0;   ///< 0 for a free body (rigid modes)
  double highest_radps = 0.0;  ///< the stiffest mode's frequency
};

/// The natural frequencies' range of `model`: from Model::modes() when the model carries them,
/// else from one eigenvalue-only solve of (K, M) (the eigenvalues of ComputeModes, same bits);
/// a free body's rigid modes, solved a rounding below zero, count as 0.
FrequencyRange NaturalFrequencyRange(const Model& model);

/// The lowest natural frequency of `model` (rad/s; 0 for a free body): what the integrators'
/// velocity scales, the spectra's end times and the plausibility warnings all use.
double LowestFrequency(const Model& model);

/// Mode shapes for display: column k is phi_k with each body's rotation times its radius of
/// gyration (x_i, y_i, rho_i theta_i, all in m), scaled so that its largest entry in magnitude
/// is +1; the components are then comparable across DOFs and independent of the
/// normalisation of phi.
Eigen::MatrixXd DisplayModeShapes(const Modes& modes, const std::vector<Body>& bodies);

/// Classical damping with ratio xi in every mode: C = M Phi diag(2 xi w_k) Phi^T M
/// [docs/theory.md §2, damping].
/// @throws InputError (field "substructure.xi") when xi is outside [0, 1).
Eigen::MatrixXd ClassicalDamping(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                 const Eigen::Ref<const Eigen::MatrixXd>& K, double xi);

/// The same from the modes of (K, M) already solved (ComputeModes(M, K)): the same bits.
Eigen::MatrixXd ClassicalDamping(const Eigen::Ref<const Eigen::MatrixXd>& M, const Modes& modes,
                                 double xi);

/// Which abutments a deck can strike: "+x" only (contacts P1, P2: the single-abutment
/// subsystem of docs/theory.md §6) or "both" (P1..P4).
enum class AbutmentSet { kPlusX, kBoth };

/// Contacts of deck `body_index` against ground-fixed abutments: P1, P2 against the +x face
/// with gap gap_plus_m, and for kBoth P3, P4 against the -x face with gap gap_minus_m (gaps
/// measured along x; the gap at rest is delta cos a). All get eps_N and mu.
std::vector<Contact> AbutmentContacts(const Body& body, int body_index, AbutmentSet set,
                                      double gap_plus_m, double gap_minus_m, double restitution,
                                      double friction);

/// Per-contact overrides of the abutment defaults.
struct ContactOverride {
  std::string name;                   ///< "P1".."P4"
  std::optional<double> restitution;  ///< eps_N
  std::optional<double> friction;     ///< mu
};

/// Plain data describing one deck on its substructure between abutments: everything the model
/// file's [deck], [substructure] and [abutments] sections say, in SI units.
struct DeckSpec {
  // [deck]
  double mass_kg = 0.0;                ///< deck.m
  std::optional<double> inertia_kgm2;  ///< deck.I_m; empty = uniform-deck rule
  DeckGeometry geometry;               ///< deck.L, deck.W (or eta0), deck.skew_deg

  // [substructure]
  enum class StiffnessKind { kUncoupled, kPrincipal, kMatrix, kElements };
  StiffnessKind stiffness = StiffnessKind::kUncoupled;
  double w0x_radps = 0.0;      ///< uncoupled: substructure.w0x
  double w0y_radps = 0.0;      ///< uncoupled: substructure.w0y
  double W0_radps = 0.0;       ///< uncoupled: substructure.W0 (torsion)
  double w1_radps = 0.0;       ///< principal: substructure.w1
  double w2_radps = 0.0;       ///< principal: substructure.w2
  double w_theta_radps = 0.0;  ///< principal: substructure.w_theta
  double axis_rad = 0.0;       ///< principal: substructure.axis_deg
  Eigen::Vector2d centre_of_rigidity_m = Eigen::Vector2d::Zero();  ///< substructure.e_x, e_y
  Eigen::Matrix3d K = Eigen::Matrix3d::Zero();                     ///< matrix: substructure.K
  std::vector<BearingSpec> bearings;  ///< elements: [[substructure.bearing]]
  std::vector<PierSpec> piers;        ///< elements: [[substructure.pier]]
  std::optional<Eigen::Matrix3d> C;   ///< substructure.C; empty = classical from xi
  double xi = 0.05;                   ///< substructure.xi

  // [abutments]
  AbutmentSet abutments = AbutmentSet::kPlusX;  ///< abutments.set
  double gap_plus_m = 0.0;                      ///< abutments.gap_m ("+x")
  double gap_minus_m = 0.0;                     ///< abutments.gap_m ("-x")
  double restitution = 0.5;                     ///< abutments.eps_N
  double friction = 0.0;                        ///< abutments.mu
  std::vector<ContactOverride> overrides;       ///< abutments.contacts.<name>
};

/// The modes and classical damping of single-deck models (3 DOFs) by the bits of (M, K, xi),
/// what BuildDeckModel keeps on its thread: a sweep's cells that differ only in their excitation
/// (a pulse's shape, a record, a stripe) build the same deck, and its modes and damping are a
/// function of those bits alone. Holds at most kCapacity entries in storage allocated once, on
/// first use (all dropped when full), so that it leaves the heap of the cells alone.
class DeckModesMemo {
 public:
  static constexpr std::size_t kCapacity = 8192;

  /// Writes the modes and damping held for (M, K, xi) (3 x 3 each) into `modes` and `C`; false
  /// (nothing written) when none is held.
  bool Find(const Eigen::MatrixXd& M, const Eigen::Matrix3d& K, double xi, Modes& modes,
            Eigen::MatrixXd& C) const;
  /// Writes ComputeModes(M, K) and ClassicalDamping(M, modes, xi) into `modes` and `C`, and
  /// holds them for (M, K, xi). @pre K passed CheckSymmetricPsd, xi in [0, 1).
  void Compute(const Eigen::MatrixXd& M, const Eigen::Matrix3d& K, double xi, Modes& modes,
               Eigen::MatrixXd& C);
  /// Number of entries held.
  std::size_t size() const { return entries_.size(); }

 private:
  // The bits of M (9), K (9) and xi.
  using Key = std::array<std::uint64_t, 19>;
  struct Entry {
    Key key;
    double omega[3], phi[9], eigenvalues[3], C[9];
  };
  static constexpr std::size_t kSlots = 2 * kCapacity;  // open addressing, a power of 2
  static Key KeyOf(const Eigen::MatrixXd& M, const Eigen::Matrix3d& K, double xi);
  static std::size_t SlotOf(const Key& key);
  // The slot of `key`: the one holding it or the empty one where it would go.
  std::size_t Probe(const Key& key) const;
  std::vector<Entry> entries_;        // reserved to kCapacity on first use
  std::vector<std::uint32_t> slots_;  // per slot, 1 + its entry's index (0: empty)
};

/// ComputeModes(M, K) and ClassicalDamping(M, modes, xi), bit for bit, of a deck whose M and K
/// are diagonal (every off-diagonal entry +0; M_ii > 0, K_ii >= 0 finite, xi in [0, 1)), by the
/// floating-point operations the generalised eigensolver performs on such a pair: L = diag(l_i),
/// l_i = sqrt(M_ii); c_i = (K_ii (1 / l_i)) (1 / l_i); the scaled c_i / s (s = max c_i, or 1)
/// need no rotation and are sorted ascending by selection (the first of equal ones first),
/// lambda = (c_i / s) s; Phi's column of c_i holds 1 / l_i in row i. The damping's products then
/// have one non-zero term each: C_ii = 0.5 (d_i + d_i), d_i = ((M_ii / l_i) 2 xi w) (M_ii / l_i).
/// @return false (nothing written) when M or K is not of that form: the general solve applies.
bool DiagonalDeckModes(const Eigen::MatrixXd& M, const Eigen::Matrix3d& K, double xi, Modes& modes,
                       Eigen::MatrixXd& C);

/// Builds and validates the Model described by a DeckSpec.
/// @throws InputError naming the model-file key (e.g. "deck.W: must be > 0 (got -1)") for any
/// value outside its range; `source` prefixes the message.
Model BuildDeckModel(const DeckSpec& spec, const std::string& source = "model");

}  // namespace skewbridge::model
