#pragma once
/// @file
/// Record sets: a TOML manifest that names a suite of records as one thing ("the 62-record
/// set"), with per-record component, scale factor, label and the dt/units that headerless files
/// need. Paths are relative to the manifest.
///
///     name = "greek-62"
///     [[record]]
///     file = "records/A299_T"   # required
///     label = "Athens 1999 T"   # default: the file name
///     component = "T"           # default: the header's
///     scale = 1.0               # default 1; multiplies the accelerations
///     units = "g"               # g | m/s^2 | cm/s^2; required where the file states none
///     dt = 0.005                # s; required for headerless one- or multi-value files
///     format = "itsak"          # default: detected by content
///     channel = 1               # CSMIP V2 channel
///
/// A [[record]] table may instead name a pair, the two horizontal components of one station
/// (h1 and h2 in place of file; component_h1, component_h2 default to the headers'; the other
/// keys apply to both files):
///
///     [[record]]
///     label = "RSN107"          # default: the common start of the two file names
///     h1 = "RSN107_OROVILLE_B-OAP180.AT2"
///     h2 = "RSN107_OROVILLE_B-OAP270.AT2"
///
/// or, instead of [[record]] tables, a folder and a file-name glob: every matching file, in
/// byte order of the names, labelled by its file name, each with the top-level options:
///
///     name = "greek"
///     folder = "greek/"         # relative to the manifest
///     pattern = "*.AT2"         # *, ? and [...] classes; file names only
///     units = "g"               # optional, as above (a file's header must agree)
///     dt = 0.01                 # optional, as above
///     pairs = "PAIRS.csv"       # optional: the matching files are pairs, named by a CSV table
///                               # of the folder (h1_file, h2_file, pair), or true: paired by
///                               # name (PairsByName), H1 the first in byte order

#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "records/ground_motion.h"

namespace skewbridge::records {

/// One record of a set, as the manifest gives it: a single component, or a pair (H1 and H2).
struct RecordEntry {
  std::filesystem::path file;     ///< resolved against the manifest's folder; a pair's H1 file
  std::string label;              ///< user label (default: the file name, for a pair see PairLabel)
  std::string component;          ///< overrides the (H1) header's component when not empty
  double scale = 1.0;             ///< factor applied to the accelerations (both of a pair)
  ReadOptions options;            ///< format, dt, units, channel (both of a pair)
  long line = 0;                  ///< line of the [[record]] table in the manifest
  std::filesystem::path file_h2;  ///< a pair's H2 file, resolved; empty for a single record
  std::string component_h2;       ///< overrides the H2 header's component when not empty

  /// Whether the entry is a pair of horizontal components (h1 and h2 in the manifest).
  bool IsPair() const { return !file_h2.empty(); }
};

/// The components of one record-set entry, ready for a two-component consumer: one motion for
/// a single record; H1 and H2 of one dt and one length for a pair (the shorter padded with zeros
/// at its end).
struct RecordComponents {
  std::vector<GroundMotion> motions;  ///< {record} or {H1, H2}, scaled and labelled
  /// Zero samples appended at the end of motions[k] to reach the pair's common length.
  std::array<std::size_t, 2> padded_samples{0, 0};

  /// Whether the entry was a pair.
  bool IsPair() const { return motions.size() == 2; }
};

/// A named list of records.
struct RecordSet {
  std::string name;                  ///< `name` key, default the manifest's stem
  std::filesystem::path manifest;    ///< where it was read from
  std::vector<RecordEntry> records;  ///< in manifest order, at least one
  /// The CSV table that named a folder set's pairs (an input of what the set drives, as the
  /// manifest is); empty otherwise.
  std::filesystem::path pairs_table;
};

/// Reads a record-set manifest (TOML).
/// @throws InputError "MANIFEST:LINE: problem" for a syntax error, an unknown key, a missing or
/// mistyped field, a non-positive scale or dt, unknown units or format, no [[record]], or two
/// records of one label (given or defaulted to the file name); for the folder form, a missing
/// folder, a bad pattern or a pattern that matches no file.
RecordSet LoadRecordSet(const std::filesystem::path& manifest);

/// Where a folder set's folder and pattern were given, for messages: "FILE:LINE" of each and
/// the prefix of the key names ("" in a manifest, "records." in a sweep specification).
struct FolderSetSource {
  std::string folder_at;   ///< "FILE:LINE" of folder
  std::string pattern_at;  ///< "FILE:LINE" of pattern
  std::string key_prefix;  ///< "" or "records."
  std::string pairs_at;    ///< "FILE:LINE" of pairs, when given
};

/// How the files of a folder set make record pairs (two horizontal components of one station).
struct FolderPairs {
  bool by_name = false;         ///< pairs = true: PairsByName, H1 the first in byte order
  std::filesystem::path table;  ///< pairs = "FILE.csv": the table, resolved; empty: none
  bool Any() const { return by_name || !table.empty(); }  ///< whether the files are pairs
};

/// The folder form of a set: every regular file of `folder` whose name matches `pattern`, in
/// byte order of the names, each a copy of `defaults` (options, scale) with its file; labels are
/// the file names. With `pairs`, the matching files are taken two by two as record pairs
/// (docs/records.md): by name (in byte order of the H1 names, labelled by PairLabel), or as the
/// rows of the table name them (in row order, labelled by its `pair` column when it has one);
/// the table itself is never a record. RecordSet::manifest is the folder.
/// @throws InputError "<folder_at>: <prefix>folder: not a folder ...", or at pattern_at for a bad
/// pattern or one that matches no file; at pairs_at for a file that pairs with none or with more
/// than one, a missing or unreadable table; "TABLE:LINE: ..." for a row naming a missing file,
/// a file of another row, or one file that matches the pattern and one that does not.
RecordSet MakeFolderSet(const std::filesystem::path& folder, std::string_view pattern,
                        const RecordEntry& defaults, const FolderSetSource& source,
                        const FolderPairs& pairs = {});

/// Whether two file names are the two horizontal components of one station by name: they
/// differ in one run of characters, not empty in either, that holds no '_', '-', '.' or blank
/// ("RSN107_OROVILLE_B-OAP180.AT2" and "...OAP270.AT2", "...CHY027-E.AT2" and "...CHY027-N.AT2").
bool PairsByName(std::string_view a, std::string_view b);

/// Why `pattern` is not a file-name glob ("" when it is one): empty, a '/' in it, or an
/// unclosed '[' class.
std::string GlobProblem(std::string_view pattern);

/// Whether a file name matches a glob: '*' any run of characters, '?' one character,
/// '[abc]', '[a-z]', '[!a]' a class; everything else itself (case-sensitive).
/// @pre GlobProblem(pattern) is empty.
bool GlobMatch(std::string_view pattern, std::string_view name);

/// Reads one single-record entry: ReadRecord with the entry's options, then scale, label and
/// component.
/// @throws InputError from the reader (naming the record file and line), or for a pair (which
/// has two components: LoadComponents).
GroundMotion LoadRecord(const RecordEntry& entry);

/// Reads every component of an entry (LoadRecord for a single record; both files of a pair with
/// the entry's options and scale, made one dt and one length by MatchPair).
/// @throws InputError from the readers, or as MatchPair.
RecordComponents LoadComponents(const RecordEntry& entry);

/// Makes two horizontal components of one station a pair of one length: the shorter is padded
/// with zeros at its end (said in its GroundMotion::notes and in padded_samples).
/// @throws InputError naming both files when their time steps differ (by more than 1e-9
/// relative: the headers state one number).
RecordComponents MatchPair(GroundMotion h1, GroundMotion h2);

/// A display label for a record: the entry label, else the file name (PairLabel for a pair).
std::string RecordLabel(const RecordEntry& entry);

/// The default label of a pair: the common start of the two file names without a trailing
/// '_', '-', '.' or blank ("RSN107_OROVILLE_B-OAP" of ...OAP180.AT2 and ...OAP270.AT2), or the
/// H1 file name when they share none.
std::string PairLabel(const std::filesystem::path& h1, const std::filesystem::path& h2);

}  // namespace skewbridge::records
