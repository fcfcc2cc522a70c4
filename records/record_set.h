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
/// or, instead of [[record]] tables, a folder and a file-name glob: every matching file, in
/// byte order of the names, labelled by its file name, each with the top-level options:
///
///     name = "greek"
///     folder = "greek/"         # relative to the manifest
///     pattern = "*.AT2"         # *, ? and [...] classes; file names only
///     units = "g"               # optional, as above (a file's header must agree)
///     dt = 0.01                 # optional, as above

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "records/ground_motion.h"

namespace skewbridge::records {

/// One record of a set, as the manifest gives it.
struct RecordEntry {
  std::filesystem::path file;  ///< resolved against the manifest's folder
  std::string label;           ///< user label (default: the file name)
  std::string component;       ///< overrides the header's component when not empty
  double scale = 1.0;          ///< factor applied to the accelerations
  ReadOptions options;         ///< format, dt, units, channel
  long line = 0;               ///< line of the [[record]] table in the manifest
};

/// A named list of records.
struct RecordSet {
  std::string name;                  ///< `name` key, default the manifest's stem
  std::filesystem::path manifest;    ///< where it was read from
  std::vector<RecordEntry> records;  ///< in manifest order, at least one
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
  std::string folder_at;
  std::string pattern_at;
  std::string key_prefix;
};

/// The folder form of a set: every regular file of `folder` whose name matches `pattern`, in
/// byte order of the names, each a copy of `defaults` (options, scale) with its file; labels are
/// the file names. RecordSet::manifest is the folder.
/// @throws InputError "<folder_at>: <prefix>folder: not a folder ...", or at pattern_at for a bad
/// pattern or one that matches no file.
RecordSet MakeFolderSet(const std::filesystem::path& folder, std::string_view pattern,
                        const RecordEntry& defaults, const FolderSetSource& source);

/// Why `pattern` is not a file-name glob ("" when it is one): empty, a '/' in it, or an
/// unclosed '[' class.
std::string GlobProblem(std::string_view pattern);

/// Whether a file name matches a glob: '*' any run of characters, '?' one character,
/// '[abc]', '[a-z]', '[!a]' a class; everything else itself (case-sensitive).
/// @pre GlobProblem(pattern) is empty.
bool GlobMatch(std::string_view pattern, std::string_view name);

/// Reads one entry: ReadRecord with the entry's options, then scale, label and component.
/// @throws InputError from the reader (naming the record file and line).
GroundMotion LoadRecord(const RecordEntry& entry);

/// A display label for a record: the entry label, else the file name.
std::string RecordLabel(const RecordEntry& entry);

}  // namespace skewbridge::records
