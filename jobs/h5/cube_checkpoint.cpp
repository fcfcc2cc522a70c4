#include <algorithm>

#include "jobs/h5/cube_file.h"
#include "jobs/h5/cube_layout.h"
#include "solver/common/error.h"

namespace skewbridge::jobs::h5 {
namespace {

// Reads every dataset of a checkpoint into `data`, which verifies each chunk's Fletcher-32
// checksum, and checks what a checksum cannot see (bytes rewritten through HDF5): a done cell
// must carry a status of the table other than not-done and the number of a run that has
// happened. Any failure refuses the resume naming the dataset and the cell.
void ReadVerified(const std::string& file_name, const std::string& group_path, hid_t group,
                  const CubeLayout& layout, CubeData& data) {
  auto corrupted = [&](const std::string& dataset, const std::string& problem) {
    return InputError::AtLine(file_name, 0,
                              "cannot resume: dataset " + group_path + "/" + dataset +
                                  " is corrupted (" + problem +
                                  "); use --force to start over or a new output file");
  };
  auto read = [&](const std::string& dataset, hid_t mem_type, void* out) {
    try {
      ReadAll(OpenDataset(group, dataset).get(), mem_type, out);
    } catch (const H5Error& e) {
      // "H5Dread /path: reason": the dataset is named already, keep the reason.
      const std::string message = e.what();
      const std::size_t colon = message.rfind(": ");
      throw corrupted(dataset, colon == std::string::npos ? message : message.substr(colon + 2));
    }
  };
  for (std::size_t r = 0; r < layout.responses.size(); ++r) {
    read("responses/" + layout.responses[r].name, H5T_NATIVE_DOUBLE, data.responses[r].data());
  }
  read("status", H5T_NATIVE_INT32, data.status.data());
  read("done", H5T_NATIVE_UINT8, data.done.data());
  read("stats/run", H5T_NATIVE_INT32, data.run.data());
  read("stats/events", H5T_NATIVE_INT64, data.events.data());
  read("stats/steps", H5T_NATIVE_INT64, data.steps.data());
  read("stats/wall_s", H5T_NATIVE_DOUBLE, data.wall_s.data());
  const std::int64_t runs = GetIntAttr(group, "runs");
  for (std::uint64_t c = 0; c < data.Cells(); ++c) {
    const std::string cell = "cell " + std::to_string(c);
    if (data.done[c] > 1) {
      throw corrupted("done", cell + " has flag " + std::to_string(data.done[c]) + ", not 0 or 1");
    }
    if (data.done[c] == 0) {
      continue;
    }
    const std::int32_t status = data.status[c];
    const bool known = status != kStatusNotDone &&
                       std::any_of(layout.status_names.begin(), layout.status_names.end(),
                                   [status](const auto& entry) { return entry.first == status; });
    if (!known) {
      throw corrupted("status", cell + " is done with status " + std::to_string(status) +
                                    ", which is not a computed status of the table");
    }
    if (data.run[c] < 1 || data.run[c] > runs) {
      throw corrupted("stats/run", cell + " is done but names run " + std::to_string(data.run[c]) +
                                       " of " + std::to_string(runs) +
                                       " (a done flag without data)");
    }
  }
}

// Checks, read-only, that a checkpoint holds every dataset this program would write into it,
// with the axis order and shape of `spec`: a file from an older program version (one response
// fewer, same spec hash) is refused before it is opened for writing, naming what is missing.
// Then reads and verifies every cell into `data` (ReadVerified).
void CheckResumable(const std::filesystem::path& path, const SweepSpec& spec,
                    const CubeLayout& layout, CubeData& data) {
  const std::string file_name = path.string();
  auto refuse = [&](const std::string& problem) {
    return InputError::AtLine(file_name, 0,
                              "cannot resume: " + problem +
                                  ", as in a file of another program version; use --force to "
                                  "start over or a new output file");
  };
  Id file;
  try {
    file = OpenFile(file_name, false);
  } catch (const H5Error&) {
    throw InputError::AtLine(file_name, 0, "cannot open as an HDF5 file");
  }
  const std::string group_path = GroupPath(spec.name);
  if (!HasAttr(file.get(), "format") || GetStringAttr(file.get(), "format") != kCubeFormat) {
    throw InputError::AtLine(file_name, 0, "not a skewbridge cube (root attribute format)");
  }
  if (!Exists(file.get(), "sweeps") || !Exists(OpenGroup(file.get(), "sweeps").get(), spec.name)) {
    throw InputError::AtLine(file_name, 0, "holds no sweep named '" + spec.name + "'");
  }
  Id g = OpenGroup(file.get(), group_path);
  const std::string hash = GetStringAttr(g.get(), "spec_hash");
  const std::string change = DescribeIdentityChange(
      HasAttr(g.get(), "spec_canonical") ? GetStringAttr(g.get(), "spec_canonical") : "",
      HasAttr(g.get(), "inputs_canonical") ? GetStringAttr(g.get(), "inputs_canonical") : "", spec);
  if (!change.empty()) {
    throw InputError::AtLine(file_name, 0,
                             "cannot resume: " + change +
                                 "; restore it, write a new output file, or use --force to "
                                 "recompute every cell from the inputs as they are now");
  }
  if (hash != spec.Hash()) {
    throw InputError::AtLine(
        file_name, 0,
        "cannot resume: it was written by a different sweep specification (hash " + hash + ", " +
            spec.source + " has " + spec.Hash() +
            "); use the original specification, a new output file, or --force to start over");
  }
  std::vector<std::string> axis_order;
  for (const Axis& axis : spec.axes) {
    axis_order.push_back(axis.key);
  }
  if (!HasAttr(g.get(), "axis_order") || GetStringListAttr(g.get(), "axis_order") != axis_order) {
    throw refuse("its axis order differs from the specification's");
  }
  const std::vector<hsize_t> shape = ShapeOf(spec);
  std::vector<std::string> datasets;
  for (const ResponseInfo& r : layout.responses) {
    datasets.push_back("responses/" + r.name);
  }
  for (const char* name :
       {"status", "done", "stats/run", "stats/events", "stats/steps", "stats/wall_s"}) {
    datasets.emplace_back(name);
  }
  for (const std::string& name : datasets) {
    const std::size_t slash = name.find('/');
    const bool present = slash == std::string::npos
                             ? Exists(g.get(), name)
                             : Exists(g.get(), name.substr(0, slash)) && Exists(g.get(), name);
    if (!present) {
      throw refuse("it has no dataset " + group_path + "/" + name);
    }
    if (Shape(OpenDataset(g.get(), name).get()) != shape) {
      throw refuse("its dataset " + group_path + "/" + name + " has another shape");
    }
  }
  std::vector<std::string> expected;
  for (const ResponseInfo& r : layout.responses) {
    expected.push_back(r.name);
  }
  if (GetStringListAttr(g.get(), "response_order") != expected) {
    throw refuse("its responses differ from this program's evaluator");
  }
  data.Reset(spec.CellCount(), layout.responses.size());
  ReadVerified(file_name, group_path, g.get(), layout, data);
  try {
    ReadAllMetadata(file.get());
  } catch (const H5Error& e) {
    throw InputError::AtLine(file_name, 0,
                             std::string("cannot resume: its metadata is corrupted (") + e.what() +
                                 "); use --force to start over or a new output file");
  }
}

}  // namespace

struct CheckpointFile::Impl {
  Datasets d;
  std::string path;
  std::int32_t run = 1;
  std::string created_utc;
};

CheckpointFile::CheckpointFile(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CheckpointFile::CheckpointFile(CheckpointFile&&) noexcept = default;
CheckpointFile& CheckpointFile::operator=(CheckpointFile&&) noexcept = default;
CheckpointFile::~CheckpointFile() = default;

CheckpointFile CheckpointFile::Create(const std::filesystem::path& path, const SweepSpec& spec,
                                      const CubeLayout& layout) {
  auto impl = std::make_unique<Impl>();
  impl->path = path.string();
  impl->created_utc = UtcNow();
  {
    const Datasets image = CreateLayout(path.string(), spec, layout, false, 1, impl->created_utc);
    // No fsync: the new file holds no cell yet, and the first checkpoint's FlushToDisk syncs
    // the whole file (its layout with its cells) before any cell counts as saved.
    SaveFileImage(image.file.get(), *image.memory, path.string(), Durability::kWritten);
  }
  impl->d = OpenLayout(path.string(), spec.name, true, nullptr);
  return CheckpointFile(std::move(impl));
}

CheckpointFile CheckpointFile::Resume(const std::filesystem::path& path, const SweepSpec& spec,
                                      const CubeLayout& layout, CubeData& data) {
  // Everything is checked read-only first: a refused file is left byte for byte as it was.
  CheckResumable(path, spec, layout, data);
  auto impl = std::make_unique<Impl>();
  impl->path = path.string();
  std::vector<std::string> names;
  impl->d = OpenLayout(path.string(), spec.name, true, &names);
  const hid_t g = impl->d.group.get();
  SB_DEMAND(names.size() == layout.responses.size(), "checked response order changed");
  // Bytes of cells without a done flag may be half-written: forget them.
  for (std::uint64_t c = 0; c < data.Cells(); ++c) {
    if (data.done[c] == 0) {
      data.Store(c, kStatusNotDone, {}, CellStats{}, 0);
    }
  }
  impl->run = static_cast<std::int32_t>(GetIntAttr(g, "runs")) + 1;
  impl->created_utc = GetStringAttr(g, "created_utc");
  SetAttr(g, "runs", static_cast<std::int64_t>(impl->run));
  FlushToDisk(impl->d.file.get());
  return CheckpointFile(std::move(impl));
}

std::int32_t CheckpointFile::Run() const { return impl_->run; }

std::string CheckpointFile::CreatedUtc() const { return impl_->created_utc; }

void CheckpointFile::Write(const CubeData& data, std::span<const std::uint64_t> cells) {
  SB_DEMAND(impl_ != nullptr, "checkpoint file is closed");
  if (cells.empty()) {
    return;
  }
  // A failure leaves the file as the last complete checkpoint left it for the cells marked
  // done there (their chunks are rewritten in place, their flags come after their data).
  try {
    for (const Writable& w : DataOf(impl_->d, data)) {
      WriteCells(w.dataset, w.mem_type, w.size, w.data, cells);
    }
    FlushToDisk(impl_->d.file.get());
    WriteCells(impl_->d.done.get(), H5T_NATIVE_UINT8, 1, data.done.data(), cells);
    FlushToDisk(impl_->d.file.get());
  } catch (const H5Error& e) {
    throw H5Error(impl_->path + ": checkpoint: " + e.what());
  }
}

void CheckpointFile::Close() { impl_.reset(); }

}  // namespace skewbridge::jobs::h5
