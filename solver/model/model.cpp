#include "solver/model/model.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <cstring>
#include <numbers>

#include "solver/common/error.h"
#include "solver/model/checks.h"

namespace skewbridge::model {

using detail::CheckFinite;
using detail::CheckNonNegative;
using detail::CheckPositive;
using detail::CheckRange;
using detail::CheckSymmetricPsd;
using detail::Fail;
using detail::Show;
using detail::Where;

Face PlusXAbutmentFace(const DeckGeometry& deck, double gap_m) {
  const double s = std::sin(deck.skew_rad);
  const double c = std::cos(deck.skew_rad);
  Face face;
  face.body = kGround;
  face.point_m = {0.5 * deck.length_m + gap_m, 0.0};
  face.normal = {-c, s};
  face.tangent = {s, c};
  return face;
}

Face MinusXAbutmentFace(const DeckGeometry& deck, double gap_m) {
  const double s = std::sin(deck.skew_rad);
  const double c = std::cos(deck.skew_rad);
  Face face;
  face.body = kGround;
  face.point_m = {-0.5 * deck.length_m - gap_m, 0.0};
  face.normal = {c, -s};
  face.tangent = {-s, -c};
  return face;
}

namespace detail {

namespace {

// The last matrices of at most kMaxSize x kMaxSize that passed CheckSymmetricPsd with the
// semi-definiteness check on this thread, by their bits: the verdict is a function of the bits
// alone (and a pass with the check implies one without), so a matrix with the same bits passes
// again without its factorisation. A sweep builds a model per cell, and its builder checks K
// before the model checks K and C again.
class PassedMatrices {
 public:
  static constexpr int kMaxSize = 6;
  bool Has(const Eigen::MatrixXd& A) const {
    const auto bytes = static_cast<std::size_t>(A.size()) * sizeof(double);
    for (const Slot& slot : slots_) {
      if (slot.n == A.rows() && std::memcmp(slot.a.data(), A.data(), bytes) == 0) return true;
    }
    return false;
  }
  void Add(const Eigen::MatrixXd& A) {
    if (A.rows() > kMaxSize || A.rows() != A.cols()) return;
    Slot& slot = slots_[next_];
    next_ = (next_ + 1) % kSlots;
    slot.n = static_cast<int>(A.rows());
    std::memcpy(slot.a.data(), A.data(), static_cast<std::size_t>(A.size()) * sizeof(double));
  }

 private:
  static constexpr int kSlots = 2;  // K and C of one model
  struct Slot {
    int n = -1;  // -1: empty
    std::array<double, kMaxSize * kMaxSize> a{};
  };
  std::array<Slot, kSlots> slots_{};
  int next_ = 0;
};

}  // namespace

void CheckSymmetricPsd(const Eigen::MatrixXd& A, int n, std::string_view field, const Where& where,
                       bool require_psd) {
  if (n == 3 && A.rows() == 3 && A.cols() == 3) {
    // A deck's diagonal matrix of finite entries >= 0 (a subsystem's K and its classical C)
    // passes every check below whatever its values: no asymmetry, and the shifted diagonal's
    // Cholesky factor exists or, where the shift underflows, the smallest eigenvalue is >= 0.
    bool diagonal = true;
    for (int j = 0; j < 3 && diagonal; ++j) {
      for (int i = 0; i < 3; ++i) {
        const double a = A(i, j);
        if (i == j ? !(std::isfinite(a) && a >= 0.0) : a != 0.0) {
          diagonal = false;
          break;
        }
      }
    }
    if (diagonal) return;
  }
  thread_local PassedMatrices passed;
  if (A.rows() == n && A.cols() == n && passed.Has(A)) {
    return;
  }
  if (A.rows() != n || A.cols() != n) {
    Fail(where, field,
         "must be " + std::to_string(n) + " x " + std::to_string(n) + " (got " +
             std::to_string(A.rows()) + " x " + std::to_string(A.cols()) + ")");
  }
  if (n == 3 && require_psd) {
    // A deck's matrices: the same checks in fixed-size arithmetic (the same maxima, and a
    // Cholesky verdict that could differ only within its rounding of a matrix at the bound).
    const Eigen::Matrix3d a = A;
    if (a.allFinite()) {
      const double scale3 = a.cwiseAbs().maxCoeff();
      if (!((a - a.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale3)) {
        Eigen::Matrix3d shifted3 = 0.5 * (a + a.transpose());
        shifted3.diagonal().array() += 1e-9 * scale3;
        if (scale3 == 0.0 || Eigen::LLT<Eigen::Matrix3d>(shifted3).info() == Eigen::Success) {
          passed.Add(A);
          return;
        }
      }
    }
    // A failure: the general checks below name it.
  }
  if (!A.allFinite()) {
    Fail(where, field, "must contain finite numbers only (got NaN or Inf)");
  }
  const double scale = A.cwiseAbs().maxCoeff();
  const double asymmetry = (A - A.transpose()).cwiseAbs().maxCoeff();
  if (asymmetry > 1e-9 * scale) {
    Fail(where, field,
         "must be symmetric (max |A - A^T| = " + Show(asymmetry) + ", allowed 1e-9 max|A|)");
  }
  if (require_psd && scale > 0.0) {
    // Asked: every eigenvalue >= -1e-9 max|A|. A Cholesky factor of A + 1e-9 max|A| I exists
    // exactly when that holds (up to the factorisation's rounding, ~1e-16 max|A|), at a small
    // part of an eigenvalue solve's cost: a sweep builds a model per cell. The solve stays for
    // a failure, whose message gives the smallest eigenvalue. The matrix and the factorisation
    // are this thread's, kept from call to call: at the same size they allocate nothing.
    thread_local Eigen::MatrixXd shifted;
    thread_local Eigen::LLT<Eigen::MatrixXd> llt;
    shifted = 0.5 * (A + A.transpose());
    shifted.diagonal().array() += 1e-9 * scale;
    if (llt.compute(shifted).info() == Eigen::Success) {
      passed.Add(A);
      return;
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (A + A.transpose()),
                                                             Eigen::EigenvaluesOnly);
    const double smallest = eig.eigenvalues().minCoeff();
    if (smallest < -1e-9 * scale) {
      Fail(where, field,
           "must be positive semi-definite (smallest eigenvalue " + Show(smallest) + ")");
    }
    passed.Add(A);
  }
}

}  // namespace detail

namespace {

std::string BodyField(int n_bodies, int i, std::string_view key) {
  std::string prefix = n_bodies == 1 ? "deck" : "deck[" + std::to_string(i) + "]";
  return prefix + "." + std::string(key);
}

}  // namespace

Model::Model(std::vector<Body> bodies, Eigen::MatrixXd K, Eigen::MatrixXd C, Eigen::MatrixXd r,
             std::vector<Contact> contacts, std::string source, std::optional<Modes> modes)
    : bodies_(std::move(bodies)),
      K_(std::move(K)),
      C_(std::move(C)),
      r_(std::move(r)),
      contacts_(std::move(contacts)),
      source_(std::move(source)),
      modes_(std::move(modes)) {
  const Where where{source_, 0};
  const int nb = n_bodies();
  if (nb == 0) {
    Fail(where, "deck", "at least one deck is required");
  }
  // The checks name their field only when they fail: a sweep builds a model per cell, and the
  // names are strings to build.
  const auto positive = [&](double value, int i, std::string_view key) {
    if (!(std::isfinite(value) && value > 0.0)) CheckPositive(value, BodyField(nb, i, key), where);
  };
  for (int i = 0; i < nb; ++i) {
    const Body& b = bodies_[static_cast<std::size_t>(i)];
    positive(b.mass_kg, i, "m");
    positive(b.inertia_kgm2, i, "I_m");
    positive(b.geometry.length_m, i, "L");
    positive(b.geometry.width_m, i, "W");
    const double skew_deg = b.geometry.skew_rad * 180.0 / std::numbers::pi;
    if (!(std::isfinite(skew_deg) && skew_deg >= 0.0 && skew_deg < 90.0)) {
      CheckRange(skew_deg, 0.0, 90.0, true, BodyField(nb, i, "skew_deg"), where, "deg");
    }
    if (!b.rest_position_m.allFinite()) {
      Fail(where, BodyField(nb, i, "rest_position"), "must be finite (got NaN or Inf)");
    }
  }
  const int n = n_dof();
  mass_diagonal_.resize(n);
  for (int i = 0; i < nb; ++i) {
    const Body& b = bodies_[static_cast<std::size_t>(i)];
    mass_diagonal_.segment<3>(3 * i) << b.mass_kg, b.mass_kg, b.inertia_kgm2;
  }
  inverse_mass_diagonal_ = mass_diagonal_.cwiseInverse();
  M_ = mass_diagonal_.asDiagonal();

  if (modes_) {
    SB_DEMAND(modes_->phi.rows() == n && modes_->phi.cols() == n &&
                  modes_->eigenvalues.size() == n && modes_->omega_radps.size() == n,
              "Model: the modes do not match the model's size");
  }
  CheckSymmetricPsd(K_, n, "substructure.K", where, true);
  CheckSymmetricPsd(C_, n, "substructure.C", where, true);
  if (r_.rows() != n || r_.cols() != 2 || !r_.allFinite()) {
    Fail(where, "r", "must be a finite " + std::to_string(n) + " x 2 ground-influence matrix");
  }
  // M r, element by element: the products AppliedForces used to form on every call.
  mass_r_.resize(n, 2);
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < n; ++i) {
      mass_r_(i, j) = mass_diagonal_[i] * r_(i, j);
    }
  }

  for (const Contact& c : contacts_) {
    const auto field = [&](std::string_view key) {
      return "abutments.contacts." + c.name + std::string(key);
    };
    if (c.body < 0 || c.body >= nb) {
      Fail(where, field(".body"), "must be a deck index in [0, " + std::to_string(nb) + ")");
    }
    if (c.face.body != kGround && (c.face.body < 0 || c.face.body >= nb || c.face.body == c.body)) {
      Fail(where, field(".face"), "must be on the ground or on another deck");
    }
    if (!c.point_m.allFinite() || !c.face.point_m.allFinite() || !c.face.normal.allFinite() ||
        !c.face.tangent.allFinite()) {
      Fail(where, field(""), "must have finite geometry (got NaN or Inf)");
    }
    if (std::abs(c.face.normal.norm() - 1.0) > 1e-12 ||
        std::abs(c.face.tangent.norm() - 1.0) > 1e-12 ||
        std::abs(c.face.normal.dot(c.face.tangent)) > 1e-12) {
      Fail(where, field(".face"), "n and t must be orthogonal unit vectors");
    }
    if (!(std::isfinite(c.restitution) && c.restitution >= 0.0 && c.restitution <= 1.0)) {
      CheckRange(c.restitution, 0.0, 1.0, false, field(".eps_N"), where);
    }
    if (!(std::isfinite(c.friction) && c.friction >= 0.0)) {
      CheckNonNegative(c.friction, field(".mu"), where);
    }
    // The gap at rest (q = 0): g = n . (X_i + p - A) for ground faces and
    // g = n . (X_i + p - X_j - A) for a face on body j, whose frame is not turned at rest.
    const Body& carrier = bodies_[static_cast<std::size_t>(c.body)];
    Eigen::Vector2d face_point = c.face.point_m;
    if (c.face.body != kGround) {
      face_point += bodies_[static_cast<std::size_t>(c.face.body)].rest_position_m;
    }
    const double gap = c.face.normal.dot(carrier.rest_position_m + c.point_m - face_point);
    if (gap < -1e-12 * carrier.geometry.length_m) {
      Fail(where, c.face.body == kGround ? "abutments.gap_m" : "joint.gap_m",
           "must be >= 0: contact " + c.name + " has gap " + Show(gap) + " m at rest");
    }
  }
}

int Model::FindContact(const std::string& name) const {
  for (int c = 0; c < n_contacts(); ++c) {
    if (contacts_[static_cast<std::size_t>(c)].name == name) {
      return c;
    }
  }
  return -1;
}

void Model::AppliedForces(const Eigen::Ref<const Eigen::VectorXd>& q,
                          const Eigen::Ref<const Eigen::VectorXd>& u,
                          const Eigen::Vector2d& a_g_mps2, Eigen::Ref<Eigen::VectorXd> h) const {
  const Eigen::Index n = h.size();
  const double a_x = a_g_mps2(0), a_y = a_g_mps2(1);
  if (n == 3) {
    // A single deck, the loops below unrolled (their operations in their order).
    const double* C = C_.data();
    const double* K = K_.data();
    const double* mr = mass_r_.data();
    const double u0 = u(0), u1 = u(1), u2 = u(2), q0 = q(0), q1 = q(1), q2 = q(2);
    for (int i = 0; i < 3; ++i) {
      double sum = 0.0;
      sum += C[i] * u0 + K[i] * q0;
      sum += C[i + 3] * u1 + K[i + 3] * q1;
      sum += C[i + 6] * u2 + K[i + 6] * q2;
      double v = -sum;
      v -= a_x * mr[i];
      v -= a_y * mr[i + 3];
      h(i) = v;
    }
    return;
  }
  if (n <= 6) {
    // Two decks: plain loops, without the dispatch of a dynamic-size product (this runs in
    // every Runge-Kutta stage of a constrained phase). Per entry the operations of the general
    // path in its order: -(C u + K q), minus a_x (M r)_x, minus a_y (M r)_y.
    for (Eigen::Index i = 0; i < n; ++i) {
      double sum = 0.0;
      for (Eigen::Index j = 0; j < n; ++j) {
        sum += C_(i, j) * u(j) + K_(i, j) * q(j);
      }
      double v = -sum;
      v -= a_x * mass_r_(i, 0);
      v -= a_y * mass_r_(i, 1);
      h(i) = v;
    }
    return;
  }
  h.noalias() = -C_ * u;
  h.noalias() -= K_ * q;
  // M r a_g column by column (M r formed once): no temporary.
  h.noalias() -= a_x * mass_r_.col(0);
  h.noalias() -= a_y * mass_r_.col(1);
}

double Model::MechanicalEnergy(const Eigen::Ref<const Eigen::VectorXd>& q,
                               const Eigen::Ref<const Eigen::VectorXd>& u) const {
  const double kinetic = 0.5 * u.dot(mass_diagonal_.asDiagonal() * u);
  double strain = 0.0;
  for (int i = 0; i < K_.cols(); ++i) {
    strain += 0.5 * q(i) * K_.col(i).dot(q);
  }
  return kinetic + strain;
}

}  // namespace skewbridge::model
