#pragma once
/// @file
/// One parser per format: text lines in, GroundMotion (m/s^2) out. Each throws InputError
/// "SOURCE:LINE: problem" for malformed content. The formats are described in docs/records.md.

#include <string_view>
#include <vector>

#include "records/ground_motion.h"
#include "records/readers/text.h"

namespace skewbridge::records::detail {

/// PEER NGA .AT2: free text, then a line with NPTS and DT ("NPTS=  5372, DT= .0100 SEC",
/// "NPTS= 6557, dt= .00244" or "4096  0.0100  NPTS, DT"), then exactly NPTS values.
GroundMotion ParseAt2(const std::vector<Line>& lines, std::string_view source,
                      const ReadOptions& options);

/// ESM / ITACA ASCII: "KEY: value" header (SAMPLING_INTERVAL_S, NDATA, UNITS), then NDATA values.
GroundMotion ParseEsm(const std::vector<Line>& lines, std::string_view source,
                      const ReadOptions& options);

/// ITSAK: "NAME  STATION  N Values" / "(8F15.0)  dt", then N values; values beyond N must be
/// exactly zero (padding to a full line) and are dropped. Units are not stated.
GroundMotion ParseItsak(const std::vector<Line>& lines, std::string_view source,
                        const ReadOptions& options);

/// COSMOS V2 / V2c (v01.20): text lines, integer and real headers (dt = real #62 in ms),
/// comments, "N acceleration pts, ..., units=cm/sec2(04), Format=(...)", N values.
GroundMotion ParseCosmos(const std::vector<Line>& lines, std::string_view source,
                         const ReadOptions& options);

/// CSMIP / CDMG V2: channel blocks; the chosen channel's "N POINTS OF ACCEL DATA EQUALLY
/// SPACED AT dt SEC. (UNITS: CM/SEC/SEC)" block holds exactly N values.
GroundMotion ParseCsmip(const std::vector<Line>& lines, std::string_view source,
                        const ReadOptions& options);

/// USGS SMC: 11 text lines, 48 integers (#16 comment lines, #17 NPTS), 50 reals (#2 samples per
/// second), '|' comment lines, then NPTS values in cm/s^2 (8E10.4, possibly packed).
GroundMotion ParseSmc(const std::vector<Line>& lines, std::string_view source,
                      const ReadOptions& options);

/// GEM strong-motion toolkit .cor.acc: "Key : value" header (Time Increment (s), Number of
/// Data), a units line "... time series in m/s/s", then the values (E14.7, packed).
GroundMotion ParseSmtk(const std::vector<Line>& lines, std::string_view source,
                       const ReadOptions& options);

/// Headerless values, one or several per line, read in order; dt and units from the user.
GroundMotion ParsePlainText(const std::vector<Line>& lines, std::string_view source,
                            const ReadOptions& options);

/// Headerless (time, acceleration) pairs on a uniform time grid; units from the user.
GroundMotion ParseTimeSeries(const std::vector<Line>& lines, std::string_view source,
                             const ReadOptions& options);

/// Reads every number of lines[first, lines.size()) (blank lines allowed).
/// @returns the line number of the last non-blank line read (0 when none).
long ReadValues(const std::vector<Line>& lines, std::size_t first, std::string_view source,
                std::vector<double>& out);

/// Throws "SOURCE:LINE: header declares NPTS = n but the file holds m values" unless equal.
void RequireCount(std::size_t declared, std::size_t found, std::string_view source,
                  long header_line, std::string_view what = "NPTS");

}  // namespace skewbridge::records::detail
