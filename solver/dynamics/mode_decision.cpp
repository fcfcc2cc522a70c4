#include "solver/dynamics/mode_decision.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "solver/common/error.h"
#include "solver/dynamics/event_location.h"

namespace skewbridge::dynamics {

DecisionScratch::DecisionScratch(int n_dof, int n_contacts)
    : h(Eigen::VectorXd::Zero(n_dof)),
      lambda_N(Eigen::VectorXd::Zero(n_contacts)),
      lambda_T(Eigen::VectorXd::Zero(n_contacts)),
      event_values(Eigen::VectorXd::Zero(2 * n_contacts)),
      cone_sign(static_cast<std::size_t>(n_contacts), 0) {
  const auto n = static_cast<std::size_t>(n_contacts);
  index_set.reserve(n);
  persistent.reserve(n);
  closed.reserve(n);
  previous.reserve(n);
}

DecisionWorkspace::DecisionWorkspace(const model::Model& model, double rank_threshold)
    : impact(model),
      impact_result(impact.MakeResult()),
      contact_problem(model),
      contact_result(contact_problem.MakeResult()),
      projection(model, rank_threshold),
      scratch(model.n_dof(), model.n_contacts()) {}

double KineticEnergy(const model::Model& model, const Eigen::Ref<const Eigen::VectorXd>& u) {
  const Eigen::VectorXd& m = model.mass_diagonal();
  if (u.size() == 3) {
    // Eigen's dot product of three entries sums the first two, then the third.
    return 0.5 * ((u[0] * (m[0] * u[0]) + u[1] * (m[1] * u[1])) + u[2] * (m[2] * u[2]));
  }
  return 0.5 * u.dot(m.cwiseProduct(u));
}

bool Wedged(const model::Model& model, std::span<const contact::ClosedContact> closed) {
  bool sliding = false, opposing = false;
  for (std::size_t i = 0; i < closed.size(); ++i) {
    sliding = sliding || closed[i].slip_sign != 0;
    const Eigen::Vector2d& ni = model.contact(closed[i].contact).face.normal;
    for (std::size_t j = i + 1; j < closed.size() && !opposing; ++j) {
      opposing = ni.dot(model.contact(closed[j].contact).face.normal) < 0.0;
    }
  }
  return sliding && opposing;
}

ContactMode ModeOfOutcome(contact::ContactOutcome outcome, contact::ContactOutcome friction_outcome,
                          double gammadot_N, double gammadot_T, int slip_sign, bool frictionless,
                          double a_detach_mps2, const EventPolicy& policy,
                          std::optional<ContactMode>& fallback) {
  using contact::ContactOutcome;
  // Ties [§3.7]: a separating acceleration within the band a_detach keeps the contact closed
  // with lambda_N = 0 (what the detachment event of a closed contact allows, lambda_N >
  // -force_tol), and a slip acceleration within it keeps the contact sticking at the cone.
  // Decided the other way, a contact whose acceleration is about to reverse (a graze) comes back
  // within the first step, below any resolvable gap or slip, and the same decision repeats at
  // the same instant.
  fallback.reset();
  if (policy.tie_bands && outcome == ContactOutcome::kDetaches && gammadot_N <= a_detach_mps2) {
    fallback = ContactMode::kOpen;
    outcome = friction_outcome;
  }
  if (policy.tie_bands &&
      (outcome == ContactOutcome::kStartsSlipPositive ||
       outcome == ContactOutcome::kStartsSlipNegative) &&
      std::abs(gammadot_T) <= a_detach_mps2) {
    if (!fallback) {
      fallback = outcome == ContactOutcome::kStartsSlipPositive ? ContactMode::kSlidePositive
                                                                : ContactMode::kSlideNegative;
    }
    outcome = ContactOutcome::kSticks;
  }
  ContactMode mode = ContactMode::kOpen;
  switch (outcome) {
    case ContactOutcome::kDetaches:
      mode = ContactMode::kOpen;
      break;
    case ContactOutcome::kSticks:
      mode = ContactMode::kStick;
      break;
    case ContactOutcome::kStartsSlipPositive:
      mode = ContactMode::kSlidePositive;
      break;
    case ContactOutcome::kStartsSlipNegative:
      mode = ContactMode::kSlideNegative;
      break;
    case ContactOutcome::kSlides:
    case ContactOutcome::kStaysClosed:
      mode = SlideOrStick(slip_sign);
      break;
  }
  if (frictionless && IsClosed(mode)) {
    mode = ContactMode::kFrictionless;
    if (fallback && IsClosed(*fallback)) {
      fallback.reset();  // no slip tie without friction
    }
  }
  if (!IsClosed(mode)) {
    fallback.reset();
  }
  return mode;
}

namespace {

using Vec = Eigen::VectorXd;

// The decision at one instant over its inputs; DecideModes runs it once.
class Decider {
 public:
  Decider(const model::Model& model, const EventPolicy& policy, const DecisionScales& s,
          const DecisionInstant& instant, Eigen::Ref<Vec> q, Eigen::Ref<Vec> u, ContactModes& modes,
          DecisionMemory& memory, ConstrainedForces& forces, DecisionWorkspace& ws,
          DecisionLog& log, AddedForces* added)
      : model_(model),
        policy_(policy),
        s_(s),
        t_(instant.t_s),
        a_g_(instant.a_g_mps2),
        q_(q),
        u_(u),
        modes_(modes),
        memory_(memory),
        forces_(forces),
        ws_(ws),
        kin_(ws.projection.kin),
        scratch_(ws.scratch),
        log_(log),
        added_(added),
        nc_(model.n_contacts()) {}

  DecisionOutcome Decide(std::span<const int> forced);

 private:
  enum class PassEnd { kDone, kJammed, kFailed };

  // 1/2 u^T M u (J), M diagonal.
  double Kinetic() const { return KineticEnergy(model_, u_); }
  DecisionOutcome Fail(RunStatus status, const std::string& what) const {
    return {status, fmt::format("{} at t = {:g} s", what, t_)};
  }
  void ConeSigns();
  PassEnd Pass(std::span<const int> forced, DecisionOutcome& outcome);
  bool ImpactLevel(bool impact, DecisionOutcome& outcome);
  void Jam();
  void Ties();
  void Transitions();
  void Project();
  bool OpenContactApproaching();
  // kin_ at the current (q_, u_): evaluated unless nothing changed q_, u_ or kin_ since the last
  // evaluation (Evaluate is a function of (q, u) alone: the same bits either way).
  void EvaluateKinematics() {
    if (!kin_current_) {
      contact::Evaluate(model_, q_, u_, kin_);
      kin_current_ = true;
    }
  }

  const model::Model& model_;
  const EventPolicy& policy_;
  const DecisionScales& s_;
  const double t_;
  const Eigen::Vector2d a_g_;
  Eigen::Ref<Vec> q_, u_;
  ContactModes& modes_;
  DecisionMemory& memory_;
  ConstrainedForces& forces_;
  DecisionWorkspace& ws_;
  contact::ContactKinematics& kin_;
  DecisionScratch& scratch_;
  DecisionLog& log_;
  AddedForces* added_;  // forces added to the applied forces (AppliedForces); null: none
  const int nc_;
  // Whether kin_ holds the kinematics of (q_, u_): cleared where u_ or q_ change (the impact,
  // the projection, which also evaluates into kin_).
  bool kin_current_ = false;
};

DecisionOutcome Decider::Decide(std::span<const int> forced) {
  // The cascade guard [§3.11].
  if (t_ == memory_.last_event_t_s) {
    if (++memory_.events_here > policy_.max_events_at_one_instant) {
      return Fail(RunStatus::kEventCascade, fmt::format("event cascade: more than {} events",
                                                        policy_.max_events_at_one_instant));
    }
  } else {
    memory_.last_event_t_s = t_;
    memory_.events_here = 0;
    memory_.jammed_here = false;
  }
  const double kinetic_before = Kinetic();
  ConeSigns();
  // The decision passes [§3.11]: the projection of the closed contacts (an equality) can leave
  // an open contact at the face approaching it by a speed of the order of the accumulation
  // threshold (a deck rocking between two corners); the decision is then made again at the same
  // instant with that contact among the candidates, so the state the integrator continues from
  // is consistent and no event re-fires on it.
  for (int pass = 0; pass < policy_.decision_passes; ++pass) {
    if (pass > 0) {
      // A contact that this instant's decision set sliding keeps its direction unless its slip
      // says otherwise (its slip velocity is still zero: the cone decides, not a new tie-break).
      for (int c = 0; c < nc_; ++c) {
        scratch_.cone_sign[static_cast<std::size_t>(c)] = SlipSign(modes_[c]);
      }
    }
    // A jam [§3.9] ends the pass early; the pass then runs once more from the stopped state (at
    // most one jam per instant, so at most twice).
    DecisionOutcome outcome;
    PassEnd end = Pass(pass == 0 ? forced : std::span<const int>(), outcome);
    if (end == PassEnd::kJammed) {
      end = Pass({}, outcome);
      SB_DEMAND(end != PassEnd::kJammed, "DecideModes: a second jam at one instant");
    }
    if (end == PassEnd::kFailed) {
      return outcome;
    }
    if (!OpenContactApproaching()) {
      break;
    }
  }
  log_.impact_J += kinetic_before - Kinetic();
  return {};
}

void Decider::ConeSigns() {
  // A sticking contact whose friction has reached the cone (the stick-slip event) enters the
  // contact problem as sliding against its friction force [§3.8; Pfeiffer and Glocker 1996,
  // ch. 6]: at the cone both sticking and slipping solve the contact problem, Lemke returns
  // sticking, and the friction event would fire again at the same instant.
  std::fill(scratch_.cone_sign.begin(), scratch_.cone_sign.end(), 0);
  if (!policy_.cone_sign || !modes_.any_stick()) {
    return;
  }
  const Vec& lambda_N = scratch_.lambda_N;
  const Vec& lambda_T = scratch_.lambda_T;
  forces_.Forces(modes_, t_, q_, u_, scratch_.lambda_N, scratch_.lambda_T);
  for (int c = 0; c < nc_; ++c) {
    if (modes_[c] == ContactMode::kStick && lambda_T[c] != 0.0 &&
        model_.contact(c).friction * lambda_N[c] + s_.force_tol_N - std::abs(lambda_T[c]) <= 0.0) {
      scratch_.cone_sign[static_cast<std::size_t>(c)] = lambda_T[c] > 0.0 ? -1 : 1;
    }
  }
}

bool Decider::ImpactLevel(bool impact, DecisionOutcome& outcome) {
  // One impact problem over every candidate [§3.3]: the persistent ones with restitution 0. A
  // closure slower than v_acc alone is solved frictionless: its impulse only stops the approach,
  // so the contact problem that follows starts from gamma_N >= 0.
  const std::vector<int>& index_set = scratch_.index_set;
  const double kinetic_before = Kinetic();
  const lcp::LcpStatus status =
      ws_.impact.Solve(kin_, index_set, u_, ws_.impact_result, scratch_.persistent, !impact);
  if (status != lcp::LcpStatus::kSolved) {
    outcome = Fail(RunStatus::kLcpFailure, std::string("impact LCP: ") + lcp::ToString(status));
    return false;
  }
  const contact::ImpactResult& ir = ws_.impact_result;
  u_ = ir.u_E;
  kin_current_ = false;
  const double loss = kinetic_before - Kinetic();
  if (!impact) {
    ++log_.plastic_closures;
    for (int j = 0; j < ir.k; ++j) {
      if (ir.gamma_N_A[j] < -s_.v_tol_mps) {
        log_.events.push_back({t_, EventKind::kPlasticClosure,
                               index_set[static_cast<std::size_t>(j)], ir.Lambda_N[j],
                               ir.Lambda_T[j], ir.gamma_N_A[j], ir.gamma_N_E[j], loss});
      }
    }
    return true;
  }
  ++log_.impacts;
  if (t_ - memory_.last_impact_t_s > s_.simultaneity_s && std::isfinite(memory_.last_impact_t_s)) {
    log_.min_impact_separation_s =
        std::min(log_.min_impact_separation_s, t_ - memory_.last_impact_t_s);
  }
  memory_.last_impact_t_s = t_;
  ++memory_.impact_sequence;
  for (int j = 0; j < ir.k; ++j) {
    const int c = index_set[static_cast<std::size_t>(j)];
    if (ir.gamma_N_A[j] < -s_.v_acc_mps) {
      ImpactHistory& h = memory_.history[static_cast<std::size_t>(c)];
      h.bounce_t_s = t_;
      h.bounce_v_mps = -ir.gamma_N_A[j];
      h.bounce_seq = memory_.impact_sequence;
    }
    if (ir.Lambda_N[j] > 0.0) {
      log_.events.push_back({t_, EventKind::kImpact, c, ir.Lambda_N[j], ir.Lambda_T[j],
                             ir.gamma_N_A[j], ir.gamma_N_E[j], loss});
    }
  }
  return true;
}

Decider::PassEnd Decider::Pass(std::span<const int> forced, DecisionOutcome& outcome) {
  EvaluateKinematics();
  const contact::ContactKinematics& kin = kin_;
  const AccumulationScales acc{s_.period_min_s, s_.gap_tol_m, s_.v_acc_mps};
  // Candidates [§3.3]: closed contacts, touching ones not separating, and the simultaneous ones;
  // each an impact, the end of an accumulation [§3.4] or a settling closure [§3.5] (restitution
  // 0), or persistent (closed, or closing slower than v_acc: restitution 0).
  std::vector<int>& index_set = scratch_.index_set;
  std::vector<int>& persistent = scratch_.persistent;
  index_set.clear();
  persistent.clear();
  bool impact = false, plastic = false, settling = false;
  for (int c = 0; c < nc_; ++c) {
    const bool closed = modes_.closed(c);
    const bool touching = kin.gap_m[c] <= s_.gap_tol_m && kin.gamma_N[c] <= s_.v_tol_mps;
    const bool listed = std::find(forced.begin(), forced.end(), c) != forced.end();
    if (!(closed || touching || listed)) {
      continue;
    }
    index_set.push_back(c);
    const ImpactHistory& history = memory_.history[static_cast<std::size_t>(c)];
    const double approach = -kin.gamma_N[c];
    const auto accumulating = [&]() {
      return Accumulating(history, memory_.impact_sequence, t_, approach, acc, policy_);
    };
    if (kin.gamma_N[c] < -s_.v_acc_mps && !accumulating() &&
        !Settling(history, memory_.impact_sequence, t_, approach, acc, policy_)) {
      impact = true;
    } else if (kin.gamma_N[c] < -s_.v_acc_mps) {
      impact = true;
      settling = settling || !accumulating();
      persistent.push_back(c);
    } else {
      persistent.push_back(c);
      plastic = plastic || kin.gamma_N[c] < -s_.v_tol_mps;
    }
  }
  if ((impact || plastic) && !ImpactLevel(impact, outcome)) {
    return PassEnd::kFailed;
  }
  // Who leaves [§3.5, §3.6]: a candidate separating faster than the thresholds, except a closed
  // contact that the closure of a settling corner lifts (the rocking exception: the deck rocks
  // between the two, and the rocking converges to both closed) and a rebound predicted to return
  // within an accumulation's flight. That prediction takes the free normal acceleration, sound
  // only when every candidate leaves: a deck clamped between two faces, or resting on another
  // corner, returns at a time the free motion does not give. A contact separating slower than
  // the thresholds stays a candidate: it is where an accumulation converges.
  EvaluateKinematics();
  const auto leaves = [&](int c) {
    const bool rocking = settling && modes_.closed(c);
    return kin.gamma_N[c] > std::max(s_.v_tol_mps, s_.v_acc_mps) && !rocking;
  };
  const bool all_leave = impact && std::all_of(index_set.begin(), index_set.end(), leaves);
  Vec& h = scratch_.h;
  if (all_leave) {
    AppliedForces(model_, added_, q_, u_, a_g_, h);
  }
  std::vector<contact::ClosedContact>& closed = scratch_.closed;
  closed.clear();
  for (std::size_t j = 0; j < index_set.size(); ++j) {
    const int c = index_set[j];
    const auto normal_accel = [&]() {
      const double* inv_m = model_.inverse_mass_diagonal().data();
      double a = kin.what_N[c];
      for (int i = 0; i < model_.n_dof(); ++i) {
        a += kin.W_N(i, c) * (inv_m[i] * h[i]);
      }
      return a;
    };
    const bool accumulates =
        all_leave && BounceClosesAtOnce(-ws_.impact_result.gamma_N_A[static_cast<Eigen::Index>(j)],
                                        kin.gamma_N[c], normal_accel, acc, policy_);
    if (leaves(c) && !accumulates) {
      memory_.history[static_cast<std::size_t>(c)].left_t_s = t_;
      if (modes_.closed(c)) {
        ++log_.detachments;
        log_.events.push_back({t_, EventKind::kDetachment, c, 0.0, 0.0, 0.0, 0.0});
      }
      modes_.Set(c, ContactMode::kOpen);
      memory_.tie[static_cast<std::size_t>(c)].reset();  // an open contact has no tie
      continue;
    }
    // The slip sign it enters the contact problem with [§3.7, §3.8].
    int sign = 0;
    if (model_.contact(c).friction == 0.0) {
      sign = 1;
    } else if (std::abs(kin.gamma_T[c]) > policy_.stick_band * s_.v_tol_mps) {
      sign = kin.gamma_T[c] > 0.0 ? 1 : -1;
    } else if (!impact) {
      sign = scratch_.cone_sign[static_cast<std::size_t>(c)];
    }
    closed.push_back({c, sign});
  }
  scratch_.previous.clear();
  for (const contact::ClosedContact& cc : closed) {
    scratch_.previous.push_back(modes_[cc.contact]);
    modes_.Set(cc.contact, ContactMode::kOpen);
  }
  if (!closed.empty()) {
    // The contact problem [§3.7].
    AppliedForces(model_, added_, q_, u_, a_g_, h);
    const contact::ContactStatus status =
        ws_.contact_problem.Solve(kin, closed, h, ws_.contact_result);
    if (policy_.jam && status == contact::ContactStatus::kPainleve && !memory_.jammed_here &&
        Wedged(model_, closed)) {
      Jam();
      return PassEnd::kJammed;
    }
    if (status == contact::ContactStatus::kPainleve) {
      outcome = Fail(RunStatus::kPainleve, "Painleve situation (contact LCP on a secondary ray)");
      return PassEnd::kFailed;
    }
    if (status != contact::ContactStatus::kSolved) {
      outcome =
          Fail(RunStatus::kLcpFailure, std::string("contact LCP: ") + contact::ToString(status));
      return PassEnd::kFailed;
    }
    const contact::ContactResult& cr = ws_.contact_result;
    for (std::size_t j = 0; j < closed.size(); ++j) {
      const int c = closed[j].contact;
      const auto jj = static_cast<Eigen::Index>(j);
      std::optional<ContactMode>& fallback = memory_.tie[static_cast<std::size_t>(c)];
      modes_.Set(
          c, ModeOfOutcome(cr.outcome[j], cr.friction_outcome[j], cr.gammadot_N(jj),
                           cr.gammadot_T(jj), closed[j].slip_sign,
                           model_.contact(c).friction == 0.0, s_.a_detach_mps2, policy_, fallback));
    }
    Ties();
    Transitions();
  }
  if (modes_.any_closed()) {
    Project();
  }
  return PassEnd::kDone;
}

void Decider::Jam() {
  // A jam [§3.9]: corners on two opposing faces, some sliding (a deck wedged between its
  // abutments, the friction of one corner pressing the other into its face), can leave the
  // contact problem without a solution; the deck wedges and the sliding stops at once by a
  // tangential impact [Genot and Brogliato 1999; Pfeiffer and Glocker 1996, ch. 6]. Its impulse
  // is the velocity projection onto gamma_N = gamma_T = 0 of these contacts, with no
  // restitution; the caller then decides again from the stopped state, once per instant (a
  // second jam at the same instant is a Painleve situation).
  memory_.jammed_here = true;
  const double kinetic_before = Kinetic();
  for (const contact::ClosedContact& cc : scratch_.closed) {
    const int c = cc.contact;
    modes_.Set(
        c, model_.contact(c).friction == 0.0 ? ContactMode::kFrictionless : ContactMode::kStick);
    memory_.tie[static_cast<std::size_t>(c)].reset();  // the jam, not a tie, set this mode
    scratch_.cone_sign[static_cast<std::size_t>(c)] = 0;
  }
  Project();
  ++log_.impacts;
  const double loss = kinetic_before - Kinetic();
  for (const contact::ClosedContact& cc : scratch_.closed) {
    log_.events.push_back({t_, EventKind::kImpact, cc.contact, 0.0, 0.0, 0.0, 0.0, loss});
  }
}

void Decider::Ties() {
  // The tie fallback [§3.7]: each tie against the constrained phase's event functions at this
  // instant; a tie whose function is not positive takes the contact problem's answer (one at a
  // time, since each change moves the others' forces).
  Vec& values = scratch_.event_values;
  for (int pass = 0; pass < nc_; ++pass) {
    const bool any_tie =
        std::any_of(memory_.tie.begin(), memory_.tie.end(),
                    [](const std::optional<ContactMode>& tie) { return tie.has_value(); });
    if (!any_tie) {
      return;
    }
    forces_.Forces(modes_, t_, q_, u_, scratch_.lambda_N, scratch_.lambda_T);
    ClosedEventValues(model_, modes_, kin_.gamma_T, scratch_.lambda_N, scratch_.lambda_T,
                      s_.force_tol_N, s_.v_tol_mps, values);
    bool changed = false;
    for (int c = 0; c < nc_ && !changed; ++c) {
      std::optional<ContactMode>& fallback = memory_.tie[static_cast<std::size_t>(c)];
      if (!fallback) {
        continue;
      }
      const bool detach_tie = *fallback == ContactMode::kOpen;
      if (!(values[2 * c] > 0.0) || (!detach_tie && !(values[2 * c + 1] > 0.0))) {
        modes_.Set(c, *fallback);
        fallback.reset();
        changed = true;
      }
    }
    if (!changed) {
      return;
    }
  }
}

void Decider::Transitions() {
  // The events of the contact problem's contacts: each compared with its mode before it.
  const std::vector<contact::ClosedContact>& closed = scratch_.closed;
  for (std::size_t j = 0; j < closed.size(); ++j) {
    const int c = closed[j].contact;
    const ContactMode before = scratch_.previous[j];
    const ContactMode mode = modes_[c];
    if (!IsClosed(mode) && IsClosed(before)) {
      ++log_.detachments;
      log_.events.push_back({t_, EventKind::kDetachment, c, 0.0, 0.0, 0.0, 0.0});
    } else if (mode == ContactMode::kStick && IsClosed(before) && before != mode) {
      ++log_.stick_transitions;
      log_.events.push_back({t_, EventKind::kStick, c, 0.0, 0.0, 0.0, 0.0});
    } else if (IsSliding(mode) && IsClosed(before) && before != mode) {
      ++log_.slip_transitions;
      log_.events.push_back({t_, EventKind::kSlip, c, 0.0, 0.0, 0.0, 0.0});
    }
  }
}

void Decider::Project() {
  kin_current_ = false;
  ProjectOntoContacts(model_, modes_, policy_, {s_.length_scale_m, s_.gap_tol_m, s_.v_tol_mps}, q_,
                      u_, ws_.projection);
}

bool Decider::OpenContactApproaching() {
  // Re-decision [§3.11]: an open contact at its face approaching it faster than v_tol. Leaves
  // the kinematics of every contact at the final state.
  EvaluateKinematics();
  for (int c = 0; c < nc_; ++c) {
    if (!modes_.closed(c) && kin_.gap_m[c] <= s_.gap_tol_m && kin_.gamma_N[c] < -s_.v_tol_mps) {
      return true;
    }
  }
  return false;
}

}  // namespace

DecisionOutcome DecideModes(const model::Model& model, const EventPolicy& policy,
                            const DecisionScales& scales, const DecisionInstant& instant,
                            Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> u,
                            ContactModes& modes, DecisionMemory& memory, ConstrainedForces& forces,
                            DecisionWorkspace& ws, DecisionLog& log, AddedForces* added) {
  SB_DEMAND(modes.size() == model.n_contacts() &&
                static_cast<int>(memory.history.size()) == model.n_contacts() &&
                static_cast<int>(memory.tie.size()) == model.n_contacts() &&
                static_cast<int>(ws.scratch.cone_sign.size()) == model.n_contacts(),
            "DecideModes: modes, memory or scratch sized for another model");
  Decider decider(model, policy, scales, instant, q, u, modes, memory, forces, ws, log, added);
  return decider.Decide(instant.forced);
}

}  // namespace skewbridge::dynamics
