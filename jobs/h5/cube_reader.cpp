#include <algorithm>

#include "jobs/h5/cube_file.h"
#include "jobs/h5/cube_layout.h"
#include "solver/common/error.h"

namespace skewbridge::jobs::h5 {
namespace {

// The dataset `dataset` of a sweep group, opened, or absent with a message naming it.
Id OpenSweepDataset(const std::filesystem::path& path, const Datasets& d, const std::string& sweep,
                    const std::string& dataset) {
  // H5Lexists needs every intermediate group to exist, so walk the path one link at a time.
  bool found = !dataset.empty();
  for (std::size_t slash = 0; found && slash != std::string::npos;) {
    slash = dataset.find('/', slash + 1);
    found = Exists(d.group.get(), dataset.substr(0, slash));
  }
  if (!found) {
    throw InputError::AtLine(path.string(), 0,
                             "sweep '" + sweep + "' holds no dataset '" + dataset + "'");
  }
  return OpenDataset(d.group.get(), dataset);
}

std::vector<double> ReadSweepArrayIn(const std::filesystem::path& path, const std::string& sweep,
                                     const std::string& dataset) {
  const Datasets d = OpenLayout(path.string(), sweep, false, nullptr);
  Id ds = OpenSweepDataset(path, d, sweep, dataset);
  std::size_t n = 1;
  for (hsize_t extent : Shape(ds.get())) n *= extent;
  std::vector<double> out(n);
  ReadAll(ds.get(), H5T_NATIVE_DOUBLE, out.data());
  return out;
}

std::vector<std::string> ReadSweepStringsIn(const std::filesystem::path& path,
                                            const std::string& sweep, const std::string& dataset) {
  const Datasets d = OpenLayout(path.string(), sweep, false, nullptr);
  Id ds = OpenSweepDataset(path, d, sweep, dataset);
  return ReadStrings(ds.get());
}

std::vector<SweepSummary> SummarizeCubeIn(const std::filesystem::path& path) {
  Id file;
  try {
    file = OpenFile(path.string(), false);
  } catch (const H5Error&) {
    throw InputError::AtLine(path.string(), 0, "cannot open as an HDF5 file");
  }
  if (!HasAttr(file.get(), "format") || GetStringAttr(file.get(), "format") != kCubeFormat ||
      !Exists(file.get(), "sweeps")) {
    throw InputError::AtLine(path.string(), 0, "not a skewbridge cube (root attribute format)");
  }
  std::vector<SweepSummary> out;
  Id sweeps = OpenGroup(file.get(), "sweeps");
  for (const std::string& name : ListChildren(sweeps.get())) {
    Id g = OpenGroup(sweeps.get(), name);
    SweepSummary s;
    s.name = name;
    s.family = GetStringAttr(g.get(), "family");
    s.spec_hash = GetStringAttr(g.get(), "spec_hash");
    if (HasAttr(g.get(), "spec_canonical")) {
      s.spec_canonical = GetStringAttr(g.get(), "spec_canonical");
    }
    if (HasAttr(g.get(), "inputs_canonical")) {
      s.inputs_canonical = GetStringAttr(g.get(), "inputs_canonical");
    }
    s.spec_text = GetStringAttr(g.get(), "spec_text");
    s.spec_source = GetStringAttr(g.get(), "spec_source");
    s.created_utc = GetStringAttr(g.get(), "created_utc");
    s.program_version = GetStringAttr(g.get(), "program_version");
    s.complete = GetIntAttr(g.get(), "complete") != 0;
    s.runs = GetIntAttr(g.get(), "runs");
    Id axes = OpenGroup(g.get(), "axes");
    for (const std::string& key : GetStringListAttr(g.get(), "axis_order")) {
      Id ds = OpenDataset(axes.get(), key);
      AxisSummary a;
      a.name = key;
      a.unit = GetStringAttr(ds.get(), "units");
      a.size = static_cast<std::size_t>(Shape(ds.get()).at(0));
      Id type(H5Dget_type(ds.get()), H5Tclose, "H5Dget_type " + key);
      if (H5Tget_class(type.get()) == H5T_STRING) {
        a.labels = ReadStrings(ds.get());
      } else {
        a.values.resize(a.size);
        ReadAll(ds.get(), H5T_NATIVE_DOUBLE, a.values.data());
      }
      s.axes.push_back(std::move(a));
    }
    s.children = ListChildren(g.get());
    if (Exists(g.get(), "fixed")) {
      Id fixed = OpenGroup(g.get(), "fixed");
      if (HasAttr(fixed.get(), "keys")) {
        const std::vector<std::string> keys = GetStringListAttr(fixed.get(), "keys");
        const std::vector<std::string> units = GetStringListAttr(fixed.get(), "units");
        for (std::size_t k = 0; k < keys.size(); ++k) {
          FixedSummary f;
          f.key = keys[k];
          f.unit = k < units.size() ? units[k] : "";
          f.is_label = IsStringAttr(fixed.get(), f.key);
          if (f.is_label) {
            f.label = GetStringAttr(fixed.get(), f.key);
          } else {
            f.value = GetDoubleAttr(fixed.get(), f.key);
          }
          s.fixed.push_back(std::move(f));
        }
      }
    }
    Id responses = OpenGroup(g.get(), "responses");
    for (const std::string& r : GetStringListAttr(g.get(), "response_order")) {
      Id ds = OpenDataset(responses.get(), r);
      s.responses.push_back(
          {r, GetStringAttr(ds.get(), "units"), GetStringAttr(ds.get(), "description")});
    }
    Id status_ds = OpenDataset(g.get(), "status");
    Id done_ds = OpenDataset(g.get(), "done");
    s.cells = CellsOf(status_ds.get());
    std::vector<std::int32_t> status(s.cells);
    std::vector<std::uint8_t> done(s.cells);
    ReadAll(status_ds.get(), H5T_NATIVE_INT32, status.data());
    ReadAll(done_ds.get(), H5T_NATIVE_UINT8, done.data());
    const std::vector<std::int32_t> codes = GetIntListAttr(status_ds.get(), "status_codes");
    const std::vector<std::string> names = GetStringListAttr(status_ds.get(), "status_names");
    for (std::uint64_t c = 0; c < s.cells; ++c) {
      if (done[c] == 0) {
        continue;
      }
      ++s.done;
      const auto it = std::find(codes.begin(), codes.end(), status[c]);
      const std::string label = it == codes.end() || names.size() != codes.size()
                                    ? "code " + std::to_string(status[c])
                                    : names[static_cast<std::size_t>(it - codes.begin())];
      ++s.done_by_status[label];
    }
    if (Exists(g.get(), "inputs")) {
      Id inputs = OpenGroup(g.get(), "inputs");
      if (Exists(inputs.get(), "file")) {
        Id role_ds = OpenDataset(inputs.get(), "role");
        Id file_ds = OpenDataset(inputs.get(), "file");
        Id sha_ds = OpenDataset(inputs.get(), "sha256");
        Id bytes_ds = OpenDataset(inputs.get(), "bytes");
        const std::vector<std::string> roles = ReadStrings(role_ds.get());
        const std::vector<std::string> files = ReadStrings(file_ds.get());
        const std::vector<std::string> sums = ReadStrings(sha_ds.get());
        std::vector<std::int64_t> bytes(files.size());
        if (roles.size() != files.size() || sums.size() != files.size() ||
            CellsOf(bytes_ds.get()) != files.size()) {
          throw InputError::AtLine(
              path.string(), 0,
              "sweeps/" + name + "/inputs: role, file, sha256 and bytes " + "differ in length");
        }
        ReadAll(bytes_ds.get(), H5T_NATIVE_INT64, bytes.data());
        for (std::size_t i = 0; i < files.size(); ++i) {
          InputFile input;
          input.role = roles[i];
          input.file = files[i];
          input.sha256 = sums[i];
          input.bytes = static_cast<std::uint64_t>(bytes[i]);
          s.inputs.push_back(std::move(input));
        }
      }
    }
    if (HasAttr(g.get(), "status_examples")) {
      const std::vector<std::string> examples = GetStringListAttr(g.get(), "status_examples");
      for (std::size_t i = 0; i < examples.size() && i < names.size(); ++i) {
        if (!examples[i].empty()) {
          s.status_examples[names[i]] = examples[i];
        }
      }
    }
    out.push_back(std::move(s));
  }
  return out;
}

CubeData ReadCubeDataIn(const std::filesystem::path& path, const std::string& sweep,
                        std::vector<std::string>* response_names) {
  Datasets d = OpenLayout(path.string(), sweep, false, response_names);
  CubeData data;
  ReadData(d, data);
  return data;
}

}  // namespace

std::vector<double> ReadSweepArray(const std::filesystem::path& path, const std::string& sweep,
                                   const std::string& dataset) {
  return NamingFile(path, [&] { return ReadSweepArrayIn(path, sweep, dataset); });
}

std::vector<std::string> ReadSweepStrings(const std::filesystem::path& path,
                                          const std::string& sweep, const std::string& dataset) {
  return NamingFile(path, [&] { return ReadSweepStringsIn(path, sweep, dataset); });
}

std::vector<SweepSummary> SummarizeCube(const std::filesystem::path& path) {
  return NamingFile(path, [&] { return SummarizeCubeIn(path); });
}

CubeData ReadCubeData(const std::filesystem::path& path, const std::string& sweep,
                      std::vector<std::string>* response_names) {
  return NamingFile(path, [&] { return ReadCubeDataIn(path, sweep, response_names); });
}

}  // namespace skewbridge::jobs::h5
