#include "solver/dynamics/compliant_strike.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "solver/common/error.h"
#include "solver/dynamics/root_finding.h"
#include "solver/dynamics/runge_kutta.h"

namespace skewbridge::dynamics {
namespace {

// The state of a strike: deformation d (m), velocity d' (m/s, positive loads the joint), and the
// work of the joint's force W = integral of F dd (J).
constexpr int kD = 0, kV = 1, kW = 2;

// Scales of one strike, for the step control and the event tolerance.
struct Scales {
  double time_s;
  Eigen::Vector3d atol;
};

Scales MakeScales(double mass_kg, double stiffness_N_per_m, double v0_mps,
                  const StrikeTolerances& tolerances) {
  Scales s;
  s.time_s = std::sqrt(mass_kg / stiffness_N_per_m);
  s.atol = tolerances.relative *
           Eigen::Vector3d(v0_mps * s.time_s, v0_mps, 0.5 * mass_kg * v0_mps * v0_mps);
  return s;
}

// Where a phase ended.
struct PhaseEnd {
  double t_s = 0.0;
  Eigen::Vector3d y = Eigen::Vector3d::Zero();
  bool located = false;  // false: the step budget ran out first
};

// Integrates m d'' = -F(d, d') from (t, y) until `event` (positive inside the phase) reaches zero,
// located on the dense output of the step in which it changes sign. Tracks the largest force.
template <class Force, class Event>
PhaseEnd RunPhase(DormandPrince45& rk, double mass_kg, const Force& force, const Event& event,
                  double t, const Eigen::Vector3d& y0, const Scales& scales,
                  const StrikeTolerances& tolerances, StrikeResult& result) {
  auto rhs = [&](double, const Eigen::Ref<const Eigen::VectorXd>& y,
                 Eigen::Ref<Eigen::VectorXd> dy) {
    const double f = force(y[kD], y[kV]);
    dy[kD] = y[kV];
    dy[kV] = -f / mass_kg;
    dy[kW] = f * y[kV];
  };
  Eigen::VectorXd y = y0, dy(3), dense(3);
  rhs(t, y, dy);
  double h = 0.01 * scales.time_s;
  double g_start = event(y[kD], y[kV]);
  SB_DEMAND(g_start > 0.0, "a strike's phase must start inside its event function");
  PhaseEnd end;
  while (result.steps < tolerances.max_steps) {
    rk.Step(rhs, t, y, dy, h);
    const double error = rk.ErrorNorm(scales.atol, tolerances.relative);
    if (error > 1.0) {
      h *= DormandPrince45::StepFactor(error);
      continue;
    }
    ++result.steps;
    const Eigen::VectorXd& y1 = rk.y_end();
    const double g_end = event(y1[kD], y1[kV]);
    if (g_end <= 0.0) {
      auto g = [&](double time) {
        rk.DenseAt(time, dense);
        return event(dense[kD], dense[kV]);
      };
      const RootResult root =
          FindRootBrent(g, t, t + h, g_start, g_end, tolerances.event_time * scales.time_s);
      // The end of the bracket on the event's far side, so that the next phase starts inside.
      end.t_s = root.upper;
      rk.DenseAt(end.t_s, dense);
      end.y = dense;
      end.located = true;
      ++result.events;
      for (int i = 1; i <= 16; ++i) {  // the largest force, sampled on the dense output
        rk.DenseAt(t + (end.t_s - t) * i / 16.0, dense);
        result.max_force_N = std::max(result.max_force_N, force(dense[kD], dense[kV]));
      }
      return end;
    }
    for (int i = 1; i <= 16; ++i) {
      rk.Dense(i / 16.0, dense);
      result.max_force_N = std::max(result.max_force_N, force(dense[kD], dense[kV]));
    }
    t += h;
    y = y1;
    dy = rk.dy_end();
    g_start = g_end;
    h *= DormandPrince45::StepFactor(error);
  }
  end.t_s = t;
  end.y = y;
  return end;
}

void Finish(StrikeResult& result, double mass_kg, const PhaseEnd& end) {
  const double v0 = result.approach_speed_mps;
  result.contact_duration_s = end.t_s;
  result.exit_speed_mps = std::abs(end.y[kV]);
  result.restitution = result.exit_speed_mps / v0;
  result.dissipated_J = end.y[kW];
  const double input_J = 0.5 * mass_kg * v0 * v0;
  result.energy_residual =
      (input_J - 0.5 * mass_kg * result.exit_speed_mps * result.exit_speed_mps -
       result.dissipated_J) /
      input_J;
  if (!end.located) result.status = StrikeStatus::kNoSeparation;
}

}  // namespace

StrikeResult StrikeBackfill(const joint::HyperbolicGap& law, const joint::BackfillState& state,
                            double mass_kg, double approach_speed_mps,
                            const StrikeTolerances& tolerances) {
  SB_DEMAND(mass_kg > 0.0 && approach_speed_mps > 0.0, "a strike needs a mass and a speed");
  StrikeResult result;
  result.approach_speed_mps = approach_speed_mps;
  const Scales scales = MakeScales(mass_kg, std::max(law.k_max_N_per_m, law.k_ur_N_per_m),
                                   approach_speed_mps, tolerances);
  DormandPrince45 rk(3);
  // Deformations here are measured beyond the initial gap, as the law's d.
  joint::BackfillState memory = state;
  const double d_set = joint::PermanentSet_m(law, memory);
  // On the unloading-reloading line the force is continued past the line's ends (no cut at zero,
  // no envelope above d_max): the Runge-Kutta stages see one smooth flow, and the events end the
  // phase where the law changes piece.
  auto line = [&](double d, double) {
    return joint::EnvelopeForce_N(law, memory.d_max_m) - law.k_ur_N_per_m * (memory.d_max_m - d);
  };
  Eigen::Vector3d y(d_set, approach_speed_mps, 0.0);
  double t = 0.0;
  PhaseEnd end;
  // Reloading along K_ur (when the memory holds an earlier excursion) until d_max or a turn.
  if (memory.d_max_m > d_set) {
    const double d_max = memory.d_max_m;
    end = RunPhase(
        rk, mass_kg, line, [&](double d, double v) { return std::min(d_max - d, v); }, t, y, scales,
        tolerances, result);
    if (!end.located) {
      Finish(result, mass_kg, end);
      return result;
    }
    t = end.t_s;
    y = end.y;
  }
  // Loading on the envelope until the turn; the memory follows the deformation (d >= d_max).
  if (y[kV] > 0.0) {
    auto envelope = [&](double d, double) { return joint::EnvelopeForce_N(law, d); };
    end = RunPhase(
        rk, mass_kg, envelope, [](double, double v) { return v; }, t, y, scales, tolerances,
        result);
    if (!end.located) {
      Finish(result, mass_kg, end);
      return result;
    }
    t = end.t_s;
    y = end.y;
  }
  memory = joint::BackfillCommit(law, memory, law.gap_m + y[kD]);
  result.max_deformation_m = memory.d_max_m;
  result.max_force_N = joint::EnvelopeForce_N(law, memory.d_max_m);  // the peak, exactly
  // Unloading along K_ur until the force is zero.
  end = RunPhase(rk, mass_kg, line, line, t, y, scales, tolerances, result);
  result.permanent_set_m = joint::PermanentSet_m(law, memory);
  Finish(result, mass_kg, end);
  return result;
}

StrikeResult StrikeSpringDashpot(double k_N_per_m, double c_Ns_per_m, double mass_kg,
                                 double approach_speed_mps, const StrikeTolerances& tolerances) {
  SB_DEMAND(k_N_per_m > 0.0 && c_Ns_per_m >= 0.0, "a spring-dashpot needs k > 0, c >= 0");
  SB_DEMAND(mass_kg > 0.0 && approach_speed_mps > 0.0, "a strike needs a mass and a speed");
  StrikeResult result;
  result.approach_speed_mps = approach_speed_mps;
  const Scales scales = MakeScales(mass_kg, k_N_per_m, approach_speed_mps, tolerances);
  DormandPrince45 rk(3);
  // k d + c d' > 0 while loading; after the turn it is continued to its zero, where the joint lets
  // go (the cut at zero is the event, not a kink inside a step).
  auto force = [&](double d, double v) { return k_N_per_m * d + c_Ns_per_m * v; };
  // Loading until the turn, then until the force is zero.
  PhaseEnd end = RunPhase(
      rk, mass_kg, force, [](double, double v) { return v; }, 0.0,
      Eigen::Vector3d(0.0, approach_speed_mps, 0.0), scales, tolerances, result);
  if (end.located) {
    result.max_deformation_m = end.y[kD];
    end = RunPhase(rk, mass_kg, force, force, end.t_s, end.y, scales, tolerances, result);
  }
  Finish(result, mass_kg, end);
  return result;
}

}  // namespace skewbridge::dynamics
