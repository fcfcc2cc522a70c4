#include "solver/model/builders.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
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

// The checks of BuildDeckModel: each calls the named check, which builds the message, only
// when the value fails it (a sweep builds a deck per cell).
void RequirePositive(double value, std::string_view field, const Where& where) {
  if (!(std::isfinite(value) && value > 0.0)) CheckPositive(value, field, where);
}
void RequireNonNegative(double value, std::string_view field, const Where& where) {
  if (!(std::isfinite(value) && value >= 0.0)) CheckNonNegative(value, field, where);
}
void RequireRange(double value, double lo, double hi, bool hi_open, std::string_view field,
                  const Where& where, std::string_view unit = {}) {
  if (!(std::isfinite(value) && value >= lo && (hi_open ? value < hi : value <= hi))) {
    CheckRange(value, lo, hi, hi_open, field, where, unit);
  }
}

void CheckSpring(const PlanSpring& k, const std::string& prefix, bool positive,
                 const Where& where) {
  if (positive) {
    CheckPositive(k.k_strong_Npm, prefix + ".k_strong_Npm", where);
    CheckPositive(k.k_weak_Npm, prefix + ".k_weak_Npm", where);
  } else {
    CheckNonNegative(k.k_strong_Npm, prefix + ".k_strong_Npm", where);
    CheckNonNegative(k.k_weak_Npm, prefix + ".k_weak_Npm", where);
  }
  detail::CheckFinite(k.strong_axis_rad, prefix + ".strong_axis_deg", where);
}

// The elements a deck stands on: stiffnesses in range, every bearing on an existing pier (or
// the ground), every pier carrying a bearing (else it holds nothing up).
void CheckElements(const std::vector<BearingSpec>& bearings, const std::vector<PierSpec>& piers,
                   const Where& where) {
  if (bearings.empty()) {
    Fail(where, "substructure.bearing", "at least one [[substructure.bearing]] is required");
  }
  std::vector<bool> carries(piers.size(), false);
  for (std::size_t i = 0; i < bearings.size(); ++i) {
    const std::string name = "substructure.bearing[" + std::to_string(i) + "]";
    const BearingSpec& b = bearings[i];
    detail::CheckFinite(b.position_m.x(), name + ".x_m", where);
    detail::CheckFinite(b.position_m.y(), name + ".y_m", where);
    CheckSpring(b.spring, name, false, where);
    if (b.pier >= static_cast<int>(piers.size()) || b.pier < -1) {
      Fail(where, name + ".pier",
           "must be a pier index in [0, " + std::to_string(piers.size()) + ") (got " +
               std::to_string(b.pier) + ")");
    }
    if (b.pier >= 0) {
      carries[static_cast<std::size_t>(b.pier)] = true;
    }
  }
  for (std::size_t p = 0; p < piers.size(); ++p) {
    const std::string name = "substructure.pier[" + std::to_string(p) + "]";
    detail::CheckFinite(piers[p].position_m.x(), name + ".x_m", where);
    detail::CheckFinite(piers[p].position_m.y(), name + ".y_m", where);
    CheckSpring(piers[p].spring, name, true, where);
    if (!carries[p]) {
      Fail(where, name,
           "no bearing sits on it (give a bearing with pier = " + std::to_string(p) +
               ", or remove the pier)");
    }
  }
}

}  // namespace

Eigen::Matrix3d UncoupledStiffness(const Body& body, double w0x_radps, double w0y_radps,
                                   double W0_radps) {
  Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
  K(0, 0) = body.mass_kg * w0x_radps * w0x_radps;
  K(1, 1) = body.mass_kg * w0y_radps * w0y_radps;
  K(2, 2) = body.inertia_kgm2 * W0_radps * W0_radps;
  return K;
}

Eigen::Matrix3d PrincipalAxesStiffness(const Body& body, double w1_radps, double w2_radps,
                                       double w_theta_radps, double axis_rad,
                                       const Eigen::Vector2d& centre_of_rigidity_m) {
  const double c = std::cos(axis_rad);
  const double s = std::sin(axis_rad);
  Eigen::Matrix2d R;
  R << c, -s, s, c;
  const Eigen::Vector2d principal(body.mass_kg * w1_radps * w1_radps,
                                  body.mass_kg * w2_radps * w2_radps);
  Eigen::Matrix3d K_cr = Eigen::Matrix3d::Zero();
  K_cr.topLeftCorner<2, 2>() = R * principal.asDiagonal() * R.transpose();
  K_cr(2, 2) = body.inertia_kgm2 * w_theta_radps * w_theta_radps;
  // Displacements of the centre of rigidity: (x - e_y theta, y + e_x theta, theta) = T q.
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  T(0, 2) = -centre_of_rigidity_m.y();
  T(1, 2) = centre_of_rigidity_m.x();
  const Eigen::Matrix3d K = T.transpose() * K_cr * T;
  return 0.5 * (K + K.transpose());
}

Eigen::MatrixXd MassMatrix(const std::vector<Body>& bodies) {
  const int n = 3 * static_cast<int>(bodies.size());
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const int k = 3 * static_cast<int>(i);
    M(k, k) = bodies[i].mass_kg;
    M(k + 1, k + 1) = bodies[i].mass_kg;
    M(k + 2, k + 2) = bodies[i].inertia_kgm2;
  }
  return M;
}

Eigen::MatrixXd GroundInfluence(int n_bodies) {
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(3 * n_bodies, 2);
  for (int i = 0; i < n_bodies; ++i) {
    r(3 * i, 0) = 1.0;
    r(3 * i + 1, 1) = 1.0;
  }
  return r;
}

Modes ComputeModes(const Eigen::Ref<const Eigen::MatrixXd>& M,
                   const Eigen::Ref<const Eigen::MatrixXd>& K) {
  // The generalised solver returns M-orthonormal eigenvectors, ascending eigenvalues.
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
  SB_DEMAND(eig.info() == Eigen::Success, "generalised eigenproblem failed");
  Modes modes;
  modes.omega_radps = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  modes.phi = eig.eigenvectors();
  modes.eigenvalues = eig.eigenvalues();
  return modes;
}

FrequencyRange NaturalFrequencyRange(const Model& model) {
  double smallest = 0.0, largest = 0.0;
  if (model.modes() != nullptr) {
    smallest = model.modes()->eigenvalues.minCoeff();
    largest = model.modes()->eigenvalues.maxCoeff();
  } else {
    // The eigenvalues of the generalised solver do not depend on whether it also forms the
    // eigenvectors (the same reduction and QR sweeps), so these are ComputeModes' bits.
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(model.K(), model.M(),
                                                                        Eigen::EigenvaluesOnly);
    SB_DEMAND(eig.info() == Eigen::Success, "generalised eigenproblem failed");
    smallest = eig.eigenvalues().minCoeff();
    largest = eig.eigenvalues().maxCoeff();
  }
  return {std::sqrt(std::max(smallest, 0.0)), std::sqrt(std::max(largest, 0.0))};
}

double LowestFrequency(const Model& model) { return NaturalFrequencyRange(model).lowest_radps; }

Eigen::MatrixXd DisplayModeShapes(const Modes& modes, const std::vector<Body>& bodies) {
  SB_DEMAND(modes.phi.rows() == 3 * static_cast<Eigen::Index>(bodies.size()),
            "mode shapes and bodies disagree in size");
  Eigen::MatrixXd shapes = modes.phi;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const double rho_m = std::sqrt(bodies[i].inertia_kgm2 / bodies[i].mass_kg);
    shapes.row(3 * static_cast<Eigen::Index>(i) + 2) *= rho_m;
  }
  for (Eigen::Index k = 0; k < shapes.cols(); ++k) {
    Eigen::Index largest = 0;
    shapes.col(k).cwiseAbs().maxCoeff(&largest);
    const double scale = shapes(largest, k);
    if (scale != 0.0) {
      shapes.col(k) /= scale;
    }
  }
  return shapes;
}

Eigen::MatrixXd ClassicalDamping(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                 const Eigen::Ref<const Eigen::MatrixXd>& K, double xi) {
  CheckRange(xi, 0.0, 1.0, true, "substructure.xi", Where{"model", 0});
  return ClassicalDamping(M, ComputeModes(M, K), xi);
}

Eigen::MatrixXd ClassicalDamping(const Eigen::Ref<const Eigen::MatrixXd>& M, const Modes& modes,
                                 double xi) {
  CheckRange(xi, 0.0, 1.0, true, "substructure.xi", Where{"model", 0});
  const Eigen::MatrixXd MPhi = M * modes.phi;
  const Eigen::VectorXd modal = 2.0 * xi * modes.omega_radps;
  const Eigen::MatrixXd C = MPhi * modal.asDiagonal() * MPhi.transpose();
  return 0.5 * (C + C.transpose());
}

namespace {

// The faces and corners of the last deck geometry AbutmentContacts placed on this thread: they
// are functions of the geometry's and the gaps' bits alone, and a sweep's cells that differ in
// their frequencies or excitation keep the geometry (the default spec's 81 cells of each skew).
struct AbutmentGeometryMemo {
  std::array<std::uint64_t, 5> key{};  // the bits of L, W, skew, gap_plus_m, gap_minus_m
  int count = 0;                       // corners placed (2 or 4); 0: none yet
  Face plus, minus;
  Eigen::Vector2d corners[4];
};

std::array<std::uint64_t, 5> AbutmentKeyOf(const DeckGeometry& g, double gap_plus_m,
                                           double gap_minus_m) {
  return {std::bit_cast<std::uint64_t>(g.length_m), std::bit_cast<std::uint64_t>(g.width_m),
          std::bit_cast<std::uint64_t>(g.skew_rad), std::bit_cast<std::uint64_t>(gap_plus_m),
          std::bit_cast<std::uint64_t>(gap_minus_m)};
}

}  // namespace

std::vector<Contact> AbutmentContacts(const Body& body, int body_index, AbutmentSet set,
                                      double gap_plus_m, double gap_minus_m, double restitution,
                                      double friction) {
  const int count = set == AbutmentSet::kBoth ? 4 : 2;
  std::vector<Contact> contacts(static_cast<std::size_t>(count));
  thread_local AbutmentGeometryMemo memo;
  const std::array<std::uint64_t, 5> key = AbutmentKeyOf(body.geometry, gap_plus_m, gap_minus_m);
  if (memo.count != count || memo.key != key) {
    memo.count = 0;  // invalid until every entry below is written
    memo.plus = PlusXAbutmentFace(body.geometry, gap_plus_m);
    // The -x face only for the contacts that strike it (a sweep builds a deck per cell).
    memo.minus = count > 2 ? MinusXAbutmentFace(body.geometry, gap_minus_m) : Face{};
    for (int k = 1; k <= count; ++k) memo.corners[k - 1] = Corner(body.geometry, k);
    memo.key = key;
    memo.count = count;
  }
  constexpr const char* kNames[] = {"P1", "P2", "P3", "P4"};
  for (int k = 1; k <= count; ++k) {
    Contact& c = contacts[static_cast<std::size_t>(k - 1)];
    c.name = kNames[k - 1];
    c.body = body_index;
    c.point_m = memo.corners[k - 1];
    c.face = k <= 2 ? memo.plus : memo.minus;
    c.restitution = restitution;
    c.friction = friction;
  }
  return contacts;
}

DeckModesMemo::Key DeckModesMemo::KeyOf(const Eigen::MatrixXd& M, const Eigen::Matrix3d& K,
                                        double xi) {
  SB_DEMAND(M.rows() == 3 && M.cols() == 3, "DeckModesMemo: a deck's M is 3 x 3");
  Key key{};
  std::memcpy(key.data(), M.data(), 9 * sizeof(double));
  std::memcpy(key.data() + 9, K.data(), 9 * sizeof(double));
  std::memcpy(key.data() + 18, &xi, sizeof(double));
  return key;
}

std::size_t DeckModesMemo::SlotOf(const Key& key) {
  std::uint64_t h = 0x9e3779b97f4a7c15ULL;
  for (const std::uint64_t word : key) {
    h ^= word + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
  }
  return static_cast<std::size_t>(h ^ (h >> 29)) & (kSlots - 1);
}

std::size_t DeckModesMemo::Probe(const Key& key) const {
  std::size_t slot = SlotOf(key);
  // At most half the slots are used: an empty one ends every probe.
  while (slots_[slot] != 0 && entries_[slots_[slot] - 1].key != key) {
    slot = (slot + 1) & (kSlots - 1);
  }
  return slot;
}

bool DeckModesMemo::Find(const Eigen::MatrixXd& M, const Eigen::Matrix3d& K, double xi,
                         Modes& modes, Eigen::MatrixXd& C) const {
  if (entries_.empty()) return false;
  const std::size_t slot = Probe(KeyOf(M, K, xi));
  if (slots_[slot] == 0) return false;
  const Entry& e = entries_[slots_[slot] - 1];
  modes.omega_radps = Eigen::Map<const Eigen::Vector3d>(e.omega);
  modes.phi = Eigen::Map<const Eigen::Matrix3d>(e.phi);
  modes.eigenvalues = Eigen::Map<const Eigen::Vector3d>(e.eigenvalues);
  C = Eigen::Map<const Eigen::Matrix3d>(e.C);
  return true;
}

bool DiagonalDeckModes(const Eigen::MatrixXd& M, const Eigen::Matrix3d& K, double xi, Modes& modes,
                       Eigen::MatrixXd& C) {
  if (M.rows() != 3 || M.cols() != 3 || !(xi >= 0.0 && xi < 1.0)) return false;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      if (i == j) continue;
      if (std::bit_cast<std::uint64_t>(M(i, j)) != 0 ||
          std::bit_cast<std::uint64_t>(K(i, j)) != 0) {
        return false;
      }
    }
    const double m = M(j, j), k = K(j, j);
    if (!(std::isfinite(m) && m > 0.0 && std::isfinite(k) &&
          (k > 0.0 || std::bit_cast<std::uint64_t>(k) == 0))) {
      return false;
    }
  }
  // The Cholesky factor's diagonal, and the triangular solves' multiplications by its inverse:
  // L^-1 K L^-T, whose off-diagonal entries stay +0 (0 - 0 x, x >= 0).
  double inv_l[3], c[3];
  for (int i = 0; i < 3; ++i) {
    inv_l[i] = 1.0 / std::sqrt(M(i, i));
    c[i] = (K(i, i) * inv_l[i]) * inv_l[i];
  }
  // The eigensolver scales by the largest magnitude; the tridiagonalisation of a diagonal matrix
  // is the identity (Householder coefficients 0), the QR sweeps find every sub-diagonal zero.
  double scale = std::max(std::max(c[0], c[1]), c[2]);
  if (scale == 0.0) scale = 1.0;
  double d[3];
  int row[3] = {0, 1, 2};  // the row of column k's non-zero entry
  for (int i = 0; i < 3; ++i) d[i] = c[i] / scale;
  // Selection sort as the solver does it: the first smallest of d[i..2] to position i.
  for (int i = 0; i < 2; ++i) {
    int k = i;
    for (int j = i + 1; j < 3; ++j) {
      if (d[j] < d[k]) k = j;
    }
    if (k != i) {
      std::swap(d[i], d[k]);
      std::swap(row[i], row[k]);
    }
  }
  modes.eigenvalues.resize(3);
  modes.omega_radps.resize(3);
  modes.phi.setZero(3, 3);
  C.setZero(3, 3);
  const double two_xi = 2.0 * xi;
  for (int k = 0; k < 3; ++k) {
    const int r = row[k];
    const double lambda = d[k] * scale;
    const double omega = std::sqrt(std::max(lambda, 0.0));
    modes.eigenvalues[k] = lambda;
    modes.omega_radps[k] = omega;
    modes.phi(r, k) = 1.0 * inv_l[r];
    // M Phi has M_rr Phi_rk alone in row r; (M Phi diag(2 xi w) (M Phi)^T)_rr its one term.
    const double mphi = M(r, r) * modes.phi(r, k);
    const double d_rr = (mphi * (two_xi * omega)) * mphi;
    C(r, r) = 0.5 * (d_rr + d_rr);
  }
  return true;
}

void DeckModesMemo::Compute(const Eigen::MatrixXd& M, const Eigen::Matrix3d& K, double xi,
                            Modes& modes, Eigen::MatrixXd& C) {
  if (!DiagonalDeckModes(M, K, xi, modes, C)) {
    modes = ComputeModes(M, K);
    C = ClassicalDamping(M, modes, xi);
  }
  SB_DEMAND(modes.phi.rows() == 3 && modes.phi.cols() == 3 && C.rows() == 3 && C.cols() == 3,
            "DeckModesMemo: a deck's modes are 3 x 3");
  if (slots_.empty()) {
    slots_.assign(kSlots, 0);
    entries_.reserve(kCapacity);
  }
  if (entries_.size() >= kCapacity) {
    entries_.clear();
    std::fill(slots_.begin(), slots_.end(), 0);
  }
  Entry e;
  e.key = KeyOf(M, K, xi);
  const std::size_t slot = Probe(e.key);
  if (slots_[slot] != 0) return;  // held already
  std::memcpy(e.omega, modes.omega_radps.data(), sizeof e.omega);
  std::memcpy(e.phi, modes.phi.data(), sizeof e.phi);
  std::memcpy(e.eigenvalues, modes.eigenvalues.data(), sizeof e.eigenvalues);
  std::memcpy(e.C, C.data(), sizeof e.C);
  entries_.push_back(e);
  slots_[slot] = static_cast<std::uint32_t>(entries_.size());
}

Model BuildDeckModel(const DeckSpec& spec, const std::string& source) {
  const Where where{source, 0};
  RequirePositive(spec.mass_kg, "deck.m", where);
  RequirePositive(spec.geometry.length_m, "deck.L", where);
  RequirePositive(spec.geometry.width_m, "deck.W", where);
  RequireRange(spec.geometry.skew_rad * 180.0 / std::numbers::pi, 0.0, 90.0, true, "deck.skew_deg",
               where, "deg");
  Body body;
  body.mass_kg = spec.mass_kg;
  body.geometry = spec.geometry;
  if (spec.inertia_kgm2) {
    RequirePositive(*spec.inertia_kgm2, "deck.I_m", where);
    body.inertia_kgm2 = *spec.inertia_kgm2;
  } else {
    body.inertia_kgm2 = UniformDeckInertia(spec.mass_kg, spec.geometry);
  }

  Eigen::Matrix3d K;
  switch (spec.stiffness) {
    case DeckSpec::StiffnessKind::kUncoupled:
      RequireNonNegative(spec.w0x_radps, "substructure.w0x", where);
      RequireNonNegative(spec.w0y_radps, "substructure.w0y", where);
      RequireNonNegative(spec.W0_radps, "substructure.W0", where);
      K = UncoupledStiffness(body, spec.w0x_radps, spec.w0y_radps, spec.W0_radps);
      break;
    case DeckSpec::StiffnessKind::kPrincipal:
      RequireNonNegative(spec.w1_radps, "substructure.w1", where);
      RequireNonNegative(spec.w2_radps, "substructure.w2", where);
      RequireNonNegative(spec.w_theta_radps, "substructure.w_theta", where);
      detail::CheckFinite(spec.axis_rad, "substructure.axis_deg", where);
      detail::CheckFinite(spec.centre_of_rigidity_m.x(), "substructure.e_x", where);
      detail::CheckFinite(spec.centre_of_rigidity_m.y(), "substructure.e_y", where);
      K = PrincipalAxesStiffness(body, spec.w1_radps, spec.w2_radps, spec.w_theta_radps,
                                 spec.axis_rad, spec.centre_of_rigidity_m);
      break;
    case DeckSpec::StiffnessKind::kElements:
      CheckElements(spec.bearings, spec.piers, where);
      K = ElementsStiffness(spec.bearings, spec.piers);
      break;
    case DeckSpec::StiffnessKind::kMatrix:
    default:
      K = spec.K;
      break;
  }
  std::vector<Body> bodies{body};
  // The mass matrix of the modes' solve (MassMatrix's entries) in the thread's storage: a sweep
  // builds a deck per cell, and the model forms its own M.
  thread_local Eigen::MatrixXd M;
  M.setZero(3, 3);
  M(0, 0) = body.mass_kg;
  M(1, 1) = body.mass_kg;
  M(2, 2) = body.inertia_kgm2;
  Eigen::MatrixXd C;
  // The modes the damping is built from go with the model: the integrator's modal flow needs
  // the same solve (a sweep builds a model per cell).
  std::optional<Modes> modes;
  if (spec.C) {
    C = *spec.C;
  } else {
    RequireRange(spec.xi, 0.0, 1.0, true, "substructure.xi", where);
    if (!K.allFinite()) {
      Fail(where, "substructure.K", "must contain finite numbers only (got NaN or Inf)");
    }
    // Damping needs a valid K: the Model checks it again, but an asymmetric K would make
    // the modes meaningless, so report it here first. The deck's fields are checked above but
    // for a computed I_m, which the Model would name first.
    RequirePositive(body.inertia_kgm2, "deck.I_m", where);
    // A diagonal K (a subsystem's) of finite entries >= 0 passes the check, and its modes and
    // damping cost less than a look-up (DiagonalDeckModes). Otherwise a deck of the same
    // (M, K, xi) bits as one built before on this thread (a sweep's cells that differ only in
    // their excitation): its K passed the check, its modes and damping are those bits'
    // (DeckModesMemo).
    thread_local DeckModesMemo memo;
    modes.emplace();
    if (!DiagonalDeckModes(M, K, spec.xi, *modes, C) && !memo.Find(M, K, spec.xi, *modes, C)) {
      detail::CheckSymmetricPsd(K, 3, "substructure.K", where, true);
      memo.Compute(M, K, spec.xi, *modes, C);
    }
  }

  RequireNonNegative(spec.gap_plus_m, "abutments.gap_m", where);
  RequireNonNegative(spec.gap_minus_m, "abutments.gap_m", where);
  RequireRange(spec.restitution, 0.0, 1.0, false, "abutments.eps_N", where);
  RequireNonNegative(spec.friction, "abutments.mu", where);
  std::vector<Contact> contacts = AbutmentContacts(
      body, 0, spec.abutments, spec.gap_plus_m, spec.gap_minus_m, spec.restitution, spec.friction);
  for (const ContactOverride& o : spec.overrides) {
    Contact* target = nullptr;
    for (Contact& c : contacts) {
      if (c.name == o.name) {
        target = &c;
      }
    }
    if (target == nullptr) {
      Fail(where, "abutments.contacts." + o.name,
           spec.abutments == AbutmentSet::kBoth
               ? "unknown contact (allowed: P1, P2, P3, P4)"
               : "unknown contact (allowed with set = \"+x\": P1, P2)");
    }
    if (o.restitution) {
      RequireRange(*o.restitution, 0.0, 1.0, false, "abutments.contacts." + o.name + ".eps_N",
                   where);
      target->restitution = *o.restitution;
    }
    if (o.friction) {
      RequireNonNegative(*o.friction, "abutments.contacts." + o.name + ".mu", where);
      target->friction = *o.friction;
    }
  }
  return Model(std::move(bodies), K, std::move(C), GroundInfluence(1), std::move(contacts), source,
               std::move(modes));
}

}  // namespace skewbridge::model
