#include "solver/contact/kinematics.h"

#include <bit>
#include <cmath>
#include <cstdint>

#include "solver/common/error.h"

namespace skewbridge::contact {

namespace {

// J v: v rotated by +90 deg, so that R'(theta) = J R(theta) and d(R v)/dt = thetadot J R v.
Eigen::Vector2d Perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

// The world-frame quantities of one contact at q: P, the arm R_i p, n, t, and the face body's
// mass centre (zero for the ground). World = ground frame; a body's mass centre is at
// X + (x, y) with X its rest position.
struct Geometry {
  Eigen::Vector2d P;       // world position of the point (m)
  Eigen::Vector2d arm;     // R(theta_i) p (m)
  Eigen::Vector2d n;       // face normal, world
  Eigen::Vector2d t;       // face tangent, world
  Eigen::Vector2d A;       // face point, world (m)
  Eigen::Vector2d origin;  // face body's mass centre, world (m); zero for the ground
};

Geometry Compute(const model::Model& model, int c, const Eigen::Ref<const Eigen::VectorXd>& q) {
  const model::Contact& contact = model.contact(c);
  const int i = 3 * contact.body;
  Geometry g;
  g.arm = Rotation(q(i + 2)) * contact.point_m;
  // X_i + (x_i, y_i): exact for a single deck, whose X is zero.
  g.P = (model.body(contact.body).rest_position_m + q.segment<2>(i)) + g.arm;
  if (contact.face.body == model::kGround) {
    g.n = contact.face.normal;
    g.t = contact.face.tangent;
    g.A = contact.face.point_m;
    g.origin.setZero();
  } else {
    const int j = 3 * contact.face.body;
    const Eigen::Matrix2d R_j = Rotation(q(j + 2));
    g.n = R_j * contact.face.normal;
    g.t = R_j * contact.face.tangent;
    g.origin = model.body(contact.face.body).rest_position_m + q.segment<2>(j);
    g.A = g.origin + R_j * contact.face.point_m;
  }
  return g;
}

}  // namespace

void ContactKinematics::Resize(const model::Model& model) {
  const int n = model.n_dof();
  const int k = model.n_contacts();
  gap_m.setZero(k);
  W_N.setZero(n, k);
  W_T.setZero(n, k);
  gamma_N.setZero(k);
  gamma_T.setZero(k);
  what_N.setZero(k);
  what_T.setZero(k);
}

Eigen::Matrix2d Rotation(double theta_rad) {
  // The contacts of a body share its angle, and an evaluation of all contacts asks for the same
  // sine and cosine once per contact: the last angle's are kept (per thread), compared by their
  // bits (so -0 and +0 stay apart), which gives the same values as computing them again.
  thread_local std::uint64_t last_bits = 0;  // the bits of +0.0
  thread_local double last_c = 1.0, last_s = 0.0;
  const auto bits = std::bit_cast<std::uint64_t>(theta_rad);
  if (bits != last_bits) {
    last_c = std::cos(theta_rad);
    last_s = std::sin(theta_rad);
    last_bits = bits;
  }
  const double c = last_c;
  const double s = last_s;
  Eigen::Matrix2d R;
  R << c, -s, s, c;
  return R;
}

double BodyFaceGap(const model::Model& model, int c, const Eigen::Ref<const Eigen::VectorXd>& q) {
  const Geometry g = Compute(model, c, q);
  return g.n.dot(g.P - g.A);
}

void GapRateScratch::Resize(const model::Model& model) {
  deck_corners = 0;
  bool deck =
      model.n_bodies() == 1 && model.n_contacts() > 0 && model.n_contacts() <= kMaxDeckCorners;
  for (int c = 0; deck && c < model.n_contacts(); ++c) {
    deck = model.contact(c).face.body == model::kGround;
  }
  if (deck) {
    const Eigen::Vector2d& X = model.body(0).rest_position_m;
    for (int c = 0; c < model.n_contacts(); ++c) {
      const model::Contact& contact = model.contact(c);
      corners.X_x[c] = X.x();
      corners.X_y[c] = X.y();
      corners.p_x[c] = contact.point_m.x();
      corners.p_y[c] = contact.point_m.y();
      corners.n_x[c] = contact.face.normal.x();
      corners.n_y[c] = contact.face.normal.y();
      corners.A_x[c] = contact.face.point_m.x();
      corners.A_y[c] = contact.face.point_m.y();
    }
    deck_corners = model.n_contacts();
    return;
  }
  cos.assign(static_cast<std::size_t>(model.n_bodies()), 1.0);
  sin.assign(static_cast<std::size_t>(model.n_bodies()), 0.0);
  w_N.setZero(model.n_dof());
  w_T.setZero(model.n_dof());
}

void GeneralGapsAndRates(const model::Model& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                         const Eigen::Ref<const Eigen::VectorXd>& u, Eigen::VectorXd& gap,
                         Eigen::VectorXd& gamma_N, GapRateScratch& scratch) {
  const int nb = model.n_bodies();
  for (int b = 0; b < nb; ++b) {
    scratch.cos[static_cast<std::size_t>(b)] = std::cos(q[3 * b + 2]);
    scratch.sin[static_cast<std::size_t>(b)] = std::sin(q[3 * b + 2]);
  }
  for (int c = 0; c < model.n_contacts(); ++c) {
    const model::Contact& contact = model.contact(c);
    if (contact.face.body != model::kGround) {
      gap[c] = BodyFaceGap(model, c, q);
      Jacobians(model, c, q, scratch.w_N, scratch.w_T);
      gamma_N[c] = scratch.w_N.dot(u);
      continue;
    }
    const auto b = static_cast<std::size_t>(contact.body);
    const Eigen::Vector2d arm = RotatedArm(scratch.cos[b], scratch.sin[b], contact.point_m);
    gap[c] = GroundFaceGap(model, contact, q, arm);
    gamma_N[c] = GroundFaceNormalRate(contact, u, arm);
  }
}

Eigen::Vector2d PointPosition(const model::Model& model, int c,
                              const Eigen::Ref<const Eigen::VectorXd>& q) {
  return Compute(model, c, q).P;
}

void FaceDirections(const model::Model& model, int c, const Eigen::Ref<const Eigen::VectorXd>& q,
                    Eigen::Vector2d& n, Eigen::Vector2d& t) {
  const Geometry g = Compute(model, c, q);
  n = g.n;
  t = g.t;
}

namespace {

// Writes the rows of the two bodies only; the caller zeroes the others (once per column: the
// rows a contact touches never change, which keeps Evaluate O(n_contacts), not O(n_dof n_c)).
void JacobiansAt(const model::Contact& contact, const Geometry& g, Eigen::Ref<Eigen::VectorXd> w_N,
                 Eigen::Ref<Eigen::VectorXd> w_T) {
  const int i = 3 * contact.body;
  // Velocity of P: v_i + thetadot_i J R_i p [docs/theory.md §2: R'(theta) p = J R(theta) p].
  const Eigen::Vector2d lever_i = Perp(g.arm);
  w_N.segment<2>(i) = g.n;
  w_N(i + 2) = g.n.dot(lever_i);
  w_T.segment<2>(i) = g.t;
  w_T(i + 2) = g.t.dot(lever_i);
  if (contact.face.body != model::kGround) {
    // The face's material point at P moves with v_j + thetadot_j J (P - x_j).
    const int j = 3 * contact.face.body;
    const Eigen::Vector2d lever_j = Perp(g.P - g.origin);
    w_N.segment<2>(j) = -g.n;
    w_N(j + 2) = -g.n.dot(lever_j);
    w_T.segment<2>(j) = -g.t;
    w_T(j + 2) = -g.t.dot(lever_j);
  }
}

}  // namespace

void Jacobians(const model::Model& model, int c, const Eigen::Ref<const Eigen::VectorXd>& q,
               Eigen::Ref<Eigen::VectorXd> w_N, Eigen::Ref<Eigen::VectorXd> w_T) {
  w_N.setZero();
  w_T.setZero();
  JacobiansAt(model.contact(c), Compute(model, c, q), w_N, w_T);
}

namespace {

void VelocityTermsAt(const model::Contact& contact, const Geometry& g,
                     const Eigen::Ref<const Eigen::VectorXd>& u, double& what_N, double& what_T) {
  const int i = 3 * contact.body;
  const double thetadot_i = u(i + 2);
  // d/dt (thetadot_i J R_i p) = thetadot_ddot J R_i p - thetadot_i^2 R_i p: the second term.
  const Eigen::Vector2d centripetal = -thetadot_i * thetadot_i * g.arm;
  if (contact.face.body == model::kGround) {
    what_N = g.n.dot(centripetal);
    what_T = g.t.dot(centripetal);
    return;
  }
  // Body face: gamma = n_w . (v_P - v_Q) with n_w, t_w turning at thetadot_j and
  // v_Q = v_j + thetadot_j J (P - x_j), whose arm changes at v_P - v_j.
  const int j = 3 * contact.face.body;
  const double thetadot_j = u(j + 2);
  const Eigen::Vector2d v_P = u.segment<2>(i) + thetadot_i * Perp(g.arm);
  const Eigen::Vector2d v_Q = u.segment<2>(j) + thetadot_j * Perp(g.P - g.origin);
  const Eigen::Vector2d relative = v_P - v_Q;
  const Eigen::Vector2d face_turn = -thetadot_j * Perp(v_P - u.segment<2>(j));
  what_N = thetadot_j * Perp(g.n).dot(relative) + g.n.dot(centripetal + face_turn);
  what_T = thetadot_j * Perp(g.t).dot(relative) + g.t.dot(centripetal + face_turn);
}

}  // namespace

void VelocityTerms(const model::Model& model, int c, const Eigen::Ref<const Eigen::VectorXd>& q,
                   const Eigen::Ref<const Eigen::VectorXd>& u, double& what_N, double& what_T) {
  VelocityTermsAt(model.contact(c), Compute(model, c, q), u, what_N, what_T);
}

namespace {

// w^T u over the rows of the contact's bodies: the full dot product without its terms that are
// exact zeros (a single deck's columns have no other rows: the same sum, bit for bit).
double SparseDot(const model::Contact& contact, const Eigen::Ref<const Eigen::VectorXd>& w,
                 const Eigen::Ref<const Eigen::VectorXd>& u) {
  if (w.size() == 3) {
    return w.dot(u);
  }
  const int i = 3 * contact.body;
  double sum = w.segment<3>(i).dot(u.segment<3>(i));
  if (contact.face.body != model::kGround) {
    const int j = 3 * contact.face.body;
    sum += w.segment<3>(j).dot(u.segment<3>(j));
  }
  return sum;
}

}  // namespace

double ColumnDot(const model::Model& model, int c, const Eigen::Ref<const Eigen::VectorXd>& w,
                 const Eigen::Ref<const Eigen::VectorXd>& u) {
  return SparseDot(model.contact(c), w, u);
}

namespace {

void EvaluateOne(const model::Model& model, int c, const Eigen::Ref<const Eigen::VectorXd>& q,
                 const Eigen::Ref<const Eigen::VectorXd>& u, ContactKinematics& out) {
  // One evaluation of the geometry (and its sines and cosines) per contact.
  const model::Contact& contact = model.contact(c);
  const Geometry g = Compute(model, c, q);
  out.gap_m(c) = g.n.dot(g.P - g.A);
  JacobiansAt(contact, g, out.W_N.col(c), out.W_T.col(c));
  if (u.size() == 3) {
    // A single deck: the three-entry dot products written out, in the order of Eigen's (the
    // first two entries paired, then the third), without a dynamic-size expression per call.
    const double* w_N = out.W_N.col(c).data();
    const double* w_T = out.W_T.col(c).data();
    out.gamma_N(c) = (w_N[0] * u[0] + w_N[1] * u[1]) + w_N[2] * u[2];
    out.gamma_T(c) = (w_T[0] * u[0] + w_T[1] * u[1]) + w_T[2] * u[2];
  } else {
    out.gamma_N(c) = SparseDot(contact, out.W_N.col(c), u);
    out.gamma_T(c) = SparseDot(contact, out.W_T.col(c), u);
  }
  VelocityTermsAt(contact, g, u, out.what_N(c), out.what_T(c));
}

}  // namespace

namespace {

// EvaluateOne of a single deck's contact against a ground face, given the deck's cos(theta) and
// sin(theta): Compute's, JacobiansAt's and VelocityTermsAt's operations in their order on
// scalars (R p = (c p_x - s p_y, s p_x + c p_y) as RotatedArm; the same bits). Inlined into the
// loops over the contacts, which share the body's and the output's addresses across corners.
[[gnu::always_inline]] inline void EvaluateDeckCorner(const model::Model& model, int c,
                                                      double cos_theta, double sin_theta,
                                                      const double* q, const double* u,
                                                      ContactKinematics& out) {
  const model::Contact& contact = model.contact(c);
  const Eigen::Vector2d& X = model.body(0).rest_position_m;
  const Eigen::Vector2d& p = contact.point_m;
  const Eigen::Vector2d& n = contact.face.normal;
  const Eigen::Vector2d& t = contact.face.tangent;
  const Eigen::Vector2d& A = contact.face.point_m;
  const double arm_x = cos_theta * p.x() - sin_theta * p.y();
  const double arm_y = sin_theta * p.x() + cos_theta * p.y();
  const double P_x = (X.x() + q[0]) + arm_x;
  const double P_y = (X.y() + q[1]) + arm_y;
  out.gap_m(c) = n.x() * (P_x - A.x()) + n.y() * (P_y - A.y());
  // w = (n, n . J arm), J arm = (-arm_y, arm_x).
  double* w_N = out.W_N.col(c).data();
  double* w_T = out.W_T.col(c).data();
  w_N[0] = n.x();
  w_N[1] = n.y();
  w_N[2] = n.x() * -arm_y + n.y() * arm_x;
  w_T[0] = t.x();
  w_T[1] = t.y();
  w_T[2] = t.x() * -arm_y + t.y() * arm_x;
  out.gamma_N(c) = (w_N[0] * u[0] + w_N[1] * u[1]) + w_N[2] * u[2];
  out.gamma_T(c) = (w_T[0] * u[0] + w_T[1] * u[1]) + w_T[2] * u[2];
  // The centripetal term -thetadot^2 R p.
  const double square = -u[2] * u[2];
  const double centripetal_x = square * arm_x;
  const double centripetal_y = square * arm_y;
  out.what_N(c) = n.x() * centripetal_x + n.y() * centripetal_y;
  out.what_T(c) = t.x() * centripetal_x + t.y() * centripetal_y;
}

}  // namespace

void Evaluate(const model::Model& model, const Eigen::Ref<const Eigen::VectorXd>& q,
              const Eigen::Ref<const Eigen::VectorXd>& u, ContactKinematics& out) {
  SB_ASSERT(out.W_N.rows() == model.n_dof() && out.W_N.cols() == model.n_contacts(),
            "ContactKinematics not sized for this model");
  if (model.n_bodies() == 1) {
    // A single deck: one rotation for its contacts, a ground face's on scalars.
    const Eigen::Matrix2d R = Rotation(q(2));
    for (int c = 0; c < model.n_contacts(); ++c) {
      if (model.contact(c).face.body == model::kGround) {
        EvaluateDeckCorner(model, c, R(0, 0), R(1, 0), q.data(), u.data(), out);
      } else {
        EvaluateOne(model, c, q, u, out);
      }
    }
    return;
  }
  for (int c = 0; c < model.n_contacts(); ++c) {
    EvaluateOne(model, c, q, u, out);
  }
}

void EvaluateContacts(const model::Model& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                      const Eigen::Ref<const Eigen::VectorXd>& u, std::span<const int> contacts,
                      ContactKinematics& out) {
  SB_ASSERT(out.W_N.rows() == model.n_dof() && out.W_N.cols() == model.n_contacts(),
            "ContactKinematics not sized for this model");
  if (model.n_bodies() == 1 && !contacts.empty()) {
    // A single deck: Evaluate's path for the listed contacts (one rotation, a ground face's on
    // scalars), the same bits as EvaluateOne.
    const Eigen::Matrix2d R = Rotation(q(2));
    for (int c : contacts) {
      SB_ASSERT(c >= 0 && c < model.n_contacts(), "contact index out of range");
      if (model.contact(c).face.body == model::kGround) {
        EvaluateDeckCorner(model, c, R(0, 0), R(1, 0), q.data(), u.data(), out);
      } else {
        EvaluateOne(model, c, q, u, out);
      }
    }
    return;
  }
  for (int c : contacts) {
    SB_ASSERT(c >= 0 && c < model.n_contacts(), "contact index out of range");
    EvaluateOne(model, c, q, u, out);
  }
}

}  // namespace skewbridge::contact
