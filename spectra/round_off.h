#pragma once
/// @file
/// The round-off floor of stored responses: a value below it is zero for every fit and figure
/// (jobs/study.cpp reads the responses through it; the final cube stores it as the attribute
/// round_off_floor_rad, docs/fragility.md). Stored responses keep their values.

#include <cmath>
#include <string_view>

namespace skewbridge::spectra {

/// The round-off floor of a rotation (rad). The integrators carry theta beside translations of
/// at most a few metres on decks of several metres or more; one operation's round-off in theta
/// is then of order eps |u| / L <= 2.2e-16 x 1 m / 1 m, and cells with impacts but no physical
/// rotation store 1e-20 to 1e-15 rad after the thousands of operations of a run (a subsystem
/// pushed square into its abutment: 2e-16 to 9e-16 rad). 1e-12 rad is three orders above that
/// and far below any rotation of engineering meaning: it moves a corner of a 100 m deck by
/// 5e-11 m, and rotation limit states lie at 1e-4 to 1e-2 rad.
inline constexpr double kRotationRoundOffFloor_rad = 1e-12;

/// The round-off floor of a response of unit `unit`: kRotationRoundOffFloor_rad for "rad", else
/// 0 (no floor).
inline double RoundOffFloor(std::string_view unit) {
  return unit == "rad" ? kRotationRoundOffFloor_rad : 0.0;
}

/// `value` as the fits read it: 0 when |value| < floor (round-off), else value (NaN stays NaN).
inline double AboveRoundOff(double value, double floor) {
  return std::abs(value) < floor ? 0.0 : value;
}

}  // namespace skewbridge::spectra
