#include "solver/dynamics/event_policy.h"

#include <fmt/format.h>

#include <string_view>

#include "solver/common/error.h"

namespace skewbridge::dynamics {

std::vector<EventPolicyEntry> EventPolicyEntries(const EventPolicy& p) {
  const auto real = [](const char* name, double value, const char* unit, const char* of) {
    return EventPolicyEntry{name, value, false, unit, of};
  };
  const auto count = [](const char* name, double value) {
    return EventPolicyEntry{name, value, true, "1", ""};
  };
  const auto rule = [](const char* name, bool on) {
    return EventPolicyEntry{name, on ? 1.0 : 0.0, true, "1", ""};
  };
  return {
      real("velocity_tolerance", p.velocity_tolerance, "1", "v_ref"),
      real("gap_tolerance", p.gap_tolerance, "1", "min(v_ref / omega_ref, L)"),
      real("gap_rounding_ulps", p.gap_rounding_ulps, "ulp", "L"),
      real("force_tolerance", p.force_tolerance, "1", "m_max v_ref omega_ref"),
      real("free_body_omega_radps", p.free_body_omega_radps, "rad/s", ""),
      real("ramp_horizon_s", p.ramp_horizon_s, "s", ""),
      real("steps_per_period", p.steps_per_period, "1", "2 pi / omega_max"),
      real("first_rk_step_divisor", p.first_rk_step_divisor, "1", "free step"),
      real("omega_floor_radps", p.omega_floor_radps, "rad/s", ""),
      real("nonfinite_step_error", p.nonfinite_step_error, "1", "error norm"),
      real("step_reuse_band", p.step_reuse_band, "1", "free step"),
      real("step_snap_band", p.step_snap_band, "1", "free step"),
      count("finite_check_steps", static_cast<double>(p.finite_check_steps)),
      real("event_time_tolerance", p.event_time_tolerance, "1", "max(1 s, |t|)"),
      real("event_time_floor_s", p.event_time_floor_s, "s", ""),
      real("maximum_time_tolerance", p.maximum_time_tolerance, "1", "max(1 s, |t|)"),
      real("dip_margin", p.dip_margin, "1", "Hermite bound of the dip"),
      real("start_minimum_band", p.start_minimum_band, "1", "event-time bracket"),
      count("touch_probes", p.touch_probes),
      real("output_time_band", p.output_time_band, "1", "max(1 s, |t|)"),
      count("max_events_at_one_instant", p.max_events_at_one_instant),
      count("decision_passes", p.decision_passes),
      real("stick_band", p.stick_band, "1", "v_tol"),
      rule("cone_sign", p.cone_sign),
      rule("tie_bands", p.tie_bands),
      rule("jam", p.jam),
      real("zeno_ratio", p.zeno_ratio, "1", "previous approach speed"),
      real("zeno_flight", p.zeno_flight, "1", "shortest natural period"),
      real("zeno_flight_at_once", p.zeno_flight_at_once, "1", "shortest natural period"),
      real("rocking_speed", p.rocking_speed, "1", "v_acc"),
      rule("zeno_extrapolation", p.zeno_extrapolation),
      rule("settle_in_touch_band", p.settle_in_touch_band),
      rule("slow_rocking", p.slow_rocking),
      rule("bounce_at_once", p.bounce_at_once),
      count("position_passes", p.position_passes),
      real("one_pass_gap", p.one_pass_gap, "1", "L"),
      real("rank_threshold", p.rank_threshold, "1", "largest pivot"),
      real("kernel_normal_threshold", p.kernel_normal_threshold, "1", "orthonormal kernel"),
      real("split_total_slack", p.split_total_slack, "1", "largest force"),
      rule("open_contacts_in_projection", p.open_contacts_in_projection),
      real("contact.tie_tolerance", p.contact.tie_tolerance, "1",
           "largest sum of the magnitudes of the terms of b"),
      real("contact.contact_compliance", p.contact.contact_compliance, "1",
           "largest normal diagonal entry"),
      real("contact.impact_compliance", p.contact.impact_compliance, "1",
           "largest normal diagonal entry"),
      count("contact.enumeration_unknowns", p.contact.enumeration_unknowns),
  };
}

void ValidatePolicy(const EventPolicy& p) {
  const auto refuse = [](std::string_view member, std::string_view allowed, auto value) {
    throw InputError::AtField("event policy", member,
                              fmt::format("must be {} (got {})", allowed, value));
  };
  if (p.finite_check_steps < 1 || (p.finite_check_steps & (p.finite_check_steps - 1)) != 0) {
    refuse("finite_check_steps", "a power of two (1, 2, 4, ...)", p.finite_check_steps);
  }
  if (p.decision_passes < 1) {
    refuse("decision_passes", "at least 1", p.decision_passes);
  }
  if (p.position_passes < 1) {
    refuse("position_passes", "at least 1", p.position_passes);
  }
  if (!(p.steps_per_period >= 1.0)) {
    refuse("steps_per_period", "at least 1", p.steps_per_period);
  }
  if (p.touch_probes < 0) {
    refuse("touch_probes", "at least 0", p.touch_probes);
  }
  if (p.max_events_at_one_instant < 0) {
    refuse("max_events_at_one_instant", "at least 0", p.max_events_at_one_instant);
  }
}

}  // namespace skewbridge::dynamics
