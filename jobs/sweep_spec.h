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

#include "records/record_set.h"

namespace skewbridge::jobs {

/// Whether a parameter takes numbers or text labels (pulse shape, record label).
enum class ParameterKind { kNumber, kLabel };

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

/// One axis of the grid: numbers (values) or labels, never both.
struct Axis {
  std::string key;  ///< A KnownParameters() key.
  ParameterKind kind = ParameterKind::kNumber;
  std::vector<double> values;       ///< Coordinates of a numeric axis, in the given order.
  std::vector<std::string> labels;  ///< Coordinates of a label axis.
  std::string spacing;  ///< "list", "linspace", "logspace" or "all" (record = "*" or implied).
  /// Number of coordinates (>= 1 after validation).
  std::size_t Size() const {
    return kind == ParameterKind::kNumber ? values.size() : labels.size();
  }
};

/// A parameter held constant over the sweep.
struct FixedValue {
  std::string key;  ///< A KnownParameters() key.
  ParameterKind kind = ParameterKind::kNumber;
  double value = 0.0;  ///< For numbers.
  std::string label;   ///< For labels.
};

/// A validated sweep specification. Axes are kept in the canonical order of KnownParameters(),
/// whatever the order in the file, so equal specifications give equal cube layouts.
struct SweepSpec {
  std::string source;                ///< Where it came from (file name), for messages.
  std::string text;                  ///< The original text, stored verbatim in the cube.
  std::string name;                  ///< [sweep] name: the HDF5 group name.
  std::string family;                ///< One of KnownFamilies().
  std::string model_file;            ///< [sweep] model, as written (family "model-file" only).
  std::filesystem::path model_path;  ///< model_file resolved against the spec's folder.
  /// FNV-1a hash (16 hex digits) of the model file's bytes when it was read: part of the
  /// identity, so that --resume refuses a cube of a model file that has changed since.
  std::string model_hash;
  std::string record_set;                 ///< [records] set, as written, or empty.
  std::filesystem::path record_set_path;  ///< record_set resolved against the spec's folder.
  /// [records] folder and pattern: a set of every matching file, without a manifest
  /// (records::MakeFolderSet); empty when not given.
  std::string record_folder;
  std::filesystem::path record_folder_path;  ///< record_folder resolved against the spec's folder.
  std::string record_pattern;                ///< [records] pattern, a file-name glob.
  std::string record_units;                  ///< [records] units for files stating none, or "".
  double record_dt_s = 0.0;                  ///< [records] dt for files stating none, or 0.
  std::string record_folder_at;              ///< "spec.toml:LINE" of folder, for messages.
  std::string record_pattern_at;             ///< "spec.toml:LINE" of pattern, for messages.
  /// [records] synthetic = {count, seed}: a suite made in memory (records::SynthesizeSuite)
  /// instead of a manifest; count 0 when not given.
  int synthetic_count = 0;
  std::uint64_t synthetic_seed = 0;  ///< The suite's seed (labels "synth-<seed>-<index>").
  /// [study] bands: increasing, positive w0x/w_g edges of the frequency-ratio groups; empty
  /// when not given (the evaluator then uses 0.5, 1, 2) [docs/theory.md §6].
  std::vector<double> study_bands;
  std::vector<Axis> axes;
  std::vector<FixedValue> fixed;
  std::vector<std::string> responses;  ///< Requested responses; empty = all of the evaluator's.

  /// The number of coordinates per axis, in axis order.
  std::vector<std::size_t> Shape() const;
  /// Product of the axis sizes (1 for a sweep without axes), UINT64_MAX when it overflows.
  std::uint64_t CellCount() const;
  /// Axis indices of the cell with row-major linear index `cell` (last axis fastest).
  /// @pre cell < CellCount()
  std::vector<std::size_t> AxisIndex(std::uint64_t cell) const;
  /// The axis with this key, or nullptr.
  const Axis* FindAxis(std::string_view key) const;
  /// The fixed value with this key, or nullptr.
  const FixedValue* FindFixed(std::string_view key) const;
  /// A normalised text of the specification (fixed key order, shortest round-trip numbers,
  /// expanded linspace/logspace): equal for specifications that define the same sweep.
  std::string CanonicalText() const;
  /// 16 hex digits of the 64-bit FNV-1a hash of CanonicalText(): the resume identity.
  std::string Hash() const;
};

/// The record set a spec names: its manifest ([records] set) or its folder and pattern.
/// @throws InputError from the manifest, or naming the spec's records.folder / records.pattern.
records::RecordSet LoadSpecRecordSet(const SweepSpec& spec);

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
