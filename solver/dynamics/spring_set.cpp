// The laws of a run's compliant springs (spring_set.h): the kinematics of a spring along and
// across its face, the force of each piece of its law, the event functions that say where it
// leaves the piece and the transitions there, and the friction element of a spring with wall
// friction [docs/compliant.md §4].
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "solver/common/error.h"
#include "solver/dynamics/spring_set.h"
#include "solver/joint/backfill.h"
#include "solver/joint/shear_key.h"

namespace skewbridge::dynamics {

namespace {

// Spring j of `set` seen by its friction element at (q, u): the deformation d (m) and its rate
// (m/s), the coordinate s along the wall (m) and its rate (m/s), the tangent's gradient w_t on
// the body's 3 DOFs, and the normal force N of the spring's current branch (N).
struct AlongTheWall {
  double d_m, d_rate_mps, s_m, s_rate_mps, normal_N;
  Eigen::Vector3d w_t;
};

AlongTheWall WallMotion(const SpringSet& set, int j, const Eigen::Ref<const SpringSet::Vec>& q,
                        const Eigen::Ref<const SpringSet::Vec>& u) {
  AlongTheWall m;
  set.Kinematics(j, q, u, m.d_m, m.d_rate_mps, m.w_t);
  set.Tangential(j, q, u, m.s_m, m.s_rate_mps, m.w_t);
  m.normal_N = set.BranchForce(j, m.d_m, m.d_rate_mps);
  return m;
}

}  // namespace

SpringSet::SpringSet(const model::Model& model, const std::vector<CompliantSpring>& springs)
    : model_(model),
      springs_(springs),
      n_(model.n_dof()),
      ns_(static_cast<int>(springs.size())),
      turn_(static_cast<std::size_t>(model.n_bodies())),
      state_(springs.size()) {
  for (const CompliantSpring& s : springs) {
    const std::string where = model.source() + ": spring " + s.name;
    const bool face_ok =
        s.face.body == model::kGround ||
        (s.face.body >= 0 && s.face.body < model.n_bodies() && s.face.body != s.body);
    if (s.body < 0 || s.body >= model.n_bodies() || !face_ok || !s.point_m.allFinite() ||
        !s.face.point_m.allFinite() || !(std::abs(s.face.normal.norm() - 1.0) <= 1e-12)) {
      throw InputError::AtField(where, "geometry",
                                "needs a body index, finite points and a unit normal of a face on "
                                "the ground or on another body");
    }
    if (s.law == SpringLaw::kShearKey && s.face.body != model::kGround) {
      throw InputError::AtField(where, "law", "a shear key stands on the ground (an abutment)");
    }
    if (s.law == SpringLaw::kBackfill) {
      joint::ValidateHyperbolicGap(s.backfill, where);
    } else if (s.law == SpringLaw::kShearKey) {
      joint::ValidateShearKey(s.key, where);
    } else if (!(s.k_N_per_m > 0.0 && std::isfinite(s.k_N_per_m) && s.c_Ns_per_m >= 0.0 &&
                 std::isfinite(s.c_Ns_per_m))) {
      throw InputError::AtField(where, "k, c", "must be k > 0, c >= 0, finite");
    }
    if (!(s.mu >= 0.0 && std::isfinite(s.mu))) {
      throw InputError::AtField(where, "mu", "wall friction must be a finite number >= 0");
    }
    if (!(s.k_t_N_per_m >= 0.0 && std::isfinite(s.k_t_N_per_m))) {
      throw InputError::AtField(where, "k_t", "stick stiffness must be finite, >= 0 (0: K_max)");
    }
    if (s.mu > 0.0 && (s.law != SpringLaw::kBackfill || s.face.body != model::kGround)) {
      throw InputError::AtField(where, "mu",
                                "wall friction acts on the backfill springs of abutments only");
    }
    if (s.mu > 0.0 && !(std::abs(s.face.tangent.norm() - 1.0) <= 1e-12 &&
                        std::abs(s.face.tangent.dot(s.face.normal)) <= 1e-12)) {
      throw InputError::AtField(where, "geometry",
                                "wall friction needs the face's unit tangent, normal to n");
    }
    if (s.mu > 0.0) {
      FrictionState f;
      f.spring = static_cast<int>(&s - springs.data());
      f.mu = s.mu;
      f.k_t_N_per_m = s.k_t_N_per_m > 0.0 ? s.k_t_N_per_m : s.backfill.k_max_N_per_m;
      friction_.push_back(f);
    }
  }
  max_force_N_ = Vec::Zero(ns_);
  max_deformation_m_ = Vec::Zero(ns_);
  key_break_time_s_ = Vec::Constant(ns_, std::numeric_limits<double>::quiet_NaN());
  wall_slip_m_ = Vec::Zero(ns_);
  first_slip_time_s_ = Vec::Constant(ns_, std::numeric_limits<double>::quiet_NaN());
}

std::pair<double, double> SpringSet::Turn(int b, double theta_rad) const {
  TurnMemo& m = turn_[static_cast<std::size_t>(b)];
  const auto bits = std::bit_cast<std::uint64_t>(theta_rad);
  int k = 0;
  if (bits == m.theta_bits[0]) {
    k = 0;
  } else if (bits == m.theta_bits[1]) {
    k = 1;
  } else {
    k = m.next;
    m.next = 1 - k;
    m.theta_bits[k] = bits;
    m.c[k] = std::cos(theta_rad);
    m.s[k] = std::sin(theta_rad);
  }
  return {m.c[k], m.s[k]};
}

void SpringSet::Along(int j, const Eigen::Vector2d& dir, const Eigen::Ref<const Vec>& q,
                      const Eigen::Ref<const Vec>& u, double& coord, double& rate,
                      Eigen::Vector3d& w, Eigen::Vector3d* w_face) const {
  const CompliantSpring& sp = springs_[static_cast<std::size_t>(j)];
  const int b = 3 * sp.body;
  const auto [c, sn] = Turn(sp.body, q[b + 2]);
  const Eigen::Vector2d rp(c * sp.point_m.x() - sn * sp.point_m.y(),
                           sn * sp.point_m.x() + c * sp.point_m.y());
  const Eigen::Vector2d& rest = model_.body(sp.body).rest_position_m;
  if (sp.face.body == model::kGround) {
    coord = dir.dot(rest + Eigen::Vector2d(q[b], q[b + 1]) + rp - sp.face.point_m);
    w << dir.x(), dir.y(), dir.x() * -rp.y() + dir.y() * rp.x();
    rate = w[0] * u[b] + w[1] * u[b + 1] + w[2] * u[b + 2];
    if (w_face != nullptr) w_face->setZero();
    return;
  }
  // A face on body f: its direction and point turn with f, A = X_f + (x_f, y_f) + R_f a; the
  // coordinate dir_w . (P - A) has the gradient (dir_w, dir_w . J R p) on the point's body and
  // (-dir_w, -dir_w . J (P - X_f - (x_f, y_f))) on the face's (contact/kinematics.h).
  const int f = 3 * sp.face.body;
  const auto [cf, sf] = Turn(sp.face.body, q[f + 2]);
  const Eigen::Vector2d dir_w(cf * dir.x() - sf * dir.y(), sf * dir.x() + cf * dir.y());
  const Eigen::Vector2d origin =
      model_.body(sp.face.body).rest_position_m + Eigen::Vector2d(q[f], q[f + 1]);
  const Eigen::Vector2d a(cf * sp.face.point_m.x() - sf * sp.face.point_m.y(),
                          sf * sp.face.point_m.x() + cf * sp.face.point_m.y());
  const Eigen::Vector2d point = rest + Eigen::Vector2d(q[b], q[b + 1]) + rp;
  const Eigen::Vector2d arm = point - origin;
  coord = dir_w.dot(point - origin - a);
  w << dir_w.x(), dir_w.y(), dir_w.x() * -rp.y() + dir_w.y() * rp.x();
  Eigen::Vector3d on_face(-dir_w.x(), -dir_w.y(), -(dir_w.x() * -arm.y() + dir_w.y() * arm.x()));
  rate = w[0] * u[b] + w[1] * u[b + 1] + w[2] * u[b + 2] + on_face[0] * u[f] +
         on_face[1] * u[f + 1] + on_face[2] * u[f + 2];
  if (w_face != nullptr) *w_face = on_face;
}

void SpringSet::Kinematics(int j, const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u,
                           double& d, double& rate, Eigen::Vector3d& w,
                           Eigen::Vector3d* w_face) const {
  double gap, gap_rate;
  Along(j, springs_[static_cast<std::size_t>(j)].face.normal, q, u, gap, gap_rate, w, w_face);
  d = -gap;
  rate = -gap_rate;
}

void SpringSet::Tangential(int j, const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u,
                           double& s, double& rate, Eigen::Vector3d& w_t) const {
  Along(j, springs_[static_cast<std::size_t>(j)].face.tangent, q, u, s, rate, w_t);
}

double SpringSet::BranchSlope(int j, double d) const {
  const CompliantSpring& s = springs_[static_cast<std::size_t>(j)];
  switch (state_[static_cast<std::size_t>(j)].branch) {
    case Branch::kLine:
      return LineStiffness(j);
    case Branch::kEnvelope: {
      // F = d / (a + b d): dF/dd = a / (a + b d)^2.
      const double a = 1.0 / s.backfill.k_max_N_per_m;
      const double den = a + s.backfill.r_f * d / s.backfill.f_ult_N;
      return a / (den * den);
    }
    default:
      return 0.0;
  }
}

double SpringSet::FrictionForce(const FrictionState& f, double s, double normal_N) const {
  switch (f.mode) {
    case Friction::kStick:
      return -f.k_t_N_per_m * (s - f.anchor_m);
    case Friction::kSlip:
      return -f.sigma * f.mu * normal_N;
    case Friction::kFree:
      break;
  }
  return 0.0;
}

void SpringSet::FrictionEventValues(int f, const Eigen::Ref<const Vec>& y, double& e1,
                                    double& e2) const {
  const FrictionState& fr = friction_[static_cast<std::size_t>(f)];
  e1 = e2 = kInf;
  if (fr.mode == Friction::kFree) return;
  const int j = fr.spring;
  const AlongTheWall m = WallMotion(*this, j, y.head(n_), y.segment(n_, n_));
  const double d = m.d_m, d_rate = m.d_rate_mps, s = m.s_m, s_rate = m.s_rate_mps;
  const double normal = m.normal_N;
  if (fr.mode == Friction::kStick) {
    const double f_t = FrictionForce(fr, s, normal);
    e1 = fr.mu * normal - f_t;  // the stick force reaches the cone along +t
    e2 = fr.mu * normal + f_t;  // along -t
  } else {
    // The anchor follows s - sigma mu N / k_t: its rate along sigma, the plastic slip rate.
    e1 = fr.sigma * s_rate - fr.mu * BranchSlope(j, d) * d_rate / fr.k_t_N_per_m;
  }
}

void SpringSet::SettleFriction(int f, const Eigen::Ref<const Vec>& y, double t_s) {
  FrictionState& fr = friction_[static_cast<std::size_t>(f)];
  const int j = fr.spring;
  const AlongTheWall m = WallMotion(*this, j, y.head(n_), y.segment(n_, n_));
  const double d = m.d_m, d_rate = m.d_rate_mps, s = m.s_m, s_rate = m.s_rate_mps;
  const double normal = m.normal_N;
  const auto end_slip = [&]() {
    // The slip ends: the anchor where the slipping element has it.
    const double anchor = s - fr.sigma * fr.mu * normal / fr.k_t_N_per_m;
    wall_slip_m_[j] += std::abs(anchor - fr.slip_begin_m);
    return anchor;
  };
  if (state_[static_cast<std::size_t>(j)].branch == Branch::kOpen) {
    if (fr.mode == Friction::kSlip) end_slip();
    fr.mode = Friction::kFree;
    return;
  }
  if (fr.mode == Friction::kFree) {
    fr.mode = Friction::kStick;  // a closing spring grips the wall where it touches it
    fr.anchor_m = s;
  }
  const auto rate_along = [&](double sigma) {
    return sigma * s_rate - fr.mu * BranchSlope(j, d) * d_rate / fr.k_t_N_per_m;
  };
  for (int k = 0; k < kSettleLimit; ++k) {
    if (fr.mode == Friction::kStick) {
      const double f_t = FrictionForce(fr, s, normal);
      if (fr.mu * normal - std::abs(f_t) > 0.0) return;
      // On the cone: it slips the way the stick spring is stretched if the motion goes on
      // outwards (F_t = +mu N holds a point moving along -t).
      const double sigma = f_t > 0.0 ? -1.0 : 1.0;
      if (!(rate_along(sigma) > 0.0)) return;
      fr.mode = Friction::kSlip;
      fr.sigma = sigma;
      fr.slip_begin_m = fr.anchor_m;
      if (std::isnan(first_slip_time_s_[j])) first_slip_time_s_[j] = t_s;
    } else {
      if (rate_along(fr.sigma) > 0.0) return;
      fr.anchor_m = end_slip();
      fr.mode = Friction::kStick;
    }
  }
}

double SpringSet::BranchForce(int j, double d, double rate) const {
  const CompliantSpring& s = springs_[static_cast<std::size_t>(j)];
  const SpringState& m = state_[static_cast<std::size_t>(j)];
  switch (m.branch) {
    case Branch::kOpen:
      return 0.0;
    case Branch::kLine:
      return m.f_peak_N - LineStiffness(j) * (m.d_max_m - d);
    case Branch::kEnvelope:
      return d / (1.0 / s.backfill.k_max_N_per_m + s.backfill.r_f * d / s.backfill.f_ult_N);
    case Branch::kDashpot:
      return s.k_N_per_m * d + s.c_Ns_per_m * rate;
    case Branch::kKeyRise:
      return s.key.v_n_N * d / s.key.d3_m;
    case Branch::kKeySoften:
      return s.key.v_n_N +
             (s.key.v_res_N - s.key.v_n_N) * (d - s.key.d3_m) / (s.key.d_res_m - s.key.d3_m);
    case Branch::kKeyResidual:
      return s.key.v_res_N * (s.key.dd_m - d) / (s.key.dd_m - s.key.d_res_m);
  }
  return 0.0;
}

double SpringSet::LineStiffness(int j) const {
  const CompliantSpring& s = springs_[static_cast<std::size_t>(j)];
  return s.law == SpringLaw::kShearKey ? s.key.v_n_N / s.key.d3_m : s.backfill.k_ur_N_per_m;
}

SpringSet::Branch SpringSet::KeyPieceAbove(int j, double d) const {
  const joint::ShearKey& key = springs_[static_cast<std::size_t>(j)].key;
  if (d < key.d3_m) return Branch::kKeyRise;
  if (d < key.d_res_m) return Branch::kKeySoften;
  if (d < key.dd_m) return Branch::kKeyResidual;
  return Branch::kOpen;
}

void SpringSet::CommitTurn(int j, double d) {
  const CompliantSpring& s = springs_[static_cast<std::size_t>(j)];
  SpringState& m = state_[static_cast<std::size_t>(j)];
  if (s.law == SpringLaw::kShearKey) {
    m.d_max_m = joint::ShearKeyCommit(s.key, joint::ShearKeyState{m.d_max_m}, d).d_max_m;
    m.f_peak_N = joint::ShearKeyBackbone_N(s.key, m.d_max_m);
    m.d_set_m = std::max(0.0, m.d_max_m - m.f_peak_N / LineStiffness(j));
  } else {
    const joint::BackfillState memory =
        joint::BackfillCommit(s.backfill, joint::BackfillState{m.d_max_m}, d);
    m.d_max_m = memory.d_max_m;
    m.f_peak_N = joint::EnvelopeForce_N(s.backfill, m.d_max_m);
    m.d_set_m = joint::PermanentSet_m(s.backfill, memory);
  }
  m.branch = Branch::kLine;
}

void SpringSet::EventValues(int j, double d, double rate, double& e1, double& e2) const {
  const CompliantSpring& s = springs_[static_cast<std::size_t>(j)];
  const SpringState& m = state_[static_cast<std::size_t>(j)];
  e1 = e2 = kInf;
  switch (m.branch) {
    case Branch::kOpen:
      if (m.broken) return;  // a broken key never closes again
      if (s.law != SpringLaw::kSpringDashpot) {
        e1 = m.d_set_m - d;  // closes at the permanent set
      } else {
        // A spring-dashpot left with d > 0 re-engages when k d + c d' turns positive.
        e1 = -std::min(s.k_N_per_m * d, s.k_N_per_m * d + s.c_Ns_per_m * rate);
      }
      return;
    case Branch::kLine:
      e1 = m.d_max_m - d;  // reaches the envelope
      e2 = d - m.d_set_m;  // opens at the permanent set
      return;
    case Branch::kEnvelope:
      e1 = rate;  // turns from loading to unloading
      return;
    case Branch::kDashpot:
      e1 = s.k_N_per_m * d + s.c_Ns_per_m * rate;  // its force reaches zero
      return;
    case Branch::kKeyRise:
      e1 = s.key.d3_m - d;  // reaches the capacity V_n
      e2 = rate;            // turns from loading to unloading
      return;
    case Branch::kKeySoften:
      e1 = s.key.d_res_m - d;  // reaches the residual
      e2 = rate;
      return;
    case Branch::kKeyResidual:
      e1 = s.key.dd_m - d;  // breaks
      e2 = rate;
      return;
  }
}

void SpringSet::AllEventValues(const Eigen::Ref<const Vec>& y, Vec& out) const {
  Eigen::Vector3d w;
  for (int j = 0; j < ns_; ++j) {
    double d, rate;
    Kinematics(j, y.head(n_), y.segment(n_, n_), d, rate, w);
    EventValues(j, d, rate, out[2 * j], out[2 * j + 1]);
  }
  for (int f = 0; f < static_cast<int>(friction_.size()); ++f) {
    FrictionEventValues(f, y, out[2 * ns_ + 2 * f], out[2 * ns_ + 2 * f + 1]);
  }
}

double SpringSet::EventValueAt(int e, const Eigen::Ref<const Vec>& y) const {
  double e1, e2;
  if (e < 2 * ns_) {
    const int j = e / 2;
    double d, rate;
    Eigen::Vector3d w;
    Kinematics(j, y.head(n_), y.segment(n_, n_), d, rate, w);
    EventValues(j, d, rate, e1, e2);
  } else {
    FrictionEventValues((e - 2 * ns_) / 2, y, e1, e2);
  }
  return e % 2 == 0 ? e1 : e2;
}

bool SpringSet::Settle(int j, double d, double rate, double t_s) {
  const CompliantSpring& s = springs_[static_cast<std::size_t>(j)];
  SpringState& m = state_[static_cast<std::size_t>(j)];
  const bool dashpot = s.law == SpringLaw::kSpringDashpot;
  const bool key = s.law == SpringLaw::kShearKey;
  bool closed = false;
  for (int k = 0; k < kSettleLimit; ++k) {
    double e1, e2;
    EventValues(j, d, rate, e1, e2);
    if (e1 > 0.0 && e2 > 0.0) {
      break;
    }
    switch (m.branch) {
      case Branch::kOpen:
        if (m.broken) return closed;
        if (!dashpot) {
          if (!(rate > 0.0)) return closed;  // on the closing point, moving out: stays open
          if (m.d_max_m > 0.0) {
            m.branch = Branch::kLine;
          } else {
            m.branch = key ? Branch::kKeyRise : Branch::kEnvelope;
          }
        } else {
          // At d = 0 a closing dashpot engages with c d' > 0 (the Kelvin-Voigt force jumps there).
          if (!(d >= 0.0 && s.k_N_per_m * d + s.c_Ns_per_m * rate > 0.0)) return closed;
          m.branch = Branch::kDashpot;
        }
        closed = true;
        break;
      case Branch::kLine:
        if (e1 <= 0.0 && rate > 0.0) {
          m.branch = key ? KeyPieceAbove(j, m.d_max_m) : Branch::kEnvelope;
        } else if (e2 <= 0.0 && rate < 0.0) {
          m.branch = Branch::kOpen;
        } else {
          return closed;
        }
        break;
      case Branch::kEnvelope:
        if (rate > 0.0) return closed;
        CommitTurn(j, d);  // the turn: the memory takes the deformation reached
        break;
      case Branch::kDashpot:
        m.branch = Branch::kOpen;
        break;
      case Branch::kKeyRise:
      case Branch::kKeySoften:
      case Branch::kKeyResidual: {
        if (!(rate > 0.0)) {
          CommitTurn(j, d);
          break;
        }
        if (!(e1 <= 0.0)) return closed;
        // The piece's end passed while loading: the next piece, or the break at DD, where the
        // memory takes DD and the key's force, zero there, stays zero.
        const double end = m.branch == Branch::kKeyRise     ? s.key.d3_m
                           : m.branch == Branch::kKeySoften ? s.key.d_res_m
                                                            : s.key.dd_m;
        m.branch = KeyPieceAbove(j, end);
        if (m.branch == Branch::kOpen) {
          m.d_max_m = m.d_set_m = s.key.dd_m;
          m.f_peak_N = 0.0;
          m.broken = true;
          key_break_time_s_[j] = t_s;
        }
        break;
      }
    }
  }
  return closed;
}

bool SpringSet::AnyEngaged() const {
  for (const SpringState& m : state_) {
    if (m.branch != Branch::kOpen) return true;
  }
  return false;
}

bool SpringSet::SettleAll(const Eigen::Ref<const Vec>& y, double t_s) {
  const bool engaged = AnyEngaged();
  bool strike = false;
  Eigen::Vector3d w;
  for (int j = 0; j < ns_; ++j) {
    double d, rate;
    Kinematics(j, y.head(n_), y.segment(n_, n_), d, rate, w);
    strike = Settle(j, d, rate, t_s) || strike;
  }
  for (int f = 0; f < static_cast<int>(friction_.size()); ++f) SettleFriction(f, y, t_s);
  return strike && !engaged;
}

void SpringSet::AddForces(const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u,
                          Eigen::Ref<Vec> h, double& joint_W, double& friction_W) const {
  joint_W = 0.0;
  Eigen::Vector3d w, w_face;
  for (int j = 0; j < ns_; ++j) {
    if (state_[static_cast<std::size_t>(j)].branch == Branch::kOpen) continue;
    double d, rate;
    const CompliantSpring& sp = springs_[static_cast<std::size_t>(j)];
    const bool on_body = sp.face.body != model::kGround;
    Kinematics(j, q, u, d, rate, w, on_body ? &w_face : nullptr);
    const double f = BranchForce(j, d, rate);
    h.segment<3>(3 * sp.body) += f * w;
    // A joint between bodies pushes the face's body back with the same force.
    if (on_body) h.segment<3>(3 * sp.face.body) += f * w_face;
    joint_W += f * rate;
  }
  friction_W = 0.0;
  for (const FrictionState& fr : friction_) {
    if (fr.mode == Friction::kFree) continue;
    const AlongTheWall m = WallMotion(*this, fr.spring, q, u);
    const double f_t = FrictionForce(fr, m.s_m, m.normal_N);
    h.segment<3>(3 * springs_[static_cast<std::size_t>(fr.spring)].body) += f_t * m.w_t;
    friction_W -= f_t * m.s_rate_mps;
  }
}

void SpringSet::AddTo(const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u,
                      Eigen::Ref<Vec> h) {
  double joint_W, friction_W;
  AddForces(q, u, h, joint_W, friction_W);
}

void SpringSet::Maxima(const Eigen::Ref<const Vec>& y) {
  Eigen::Vector3d w;
  for (int j = 0; j < ns_; ++j) {
    if (state_[static_cast<std::size_t>(j)].branch == Branch::kOpen) continue;
    double d, rate;
    Kinematics(j, y.head(n_), y.segment(n_, n_), d, rate, w);
    max_force_N_[j] = std::max(max_force_N_[j], std::max(0.0, BranchForce(j, d, rate)));
    max_deformation_m_[j] = std::max(max_deformation_m_[j], d);
  }
}

void SpringSet::EndEnergies(const Eigen::Ref<const Vec>& q, const Eigen::Ref<const Vec>& u,
                            double& joint_stored_J, double& friction_stored_J) {
  double stored = 0.0;
  Eigen::Vector3d w;
  for (int j = 0; j < ns_; ++j) {
    const CompliantSpring& s = springs_[static_cast<std::size_t>(j)];
    const SpringState& m = state_[static_cast<std::size_t>(j)];
    if (m.branch == Branch::kOpen) continue;
    double d, rate;
    Kinematics(j, q, u, d, rate, w);
    if (s.law != SpringLaw::kSpringDashpot) {
      const double f = std::max(0.0, BranchForce(j, d, rate));
      stored += f * f / (2.0 * LineStiffness(j));
    } else {
      stored += 0.5 * s.k_N_per_m * d * d;
    }
  }
  joint_stored_J = stored;
  // The stick springs' energy F_t^2 / (2 k_t) is stored; the rest of the friction's work is
  // dissipated. A slip going on at the end adds its travel so far.
  double friction_stored = 0.0;
  for (FrictionState& fr : friction_) {
    if (fr.mode == Friction::kFree) continue;
    const AlongTheWall m = WallMotion(*this, fr.spring, q, u);
    const double s = m.s_m, normal = m.normal_N;
    const double f_t = FrictionForce(fr, s, normal);
    friction_stored += f_t * f_t / (2.0 * fr.k_t_N_per_m);
    if (fr.mode == Friction::kSlip) {
      wall_slip_m_[fr.spring] +=
          std::abs(s - fr.sigma * fr.mu * normal / fr.k_t_N_per_m - fr.slip_begin_m);
    }
  }
  friction_stored_J = friction_stored;
}

double SpringSet::StiffnessSum_Npm() const {
  double k_sum = 0.0;
  for (const CompliantSpring& s : springs_) {
    switch (s.law) {
      case SpringLaw::kBackfill:
        k_sum += std::max(s.backfill.k_max_N_per_m, s.backfill.k_ur_N_per_m);
        break;
      case SpringLaw::kSpringDashpot:
        k_sum += s.k_N_per_m;
        break;
      case SpringLaw::kShearKey:
        k_sum += s.key.v_n_N / s.key.d3_m;
        break;
    }
  }
  for (const FrictionState& f : friction_) k_sum += f.k_t_N_per_m;
  return k_sum;
}

void SpringSet::MoveResults(CompliantRunResult& out) {
  out.max_spring_force_N = std::move(max_force_N_);
  out.max_spring_deformation_m = std::move(max_deformation_m_);
  out.key_break_time_s = std::move(key_break_time_s_);
  out.wall_slip_m = std::move(wall_slip_m_);
  out.first_slip_time_s = std::move(first_slip_time_s_);
}

}  // namespace skewbridge::dynamics
