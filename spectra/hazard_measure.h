#pragma once
/// @file
/// Whether a hazard curve measures what a fragility's intensity measure measures: the same
/// quantity (PGA, or SA at the same damping), a period within a stated tolerance, and the same
/// horizontal component, or a component conversion the user asks for by name, each with its
/// source and what it neglects. A mismatch is refused with one line naming both measures.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "spectra/hazard_curve.h"

namespace skewbridge::spectra {

/// The relative period gap |T_hazard - T_fragility| / T_fragility accepted by default: 5 %
/// admits a period rounded to two digits (a hazard at SA(0.35) for T1 = 0.349 s, 0.3 % apart)
/// but not the neighbouring period of a hazard model's list (0.3 and 0.4 s are 14 and 15 % from
/// 0.349 s).
inline constexpr double kDefaultPeriodTolerance = 0.05;

/// The damping ratios of hazard and fragility must agree to this (absolute, 1): no damping
/// scaling is applied.
inline constexpr double kDampingTolerance = 1e-6;

/// The horizontal component every skewbridge cell applies: one recorded component (a record is
/// one horizontal component, records/ground_motion.h, scaled by its own spectral ordinate), so a
/// fragility's IM is that of an arbitrary component [Baker and Cornell 2006].
inline constexpr HorizontalComponent kRecordComponent = HorizontalComponent::kArbitrary;

/// A conversion of a hazard curve's horizontal component to the fragility's, applied only when
/// asked for by name: the hazard's levels are multiplied by `median_ratio`.
struct ComponentConversion {
  std::string_view name;     ///< as the option --convert spells it
  HorizontalComponent from;  ///< the hazard's component
  HorizontalComponent to;    ///< the fragility's component
  double median_ratio;       ///< median of `to` over median of `from`, applied to the levels
  std::string_view source;   ///< the reference and what the conversion neglects
};

/// Every conversion --convert knows.
std::span<const ComponentConversion> ComponentConversions();

/// The outcome of a check that passed: how far apart the periods are and the conversion used.
struct MeasureMatch {
  double period_gap = 0.0;                          ///< |T_h - T_f| / T_f (0 for PGA)
  const ComponentConversion* conversion = nullptr;  ///< the conversion applied, or none
  double im_factor = 1.0;  ///< multiply the hazard's levels by this to read them as the fragility's
  std::vector<std::string> notes;  ///< what the match assumes, one sentence each
};

/// Checks that `hazard` measures `fragility`: the same measure (PGA with PGA, SA with SA), for
/// SA a damping within kDampingTolerance and periods within `period_tolerance` (relative), and
/// the same component unless `conversion` names one from the hazard's component to the
/// fragility's.
/// @throws InputError with one line naming both measures when they differ in measure, damping,
/// period beyond the tolerance, or component without a matching conversion; when the hazard
/// states no component; when `conversion` is unknown or converts other components.
MeasureMatch MatchMeasures(const IntensityMeasureId& hazard, const IntensityMeasureId& fragility,
                           double period_tolerance, std::string_view conversion);

}  // namespace skewbridge::spectra
