#include "solver/dynamics/event_policy.h"

#include <bit>
#include <cstdint>

namespace skewbridge::dynamics {

void ValidatePolicy(const EventPolicy& policy) { schema::Validate(policy, "event policy"); }

bool SameMembers(const EventPolicy& a, const EventPolicy& b) {
  // Member by member: the padding after each bool, int and the last member is whatever the copy
  // or the stack left there, and a memcmp over it would say unequal for equal policies.
  // A member that fits in the padding leaves sizeof alone; the count of members does not.
  static_assert(schema::MemberCount<EventPolicy>() == 41,
                "SameMembers compares each member: list a new one here");
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  return bits(a.velocity_tolerance) == bits(b.velocity_tolerance) &&
         bits(a.gap_tolerance) == bits(b.gap_tolerance) &&
         bits(a.gap_rounding_ulps) == bits(b.gap_rounding_ulps) &&
         bits(a.force_tolerance) == bits(b.force_tolerance) &&
         bits(a.free_body_omega_radps) == bits(b.free_body_omega_radps) &&
         bits(a.ramp_horizon_s) == bits(b.ramp_horizon_s) &&
         bits(a.steps_per_period) == bits(b.steps_per_period) &&
         bits(a.first_rk_step_divisor) == bits(b.first_rk_step_divisor) &&
         bits(a.omega_floor_radps) == bits(b.omega_floor_radps) &&
         bits(a.nonfinite_step_error) == bits(b.nonfinite_step_error) &&
         bits(a.step_reuse_band) == bits(b.step_reuse_band) &&
         bits(a.step_snap_band) == bits(b.step_snap_band) &&
         a.finite_check_steps == b.finite_check_steps &&
         bits(a.event_time_tolerance) == bits(b.event_time_tolerance) &&
         bits(a.event_time_floor_s) == bits(b.event_time_floor_s) &&
         bits(a.maximum_time_tolerance) == bits(b.maximum_time_tolerance) &&
         bits(a.dip_margin) == bits(b.dip_margin) &&
         bits(a.start_minimum_band) == bits(b.start_minimum_band) &&
         a.touch_probes == b.touch_probes && bits(a.output_time_band) == bits(b.output_time_band) &&
         a.max_events_at_one_instant == b.max_events_at_one_instant &&
         a.decision_passes == b.decision_passes && bits(a.stick_band) == bits(b.stick_band) &&
         a.cone_sign == b.cone_sign && a.tie_bands == b.tie_bands && a.jam == b.jam &&
         bits(a.zeno_ratio) == bits(b.zeno_ratio) && bits(a.zeno_flight) == bits(b.zeno_flight) &&
         bits(a.zeno_flight_at_once) == bits(b.zeno_flight_at_once) &&
         bits(a.rocking_speed) == bits(b.rocking_speed) &&
         a.zeno_extrapolation == b.zeno_extrapolation &&
         a.settle_in_touch_band == b.settle_in_touch_band && a.slow_rocking == b.slow_rocking &&
         a.bounce_at_once == b.bounce_at_once && a.position_passes == b.position_passes &&
         bits(a.one_pass_gap) == bits(b.one_pass_gap) &&
         bits(a.rank_threshold) == bits(b.rank_threshold) &&
         bits(a.kernel_normal_threshold) == bits(b.kernel_normal_threshold) &&
         bits(a.split_total_slack) == bits(b.split_total_slack) &&
         a.open_contacts_in_projection == b.open_contacts_in_projection &&
         contact::SameBytes(a.contact, b.contact);
}

}  // namespace skewbridge::dynamics
