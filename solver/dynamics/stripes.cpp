#include "solver/dynamics/stripes.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "solver/common/error.h"
#include "solver/contact/kinematics.h"
#include "solver/dynamics/corner_travel.h"
#include "solver/dynamics/linear_flow.h"
#include "solver/dynamics/run.h"
#include "solver/model/deck.h"

namespace skewbridge::dynamics {
namespace {

using Vec = Eigen::VectorXd;

// Up to this many DOFs (two decks) a corner's rate evaluates the whole state of the dense output
// once per instant: 2 n rows of n products against four components of n each.
constexpr int kWholeStateDofs = 6;

// Follows the trace run's free steps and, for every stripe still clear of the gaps, the scaled
// state's gaps and corner travels; a stripe whose gaps come within reach in a step stops there.
class StripeTracer final : public FreeStepObserver {
 public:
  StripeTracer(const model::Model& model, const Excitation& excitation, double trace_factor,
               const EventPolicy& policy, std::span<const double> factors)
      : model_(model),
        excitation_(excitation),
        policy_(policy),
        flow_(model.M(), model.K(), model.C(), model.r(), FlowPath::kAuto, model.modes()),
        dense_(flow_.augmented_size()),
        n_(model.n_dof()),
        nc_(model.n_contacts()) {
    // The length scale of the integrator's workspace (SimulationWorkspace).
    double length_m = 1.0;
    for (const model::Body& body : model.bodies()) {
      length_m = std::max({length_m, body.geometry.length_m, body.geometry.width_m,
                           body.rest_position_m.norm() + body.geometry.length_m});
    }
    margin_m_ = 1e-9 * length_m;
    rates_.Resize(model);
    z_aug_ = Vec::Zero(flow_.augmented_size());
    q0_ = u0_ = q1_ = u1_ = Vec::Zero(n_);
    prev_max_ = prev_time_ = Vec::Zero(n_);
    Vec rest_gap = Vec::Zero(nc_), rest_rate = Vec::Zero(nc_);
    contact::GapsAndRates(model, q0_, u0_, rest_gap, rest_rate, rates_);
    prev_z1_ = state_at_ = Vec::Zero(2 * n_);
    BoundGeometry(rest_gap);
    starts_.resize(factors.size());
    samples_.assign(factors.size(), 0);
    stripes_.reserve(factors.size());
    for (std::size_t s = 0; s < factors.size(); ++s) {
      starts_[s].factor = factors[s];
      Stripe& st = stripes_.emplace_back(model);
      st.scale = factors[s] / trace_factor;
      st.travel.Start(q0_, st.max_travel_m);
      st.g0 = rest_gap;
      st.gN0 = rest_rate;
      st.g1 = st.gN1 = Vec::Zero(nc_);
    }
    for (const model::Body& body : model.bodies()) {
      // CornerTravelTracker's end-line normal and corner radius, by the same operations.
      const double a = body.geometry.skew_rad;
      DeckReach d{std::abs(std::cos(a)), std::abs(std::sin(a)), 0.0};
      for (int k = 1; k <= 2; ++k)
        d.radius = std::max(d.radius, model::Corner(body.geometry, k).norm());
      decks_.push_back(d);
    }
    reach_bound_ = Vec::Zero(static_cast<Eigen::Index>(decks_.size()));
  }

  bool Step(double t0, const Eigen::Ref<const Vec>& z0, double h0, double t1,
            const Eigen::Ref<const Vec>& z1, const RunResult& run) override {
    const long free_steps = run.free_steps;
    const double tau = t1 - t0;
    const double tolerance =
        policy_.maximum_time_tolerance * std::max(1.0, std::abs(t1)) + policy_.event_time_floor_s;
    const double clear_below = ClearScale(z1, tau);
    for (std::size_t d = 0; d < decks_.size(); ++d) {
      reach_bound_[static_cast<Eigen::Index>(d)] =
          ReachBound(decks_[d], 3 * static_cast<int>(d), z0, z1, tau);
    }
    bool dense_built = false;
    bool any_live = false;
    for (std::size_t s = 0; s < stripes_.size(); ++s) {
      Stripe& st = stripes_[s];
      if (!st.live) continue;
      const double c = st.scale;
      // A stripe whose gaps the bound keeps open skips their values at the step's end; the next
      // step that needs its start's values takes them from the trace's state there.
      bool reach = false;
      if (c * (1.0 + 1e-9) < clear_below) {
        st.ends_known = false;
      } else {
        if (!st.ends_known) {
          q0_ = c * prev_z1_.head(n_);
          u0_ = c * prev_z1_.segment(n_, n_);
          contact::GapsAndRates(model_, q0_, u0_, st.g0, st.gN0, rates_);
        }
        q1_ = c * z1.head(n_);
        u1_ = c * z1.segment(n_, n_);
        contact::GapsAndRates(model_, q1_, u1_, st.g1, st.gN1, rates_);
        for (int k = 0; k < nc_; ++k) {
          const double gap = std::min(st.g0[k], st.g1[k]) - margin_m_;
          const double dip =
              policy_.dip_margin * 0.5 * std::max(std::abs(st.gN0[k]), std::abs(st.gN1[k])) * tau;
          if (!(gap > dip)) reach = true;
        }
        std::swap(st.g0, st.g1);
        std::swap(st.gN0, st.gN1);
        st.ends_known = true;
      }
      if (reach) {
        // The stripe's event-driven run goes on from this step's start.
        StripeStart& out = starts_[s];
        out.reaches_gap = true;
        out.state.q = c * z0.head(n_);
        out.state.u = c * z0.segment(n_, n_);
        out.state.t_s = t0;
        out.state.free_steps = free_steps - 1;
        out.state.h_free_s = h0;
        out.linear.end_time_s = t0;
        out.linear.max_abs_q = c * prev_max_;
        out.linear.time_of_max_s = prev_time_;
        out.linear.max_travel_m = st.max_travel_m;
        out.linear.free_steps = free_steps - 1;
        out.linear.energy.input_J = c * c * prev_input_J_;
        out.linear.energy.damping_J = c * c * prev_damping_J_;
        samples_[s] = prev_samples_;
        st.live = false;
        continue;
      }
      any_live = true;
      // Scan evaluates no corner when every deck's reach stays below its running maximum.
      bool below = true;
      for (Eigen::Index d = 0; d < reach_bound_.size(); ++d) {
        if (!(c * reach_bound_[d] * (1.0 + 1e-9) < st.max_travel_m[d])) below = false;
      }
      if (below) continue;
      q0_ = c * z0.head(n_);
      u0_ = c * z0.segment(n_, n_);
      q1_ = c * z1.head(n_);
      u1_ = c * z1.segment(n_, n_);
      // The scaled dense output of the trace's step, built as the integrator builds it. A
      // corner's rate reads four components at one instant: for a model of few DOFs the whole
      // state there is evaluated once (EvaluateHead, each entry the bits of EvaluateComponent:
      // the same series and the same sums from 0.0 in mode order) and kept for the next reads.
      const auto component_at = [&](double t, int i) {
        if (!dense_built) {
          z_aug_.head(2 * n_) = z0;
          const ExcitationPiece piece = excitation_.PieceAt(t0);
          flow_.SetGenerator(piece, t0, z_aug_);
          dense_.Build(flow_, piece.omega, z_aug_, tau);
          dense_built = true;
          state_known_ = false;
        }
        const double tau_s = t - t0;
        if (n_ > kWholeStateDofs || i >= 2 * n_) return c * dense_.EvaluateComponent(tau_s, i);
        if (!state_known_ || std::bit_cast<std::uint64_t>(tau_s) != state_tau_bits_) {
          dense_.EvaluateHead(tau_s, 2 * n_, state_at_);
          state_tau_bits_ = std::bit_cast<std::uint64_t>(tau_s);
          state_known_ = true;
        }
        return c * state_at_[i];
      };
      st.travel.Scan(t0, q0_, u0_, t1, q1_, u1_, tolerance, component_at, st.max_travel_m);
    }
    prev_z1_ = z1;
    prev_max_ = run.max_abs_q;
    prev_time_ = run.time_of_max_s;
    prev_input_J_ = run.energy.input_J;
    prev_damping_J_ = run.energy.damping_J;
    prev_samples_ = run.histories.t_s.size();
    last_t_s_ = t1;
    return any_live;
  }

  // The stripes after the trace run `trace`: those still clear of the gaps are whole runs when
  // the trace reached its end without an event, else they run from rest.
  std::vector<StripeStart> Finish(const RunResult& trace) {
    const bool whole = trace.status == RunStatus::kOk && trace.events.empty() &&
                       trace.rk_steps == 0 && last_t_s_ == trace.end_time_s;
    for (std::size_t s = 0; s < stripes_.size(); ++s) {
      Stripe& st = stripes_[s];
      if (!st.live) continue;
      StripeStart& out = starts_[s];
      if (!whole) {
        out.reaches_gap = true;
        out.state = InitialState{};
        out.linear = RunResult{};
        continue;
      }
      samples_[s] = trace.histories.t_s.size();
      const double c = st.scale;
      RunResult& r = out.linear;
      r.status = RunStatus::kOk;
      r.end_time_s = trace.end_time_s;
      r.max_abs_q = c * trace.max_abs_q;
      r.time_of_max_s = trace.time_of_max_s;
      r.max_travel_m = st.max_travel_m;
      r.q_end = c * trace.q_end;
      r.u_end = c * trace.u_end;
      r.free_steps = trace.free_steps;
      // The work is quadratic in the factor; without the ledger the trace's is NaN.
      r.energy.input_J = c * c * trace.energy.input_J;
      r.energy.damping_J = c * c * trace.energy.damping_J;
      r.energy.kinetic_J = 0.5 * r.u_end.dot(model_.mass_diagonal().cwiseProduct(r.u_end));
      r.energy.strain_J = 0.5 * r.q_end.dot(model_.K() * r.q_end);
      r.energy.balance_error_J =
          (r.energy.kinetic_J + r.energy.strain_J) - (r.energy.input_J - r.energy.damping_J);
    }
    // The history samples of each stripe's contact-free part: the trace's, scaled.
    for (std::size_t s = 0; s < stripes_.size(); ++s) {
      if (starts_[s].reaches_gap && starts_[s].state.t_s == 0.0) continue;
      ScaledHistories(trace.histories, stripes_[s].scale, samples_[s], starts_[s].linear.histories);
    }
    return std::move(starts_);
  }

 private:
  struct Stripe {
    explicit Stripe(const model::Model& model) : travel(model) {}
    double scale = 1.0;      // the stripe's factor over the trace's
    bool live = true;        // no gap within reach so far
    bool ends_known = true;  // g0, gN0 hold the scaled gaps and rates at the last step's end
    CornerTravelTracker travel;
    Vec max_travel_m;
    Vec g0, gN0, g1, gN1;  // the scaled gaps and normal rates at the step's ends
  };

  // A deck's |n_e| components and corner radius (m), as CornerTravelTracker holds them.
  struct DeckReach {
    double nx = 0.0, ny = 0.0, radius = 0.0;
  };

  // An upper bound (m) of the reach CornerTravelTracker::Scan compares with the deck's running
  // maximum over the step between the trace's states z0 and z1 (the deck's DOFs from b): every
  // term by its absolute value, so that the bound is homogeneous in a factor c > 0 on the state.
  // Scan evaluates no corner of a stripe at c when c times this bound times 1 + 1e-9 is below
  // its running maximum; the rounding of the scaled state and of Scan's sums lies far inside.
  double ReachBound(const DeckReach& deck, int b, const Eigen::Ref<const Vec>& z0,
                    const Eigen::Ref<const Vec>& z1, double tau) const {
    const auto reach = [&](const Eigen::Ref<const Vec>& z, int i) {
      return deck.nx * std::abs(z[i]) + deck.ny * std::abs(z[i + 1]) +
             deck.radius * std::abs(z[i + 2]);
    };
    return std::max(reach(z0, b), reach(z1, b)) +
           0.5 * tau * std::min(reach(z0, n_ + b), reach(z1, n_ + b));
  }

  // The gap bound's constants (docs/theory.md §3.19): per contact, the room left below the gap
  // at rest, |p| |n| and the body's DOF; without a bound (a face on a body, a gap at rest within
  // the margin) every stripe's gaps are evaluated at every step.
  void BoundGeometry(const Vec& rest_gap) {
    bound_ok_ = true;
    room_m_.resize(static_cast<std::size_t>(nc_));
    arm_m_.resize(static_cast<std::size_t>(nc_));
    dof_.resize(static_cast<std::size_t>(nc_));
    start_drop_.assign(static_cast<std::size_t>(nc_), 0.0);
    start_rate_.assign(static_cast<std::size_t>(nc_), 0.0);
    for (int k = 0; k < nc_; ++k) {
      const model::Contact& contact = model_.contact(k);
      const auto ki = static_cast<std::size_t>(k);
      if (contact.face.body != model::kGround) bound_ok_ = false;
      const double size = 1.0 + model_.body(contact.body).rest_position_m.norm() +
                          contact.point_m.norm() + contact.face.point_m.norm();
      room_m_[ki] = rest_gap[k] - 1e-12 * size - margin_m_;
      if (!(room_m_[ki] > 0.0)) bound_ok_ = false;
      arm_m_[ki] = contact.point_m.norm() * contact.face.normal.norm() * (1.0 + 1e-12);
      dof_[ki] = 3 * contact.body;
    }
  }

  // The largest factor on the trace's state below which no stripe's gap can come within reach in
  // the step ending at z1 (0 without a bound); keeps the bound's terms at z1 for the next step.
  // Per contact, g >= g_rest + n . (x, y) - |theta| |p| and |gamma_N| <= |n_x u_x| + |n_y u_y| +
  // |u_theta| |p| (|(R(theta) - E) p| <= |theta| |p|), both homogeneous in the factor.
  double ClearScale(const Eigen::Ref<const Vec>& z1, double tau) {
    if (!bound_ok_) return 0.0;
    double clear = std::numeric_limits<double>::infinity();
    for (int k = 0; k < nc_; ++k) {
      const auto ki = static_cast<std::size_t>(k);
      const model::Contact& contact = model_.contact(k);
      const int i = dof_[ki];
      const double nx = contact.face.normal.x(), ny = contact.face.normal.y();
      const double x = z1[i], y = z1[i + 1], th = std::abs(z1[i + 2]);
      const double turn = th * arm_m_[ki];
      const double drop =
          -(nx * x + ny * y) + turn + 1e-12 * (std::abs(nx * x) + std::abs(ny * y) + turn);
      const double rate = (std::abs(nx * z1[n_ + i]) + std::abs(ny * z1[n_ + i + 1]) +
                           std::abs(z1[n_ + i + 2]) * arm_m_[ki]) *
                          (1.0 + 1e-12);
      const double weight = std::max(start_drop_[ki], drop) +
                            policy_.dip_margin * 0.5 * std::max(start_rate_[ki], rate) * tau;
      start_drop_[ki] = drop;
      start_rate_[ki] = rate;
      if (weight > 0.0) {
        clear = std::min(clear, room_m_[ki] / weight);
      } else if (!(weight <= 0.0)) {
        clear = 0.0;  // not finite
      }
    }
    return clear;
  }

  const model::Model& model_;
  const Excitation& excitation_;
  const EventPolicy& policy_;
  LinearFlow flow_;
  FreeDenseOutput dense_;
  int n_, nc_;
  double margin_m_ = 0.0;  // a gap closer than this to the step's reach may close
  contact::GapRateScratch rates_;
  Vec z_aug_, q0_, u0_, q1_, u1_;
  Vec prev_z1_;  // the trace's state at the last step's end
  // The trace's (q, u) on the dense output of this step at the instant of bits state_tau_bits_
  // (s from the step's start), when state_known_.
  Vec state_at_;
  std::uint64_t state_tau_bits_ = 0;
  bool state_known_ = false;
  // The gap bound: whether it applies, per contact the room below the rest gap (m), |p| |n| (m),
  // the body's first DOF, the gap's drop and rate bound at the last step's end (trace units).
  bool bound_ok_ = false;
  std::vector<double> room_m_, arm_m_, start_drop_, start_rate_;
  std::vector<int> dof_;
  std::vector<DeckReach> decks_;
  Vec reach_bound_;           // per deck: ReachBound of the trace's step (m)
  Vec prev_max_, prev_time_;  // the trace's maxima and their times at the step's start
  double last_t_s_ = 0.0;     // the end of the last step seen
  // The trace's work of the ledger and history samples at the step's start.
  double prev_input_J_ = 0.0, prev_damping_J_ = 0.0;
  std::size_t prev_samples_ = 0;
  std::vector<std::size_t> samples_;  // per stripe: the trace's samples that are its own

  // The first `count` samples of `trace` (a contact-free run) at `scale`: the states scaled, the
  // gaps of the scaled state, every contact open.
  void ScaledHistories(const Histories& trace, double scale, std::size_t count,
                       Histories& out) const {
    out.n_dof = trace.n_dof;
    out.n_contacts = trace.n_contacts;
    count = std::min(count, trace.t_s.size());
    if (count == 0) return;
    const std::size_t n = static_cast<std::size_t>(n_), nc = static_cast<std::size_t>(nc_);
    out.t_s.assign(trace.t_s.begin(), trace.t_s.begin() + static_cast<std::ptrdiff_t>(count));
    out.q.resize(count * n);
    out.u.resize(count * n);
    for (std::size_t i = 0; i < count * n; ++i) {
      out.q[i] = scale * trace.q[i];
      out.u[i] = scale * trace.u[i];
    }
    out.gap_m.resize(count * nc);
    out.lambda_N.assign(count * nc, 0.0);
    out.lambda_T.assign(count * nc, 0.0);
    out.state.assign(count * nc, static_cast<int>(ContactState::kOpen));
    Vec q(n_);
    for (std::size_t k = 0; k < count; ++k) {
      for (std::size_t i = 0; i < n; ++i) q[static_cast<Eigen::Index>(i)] = out.q[k * n + i];
      for (int c = 0; c < nc_; ++c) {
        out.gap_m[k * nc + static_cast<std::size_t>(c)] = contact::Gap(model_, c, q);
      }
    }
  }
  std::vector<Stripe> stripes_;
  std::vector<StripeStart> starts_;
};

}  // namespace

std::vector<StripeStart> TraceStripes(const model::Model& model, const Excitation& trace_excitation,
                                      double trace_factor, const model::RunControl& control,
                                      const RunPolicies& policies,
                                      std::span<const double> factors) {
  SB_DEMAND(control.method == model::Method::kEventDriven, "TraceStripes: an event-driven run");
  StripeTracer tracer(model, trace_excitation, trace_factor, policies.event, factors);
  SimulationWorkspace workspace(model);
  const RunResult trace =
      Simulate(model, trace_excitation, control, workspace, {}, policies.event, &tracer);
  return tracer.Finish(trace);
}

RunResult RunStripe(const model::Model& model, const Excitation& excitation,
                    const model::RunControl& control, const RunPolicies& policies,
                    const StripeStart& start) {
  if (!start.reaches_gap) return start.linear;
  if (start.state.t_s == 0.0) return Run(model, excitation, control, policies);
  RunResult run = Run(model, excitation, control, policies, start.state);
  const RunResult& before = start.linear;
  for (Eigen::Index i = 0; i < run.max_abs_q.size(); ++i) {
    if (before.max_abs_q[i] > run.max_abs_q[i]) {
      run.max_abs_q[i] = before.max_abs_q[i];
      run.time_of_max_s[i] = before.time_of_max_s[i];
    }
  }
  run.max_travel_m = run.max_travel_m.cwiseMax(before.max_travel_m);
  // The work over [0, t_s] (quadratic in the factor) before the run's own, from rest.
  EnergyLedger& e = run.energy;
  e.initial_J = 0.0;
  e.input_J += before.energy.input_J;
  e.damping_J += before.energy.damping_J;
  e.balance_error_J = (e.kinetic_J + e.strain_J) -
                      (e.initial_J + e.input_J - e.damping_J - e.impact_J - e.friction_J);
  if (control.output_interval_s > 0.0) {
    // The samples before t_s, then the run's own (one grid: the times compare exactly).
    const Histories& first = before.histories;
    Histories& h = run.histories;
    std::size_t count = first.t_s.size();
    while (count > 0 && !h.t_s.empty() && first.t_s[count - 1] >= h.t_s.front()) --count;
    const auto prepend = [](auto& to, const auto& from, std::size_t n) {
      to.insert(to.begin(), from.begin(), from.begin() + static_cast<std::ptrdiff_t>(n));
    };
    const std::size_t n = static_cast<std::size_t>(h.n_dof);
    const std::size_t nc = static_cast<std::size_t>(h.n_contacts);
    prepend(h.t_s, first.t_s, count);
    prepend(h.q, first.q, count * n);
    prepend(h.u, first.u, count * n);
    prepend(h.gap_m, first.gap_m, count * nc);
    prepend(h.lambda_N, first.lambda_N, count * nc);
    prepend(h.lambda_T, first.lambda_T, count * nc);
    prepend(h.state, first.state, count * nc);
  }
  return run;
}

RunResult RunScaledRecord(const model::Model& model, const Excitation& excitation,
                          const Excitation& trace_excitation, double factor,
                          const model::RunControl& control, const RunPolicies& policies) {
  const double factors[] = {factor};
  const std::vector<StripeStart> starts =
      TraceStripes(model, trace_excitation, kStripeTraceFactor, control, policies, factors);
  return RunStripe(model, excitation, control, policies, starts.front());
}

}  // namespace skewbridge::dynamics
