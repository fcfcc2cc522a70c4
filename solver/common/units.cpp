#include "solver/common/units.h"

#include <cctype>
#include <string>

namespace skewbridge {

double ToMetresPerSecond2(AccelerationUnits units) {
  switch (units) {
    case AccelerationUnits::kG:
      return kStandardGravity_mps2;
    case AccelerationUnits::kMetresPerSecond2:
      return 1.0;
    case AccelerationUnits::kCentimetresPerSecond2:
      return 0.01;
  }
  return 1.0;
}

std::string_view UnitsName(AccelerationUnits units) {
  switch (units) {
    case AccelerationUnits::kG:
      return "g";
    case AccelerationUnits::kMetresPerSecond2:
      return "m/s^2";
    case AccelerationUnits::kCentimetresPerSecond2:
      return "cm/s^2";
  }
  return "?";
}

std::optional<AccelerationUnits> ParseAccelerationUnits(std::string_view text) {
  std::string s;
  for (char c : text) {
    if (!std::isspace(static_cast<unsigned char>(c))) {
      s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
  }
  if (s == "g") return AccelerationUnits::kG;
  for (std::string_view m : {"m/s2", "m/s^2", "m/s/s", "m/sec2", "m/sec^2", "m/sec/sec", "mps2"}) {
    if (s == m) return AccelerationUnits::kMetresPerSecond2;
  }
  for (std::string_view cm :
       {"cm/s2", "cm/s^2", "cm/s/s", "cm/sec2", "cm/sec^2", "cm/sec/sec", "gal", "cmps2"}) {
    if (s == cm) return AccelerationUnits::kCentimetresPerSecond2;
  }
  return std::nullopt;
}

std::string_view AllowedUnitsText() {
  return "g, m/s^2 (or m/s2, mps2), cm/s^2 (or cm/s2, gal, cmps2)";
}

}  // namespace skewbridge
