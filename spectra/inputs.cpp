#include "spectra/inputs.h"

#include <optional>
#include <set>
#include <system_error>

#include "records/record_set.h"
#include "solver/common/error.h"
#include "solver/common/file_kind.h"
#include "solver/model/model_file.h"
#include "spectra/study.h"

namespace skewbridge::spectra {

std::vector<GridInput> GridInputFiles(const CellGrid& grid) {
  std::vector<GridInput> out;
  std::set<std::filesystem::path> seen;  // normal forms of the paths in `out`
  auto add = [&out, &seen](const char* role, const std::filesystem::path& path) {
    if (seen.insert(path.lexically_normal()).second) out.push_back({role, path});
  };
  if (!grid.model_path.empty()) {
    add("model", grid.model_path);
    std::optional<model::ModelFile> file;
    try {
      file.emplace(model::ParseModelFile(grid.model_path));
    } catch (const InputError&) {
      // reported by the evaluator, with the sweep's context
    }
    if (file && !file->excitation.file.empty()) {
      std::error_code ec;
      if (!std::filesystem::is_regular_file(file->excitation.file, ec)) {
        throw InputError::AtLine(
            grid.model_path.string(), 0,
            "excitation.file: file not found: " + file->excitation.file.string());
      }
      add("excitation", file->excitation.file);
    }
  }
  if (grid.synthetic_count > 0) return out;  // made in memory from count and seed
  std::vector<std::string> wanted;
  if (const Axis* axis = grid.FindAxis("record")) wanted = axis->labels;
  if (const FixedValue* fixed = grid.FindFixed("record")) wanted = {fixed->label};
  if (wanted.empty()) return out;
  if (!grid.record_set_path.empty()) add("record-set", grid.record_set_path);
  std::optional<records::RecordSet> set;
  try {
    set.emplace(LoadSpecRecordSet(grid));
  } catch (const InputError&) {
    return out;  // reported by the evaluator, which needs the set
  }
  // The table that pairs a folder's files decides what each record is, as a manifest does.
  if (!set->pairs_table.empty()) add("record-pairs", set->pairs_table);
  for (const std::string& label : wanted) {
    for (const records::RecordEntry& entry : set->records) {
      // An unknown label adds no file: the evaluator names it with the set's labels.
      if (records::RecordLabel(entry) != label) continue;
      std::error_code ec;
      if (!std::filesystem::is_regular_file(entry.file, ec)) {
        // Named at the set's line of the record, so that the set can be mended there.
        throw InputError::AtLine(
            set->manifest.string(), entry.line,
            "record '" + label + "': " + WhyUnreadable(entry.file) + ": " + entry.file.string());
      }
      add("record", entry.file);
      if (entry.IsPair()) {
        // A pair's H2 file enters the input identity as its H1 file does.
        if (!std::filesystem::is_regular_file(entry.file_h2, ec)) {
          throw InputError::AtLine(set->manifest.string(), entry.line,
                                   "record '" + label + "': h2: " + WhyUnreadable(entry.file_h2) +
                                       ": " + entry.file_h2.string());
        }
        add("record", entry.file_h2);
      }
    }
  }
  return out;
}

}  // namespace skewbridge::spectra
