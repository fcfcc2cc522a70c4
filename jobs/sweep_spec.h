#pragma once
/// @file
/// The sweep specification (docs/sweep-format.md): a TOML file naming a family of models, the
/// axes of a grid of dimensionless parameters, fixed values for the other parameters and the
/// responses to store. Everything is validated here, before any work.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "spectra/grid.h"

namespace skewbridge::jobs {

// The grid types belong to spectra (an evaluator reads them); the specification uses them.
using spectra::Axis;
using spectra::FixedValue;
using spectra::ParameterKind;

/// One entry of the table of known axis / fixed names (jobs/sweep_spec.cpp, KnownParameters).
struct ParameterInfo {
  std::string_view key;          ///< TOML key and HDF5 scale name, e.g. "w0_over_wg".
  std::string_view symbol;       ///< Display symbol, also accepted as a quoted key: "w0/w_g".
  std::string_view unit;         ///< "1" for dimensionless, "deg" for the skew angle.
  std::string_view description;  ///< One line, with the definition [docs/theory.md §5].
  ParameterKind kind;
  double min;                ///< Lower bound for numbers.
  bool min_inclusive;        ///< Whether min itself is allowed.
  double max;                ///< Upper bound for numbers.
  bool max_inclusive;        ///< Whether max itself is allowed.
  bool integer;              ///< Numbers must be whole (number of spans).
  std::string_view choices;  ///< For labels: allowed values separated by '|'; empty = any.
};

/// The table of known parameters, in canonical axis order (the last axis varies fastest in the
/// cube, so w0_over_wg, listed last, is contiguous in memory and in the HDF5 chunks).
std::span<const ParameterInfo> KnownParameters();

/// The entry whose key or symbol is `name`, or nullptr.
const ParameterInfo* FindParameter(std::string_view name);

/// The sweep families known to the specification parser (an evaluator may support fewer).
std::span<const std::string_view> KnownFamilies();

/// A validated sweep specification: the grid the evaluator reads, plus what the sweep machinery
/// alone needs. Axes are kept in the canonical order of KnownParameters(), whatever the order in
/// the file, so equal specifications give equal cube layouts.
struct SweepSpec : spectra::CellGrid {
  std::string text;  ///< The original text, stored verbatim in the cube.
  std::string name;  ///< [sweep] name: the HDF5 group name.
  /// FNV-1a hash (16 hex digits) of the model file's bytes when it was read: part of the
  /// identity, so that --resume refuses a cube of a model file that has changed since.
  std::string model_hash;
  std::vector<std::string> responses;  ///< Requested responses; empty = all of the evaluator's.

  /// A normalised text of the specification (fixed key order, shortest round-trip numbers,
  /// expanded linspace/logspace): equal for specifications that define the same sweep.
  std::string CanonicalText() const;
  /// 16 hex digits of the 64-bit FNV-1a hash of CanonicalText(): the resume identity.
  std::string Hash() const;
};

/// Parses and validates a specification held in memory; relative paths (model, record set) are
/// resolved against base_dir and must exist.
/// @throws InputError naming "source:line: key" and what is allowed, for any problem.
SweepSpec ParseSweepSpec(std::string_view text, std::string_view source,
                         const std::filesystem::path& base_dir);

/// Reads and parses a specification file. @throws InputError (unreadable file, bad content).
SweepSpec LoadSweepSpec(const std::filesystem::path& file);

/// Coordinates of `{linspace = [a, b, n]}`: a + (b - a) i / (n - 1), the end points exact.
/// @pre n >= 1
std::vector<double> Linspace(double a, double b, std::size_t n);

/// Coordinates of `{logspace = [a, b, n]}` given as values (not decades), geometrically spaced:
/// a (b / a)^(i / (n - 1)), the end points exact. @pre a > 0, b > 0, n >= 1
std::vector<double> Logspace(double a, double b, std::size_t n);

}  // namespace skewbridge::jobs
