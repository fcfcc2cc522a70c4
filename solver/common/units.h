#pragma once
/// @file
/// The one vocabulary of acceleration units: every place that takes units (`records info
/// --units`, a record set's `units`, a model file's `excitation.units`) reads them here, so the
/// same spellings mean the same factor everywhere.

#include <optional>
#include <string_view>

namespace skewbridge {

/// Standard gravity (m/s^2) used for every g <-> m/s^2 conversion [CGPM 1901].
inline constexpr double kStandardGravity_mps2 = 9.80665;

/// The largest PGA a ground motion may have unless the user raises the bound (g): 10 g, more
/// than twice the largest ever recorded (about 4 g). A motion above it is read in the wrong
/// units (cm/s^2 taken as m/s^2 makes 0.3 g into 30 g).
inline constexpr double kMaxPlausiblePga_g = 10.0;

/// Units of a ground acceleration.
enum class AccelerationUnits { kG, kMetresPerSecond2, kCentimetresPerSecond2 };

/// The factor that turns a value in `units` into m/s^2.
double ToMetresPerSecond2(AccelerationUnits units);

/// Canonical short name of the units: "g", "m/s^2" or "cm/s^2".
std::string_view UnitsName(AccelerationUnits units);

/// Parses a unit spelling, case-insensitive and blanks ignored: "g"; "m/s^2", "m/s2", "m/s/s",
/// "m/sec2", "m/sec^2", "m/sec/sec", "mps2"; "cm/s^2", "cm/s2", "cm/s/s", "cm/sec2",
/// "cm/sec^2", "cm/sec/sec", "gal", "cmps2". std::nullopt when unknown.
std::optional<AccelerationUnits> ParseAccelerationUnits(std::string_view text);

/// The spellings ParseAccelerationUnits takes, for "allowed: ..." in messages.
std::string_view AllowedUnitsText();

}  // namespace skewbridge
