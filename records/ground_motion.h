#pragma once
/// @file
/// A uniformly sampled horizontal ground acceleration with its metadata, and the entry point
/// that reads one from any of the supported strong-motion formats (docs/records.md).

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "solver/common/units.h"

namespace skewbridge::records {

/// Standard gravity (m/s^2) used for every g <-> m/s^2 conversion [CGPM 1901].
inline constexpr double kStandardGravity_mps2 = skewbridge::kStandardGravity_mps2;

/// Acceleration units found in record files: the one vocabulary of solver/common/units.h.
using Units = AccelerationUnits;
using skewbridge::ToMetresPerSecond2;
using skewbridge::UnitsName;

/// Parses a unit spelling (ParseAccelerationUnits: "g", "m/s2", "m/s^2", "mps2", "cm/s2",
/// "gal", ...; case-insensitive); std::nullopt when unknown.
inline std::optional<Units> ParseUnits(std::string_view text) {
  return ParseAccelerationUnits(text);
}

/// The file formats the readers understand; kAuto asks for detection by content.
enum class Format {
  kAuto,
  kAt2,         ///< PEER NGA-West1/West2 .AT2 (4-line header, NPTS/DT line)
  kEsm,         ///< ESM / ITACA ASCII ("KEY: value" header)
  kItsak,       ///< ITSAK ("NAME ... N Values" / "(8F15.0) dt")
  kCosmos,      ///< COSMOS V2 / V2c (v01.20 headers)
  kCsmip,       ///< CSMIP / CDMG V2 (channels of accel, veloc, displ blocks)
  kSmc,         ///< USGS SMC (8E10.4 packed data)
  kSmtk,        ///< GEM strong-motion toolkit .cor.acc ("Key : value" header, E14.7 packed)
  kPlainText,   ///< headerless values, one or several per line, dt and units from the user
  kTimeSeries,  ///< headerless (time, acceleration) pairs, units from the user
};

/// Short lower-case name of a format ("at2", "esm", ...), as accepted by ParseFormat.
std::string_view FormatName(Format format);

/// Parses a format name (see FormatName, plus "auto"); std::nullopt when unknown.
std::optional<Format> ParseFormat(std::string_view text);

/// The largest PGA a record may have unless the user raises the bound (g), solver/common/units.h.
inline constexpr double kMaxPlausiblePga_g = skewbridge::kMaxPlausiblePga_g;

/// What the user knows that a file may not say. A value given here that contradicts the file's
/// own header is an error, never silently preferred.
struct ReadOptions {
  Format format = Format::kAuto;  ///< kAuto: detect by content (extensions are not trusted)
  std::optional<double> dt_s;     ///< required for headerless one- or multi-value files
  std::optional<Units> units;     ///< required where the file states none
  int channel = 1;                ///< CSMIP V2 channel (1-based) when a file holds several
  /// The PGA above which the record is refused as implausible for its units (g; +inf: no
  /// bound): `--max-pga-g` of `records info`, `max_pga_g` of a record set.
  double max_pga_g = kMaxPlausiblePga_g;
};

/// One horizontal component, uniformly sampled from t = 0.
struct GroundMotion {
  std::string file;              ///< path as given to the reader
  std::string format;            ///< FormatName of the format read
  std::string event;             ///< as stated by the header ("" when none)
  std::string station;           ///< as stated by the header ("" when none)
  std::string component;         ///< as stated by the header ("" when none)
  std::string original_units;    ///< UnitsName of the units in the file
  double dt_s = 0.0;             ///< sample interval (s), > 0
  std::vector<double> acc_mps2;  ///< accelerations (m/s^2), finite, at least one
  /// What the reader accepted that a user should know, "FILE:LINE: remark" (e.g. samples
  /// beyond an ITSAK header's count); `records info` prints them.
  std::vector<std::string> notes;

  /// Number of samples.
  std::size_t npts() const { return acc_mps2.size(); }
};

/// Detects the format of a record from its text (never from the file name).
/// @returns kPlainText / kTimeSeries for headerless numeric files.
/// @throws InputError naming `source` when the content matches no known format.
Format DetectFormat(std::string_view text, std::string_view source);

/// Parses a record held in memory; `source` names it in error messages.
/// @throws InputError "SOURCE:LINE: problem" for any malformed content: an NPTS that does not
/// match the values, a non-numeric token, a missing or non-positive dt, a NaN, an empty file,
/// unknown or missing units, a PGA above options.max_pga_g. Nothing is truncated or padded.
GroundMotion ParseRecord(std::string_view text, std::string_view source,
                         const ReadOptions& options = {});

/// Reads a record file (any supported format).
/// @throws InputError when the file cannot be read or is malformed (see ParseRecord).
GroundMotion ReadRecord(const std::filesystem::path& path, const ReadOptions& options = {});

}  // namespace skewbridge::records
