#pragma once
/// @file
/// The sweep-specification parser (docs/sweep-format.md), private to jobs/: one object per
/// parse, its member functions defined one TOML table per file: the document and its inputs
/// (sweep_parser.cpp), [sweep] (sweep_parse_sweep.cpp), [records] (sweep_parse_records.cpp),
/// [axes] and [fixed] (sweep_parse_axes.cpp), [limit_states] (sweep_parse_limit_states.cpp),
/// [ida] (sweep_parse_ida.cpp), [study] (sweep_parse_study.cpp) and the rules across tables
/// (sweep_parse_cross_fields.cpp). ParseSweepSpec and LoadSweepSpec (jobs/sweep_spec.h) run it.

#include <fmt/format.h>

#include <toml++/toml.h>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "jobs/sweep_spec.h"
#include "solver/common/error.h"

namespace skewbridge::jobs {

/// "file:line" when the node has a position, else the file: the place for InputError::AtField.
std::string Where(std::string_view source, const toml::source_region& region);

/// A number in its shortest round-trip form, for messages.
inline std::string Fmt(double v) { return fmt::format("{}", v); }

/// Parses one specification text named `source`, its relative paths resolved against
/// `base_dir`; every problem throws InputError naming "source:line: field" and what is allowed.
class SpecParser {
 public:
  /// A parser of the text named `source` (a file name, for messages), paths relative to
  /// `base_dir`.
  SpecParser(std::string_view source, std::filesystem::path base_dir)
      : source_(source), base_dir_(std::move(base_dir)) {}

  /// The validated specification of `text`: every table, the default record axis, the cross-
  /// table rules, the canonical axis order and the checksummed input manifest.
  /// @throws InputError for any problem.
  SweepSpec Parse(std::string_view text);

 private:
  // The document (sweep_parser.cpp).

  /// A model file or a record-set manifest given where a sweep specification belongs is named
  /// as what it is, not by its first table foreign to a specification.
  void RejectOtherKindOfFile(const toml::table& root) const;
  /// The error for `field` at `where`.
  InputError Error(const toml::source_region& where, std::string_view field,
                   std::string_view problem) const;
  /// The non-empty string `table_name.key`.
  std::string RequireString(const toml::table& table, std::string_view table_name,
                            std::string_view key) const;
  /// The path of the existing file `value` given as `table_name.key`, relative to base_dir_.
  std::filesystem::path ExistingFile(const toml::table& table, std::string_view table_name,
                                     std::string_view key, const std::string& value) const;
  /// The name of an input in the cube and the identity: relative to the specification's folder
  /// when it was found from there, so that the identity does not depend on the working folder.
  std::string RelativeName(const std::filesystem::path& path) const;
  /// Reads and checksums one input file (once: a file named twice is listed once).
  void AddInput(SweepSpec& spec, std::string role, const std::filesystem::path& path) const;
  /// The input manifest: every file the cells read, each hashed once here (not per cell).
  void CollectInputs(SweepSpec& spec) const;
  /// Axes and fixed values in the canonical order of KnownParameters().
  static void SortCanonically(SweepSpec& spec);

  // [sweep] (sweep_parse_sweep.cpp).

  /// [sweep]: name, family, model, responses, description.
  void ParseSweepTable(const toml::table& sweep, SweepSpec& spec) const;

  // [records] (sweep_parse_records.cpp).

  /// [records]: a set, a synthetic suite or a folder, and the intensity measure.
  void ParseRecordsTable(const toml::table& records, SweepSpec& spec) const;
  /// [records] scale_to = {measure, period, xi} (stripes) or im = {...} (cloud), and max_scale.
  void ParseIntensityMeasure(const toml::table& records, SweepSpec& spec) const;
  /// [records] folder and pattern: a folder set without a manifest; the folder is listed now,
  /// so a missing folder, a bad pattern or an empty match fails here.
  void ParseRecordFolder(const toml::table& records, SweepSpec& spec) const;
  /// Every label of the spec's record set, in set order ([records] must come first in the file
  /// only as far as TOML goes: tables are parsed before axes whatever their order).
  std::vector<std::string> AllRecordLabels(const SweepSpec& spec, const std::string& field,
                                           const toml::source_region& where) const;

  // [axes] and [fixed] (sweep_parse_axes.cpp).

  /// "; did you mean `a_deg` (skew angle a)?" for the parameter nearest to `word` by its key,
  /// its symbol or the model-file key of the same quantity (skew_deg), or "".
  static std::string NearestParameter(const std::string& word);
  /// The table entry of the parameter `key` given as `field`.
  const ParameterInfo& Known(const std::string& field, const std::string& key,
                             const toml::source_region& where) const;
  /// Checks a number against the parameter's range and wholeness.
  void CheckNumber(const ParameterInfo& p, double v, const std::string& field,
                   const toml::source_region& where) const;
  /// Checks a label against the parameter's choices.
  void CheckLabel(const ParameterInfo& p, const std::string& v, const std::string& field,
                  const toml::source_region& where) const;
  /// The node as a number.
  double Number(const toml::node& node, const std::string& field) const;
  /// One [axes] entry: a list, {linspace = [a, b, n]}, {logspace = [a, b, n]} or record = "*".
  Axis ParseAxis(const std::string& key, const toml::source_region& key_where,
                 const toml::node& node, const SweepSpec& spec) const;
  /// One [fixed] entry.
  FixedValue ParseFixed(const std::string& key, const toml::source_region& key_where,
                        const toml::node& node, const SweepSpec& spec) const;

  // [limit_states] (sweep_parse_limit_states.cpp).

  /// A threshold of a limit state: a finite number >= 0.
  double Threshold(const toml::node& node, const std::string& field, std::string_view unit) const;
  /// A limit state given as `key = {above_<unit> = v}`.
  double Above(const toml::node& node, const std::string& field, std::string_view key) const;
  /// [limit_states] (docs/sweep-format.md): kept in canonical order, the responses by name.
  void ParseLimitStates(const toml::table& limits, SweepSpec& spec) const;

  // [ida] (sweep_parse_ida.cpp) and [study] (sweep_parse_study.cpp).

  /// [ida] (docs/sweep-format.md): the hunt-and-fill search's intensities, in the unit of the
  /// scale_to measure, and its run budget.
  void ParseIda(const toml::table& table, SweepSpec& spec) const;
  /// [study]: the w0x/w_g band edges of the correlation statistics.
  void ParseStudyTable(const toml::table& study, SweepSpec& spec) const;

  // [event_policy] and [time_stepping_policy] (sweep_parse_policies.cpp).

  /// [event_policy]: members of the event-driven integrator's policy by their stored names (a
  /// nested member as a dotted key, contact.tie_tolerance), each checked against its
  /// description.
  void ParseEventPolicy(const toml::table& table, SweepSpec& spec) const;
  /// [time_stepping_policy]: members of Moreau-Jean's policy, as ParseEventPolicy.
  void ParseTimeSteppingPolicy(const toml::table& table, SweepSpec& spec) const;

  // Rules across tables (sweep_parse_cross_fields.cpp).

  /// The parameters that exclude or need each other, and what [ida] needs.
  void CheckCrossFields(const SweepSpec& spec) const;
  /// The intensity axis and [records] scale_to / im belong together (docs/sweep-format.md).
  template <typename Given>
  void CheckIntensityFields(const SweepSpec& spec, const Given& given) const;

  std::string source_;              ///< the specification's name in messages
  std::filesystem::path base_dir_;  ///< where its relative paths start
};

}  // namespace skewbridge::jobs
