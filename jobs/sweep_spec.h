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

/// One entry of the table of known axis / fixed names (jobs/sweep_parameters.cpp, KnownParameters).
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

/// One file a sweep's results depend on, read when the specification is loaded.
struct InputFile {
  /// "spec", "model", "excitation" (the model file's excitation.file), "record-set" (a
  /// manifest) or "record".
  std::string role;
  /// The path relative to the specification's folder ('/'-separated; absolute paths as given):
  /// the name stored in the cube and in the identity, whatever the working directory.
  std::string file;
  std::filesystem::path path;  ///< Where it was read from (for messages).
  std::string sha256;          ///< SHA-256 of its bytes (64 hex digits), as sha256sum prints it.
  std::uint64_t bytes = 0;     ///< Its size [bytes].
};

/// A validated sweep specification: the grid the evaluator reads, plus what the sweep machinery
/// alone needs. Axes are kept in the canonical order of KnownParameters(), whatever the order in
/// the file, so equal specifications give equal cube layouts.
struct SweepSpec : spectra::CellGrid {
  std::string text;  ///< The original text, stored verbatim in the cube.
  std::string name;  ///< [sweep] name: the HDF5 group name.
  /// Every file the results depend on: the specification itself first, then the model file,
  /// its excitation file, the record-set manifest and each record file the sweep reads, once
  /// each, checksummed once per sweep when the specification is loaded.
  std::vector<InputFile> inputs;
  std::vector<std::string> responses;  ///< Requested responses; empty = all of the evaluator's.

  /// A normalised text of the specification (fixed key order, shortest round-trip numbers,
  /// expanded linspace/logspace): equal for specifications that define the same sweep.
  std::string CanonicalText() const;
  /// The input manifest: the program's result-affecting version (the project VERSION) and one
  /// line `ROLE "FILE" = SHA256` per input other than the specification (whose keys
  /// CanonicalText holds, comments and formatting aside).
  std::string InputsText() const;
  /// 16 hex digits of the 64-bit FNV-1a hash of CanonicalText() + InputsText(): the resume
  /// identity, which changes with any key of the specification and any byte of an input.
  std::string Hash() const;
};

/// Why a cube computed with the specification text `stored_canonical` and the input manifest
/// `stored_inputs` (CanonicalText and InputsText when it was begun) cannot be continued by
/// `spec`, in a few words naming the first key of the specification that differs (with both
/// values) or else the first input file that changed; "" when both are equal.
std::string DescribeIdentityChange(const std::string& stored_canonical,
                                   const std::string& stored_inputs, const SweepSpec& spec);

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
