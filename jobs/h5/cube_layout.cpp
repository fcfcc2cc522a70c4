#include "jobs/h5/cube_layout.h"

#include <algorithm>
#include <array>
#include <ctime>
#include <limits>
#include <string_view>

#include "jobs/h5/event_policy_attrs.h"
#include "solver/common/error.h"

namespace skewbridge::jobs::h5 {

std::vector<hsize_t> ShapeOf(const SweepSpec& spec) {
  std::vector<hsize_t> shape;
  for (std::size_t n : spec.Shape()) {
    shape.push_back(n);
  }
  return shape;
}

std::vector<Writable> DataOf(const Datasets& d, const CubeData& data) {
  std::vector<Writable> out;
  for (std::size_t r = 0; r < d.responses.size(); ++r) {
    out.push_back(
        {d.responses[r].get(), H5T_NATIVE_DOUBLE, sizeof(double), data.responses[r].data()});
  }
  out.push_back({d.status.get(), H5T_NATIVE_INT32, sizeof(std::int32_t), data.status.data()});
  out.push_back({d.run.get(), H5T_NATIVE_INT32, sizeof(std::int32_t), data.run.data()});
  out.push_back({d.events.get(), H5T_NATIVE_INT64, sizeof(std::int64_t), data.events.data()});
  out.push_back({d.steps.get(), H5T_NATIVE_INT64, sizeof(std::int64_t), data.steps.data()});
  out.push_back({d.wall_s.get(), H5T_NATIVE_DOUBLE, sizeof(double), data.wall_s.data()});
  return out;
}

Datasets CreateLayout(const std::string& path, const SweepSpec& spec, const CubeLayout& layout,
                      bool final, std::int32_t runs, const std::string& created_utc) {
  Datasets d;
  // Built in memory and written out whole (SaveFileImage): a full disk then fails in a plain
  // write, which leaves no half-written file and no HDF5 file that cannot be closed.
  // A checkpoint's chunks are allocated and filled at creation: its per-cell bytes (a double
  // per response, the status, done, run, events, steps and wall time) are most of the file,
  // and its memory is mapped at that length, with room for the chunks' index and checksums and
  // the metadata, so that it never grows. A final cube's chunks are deflated: no estimate.
  const double cell_bytes =
      8.0 * static_cast<double>(layout.responses.size()) + 4 + 1 + 4 + 8 + 8 + 8;
  const double expected =
      final ? 0.0 : 1.125 * cell_bytes * static_cast<double>(spec.CellCount()) + (1 << 20);
  MemoryFile image = CreateMemoryFile(
      path, expected < 0x1p40 ? static_cast<std::size_t>(expected) : std::size_t{1} << 40);
  d.memory = std::move(image.memory);
  d.file = std::move(image.file);
  SetAttr(d.file.get(), "format", std::string(kCubeFormat));
  SetAttr(d.file.get(), "format_version", kCubeFormatVersion);
  d.group = CreateGroup(d.file.get(), GroupPath(spec.name));
  const hid_t g = d.group.get();
  SetAttr(g, "family", spec.family);
  SetAttr(g, "spec_text", spec.text);
  SetAttr(g, "spec_source", spec.source);
  SetAttr(g, "spec_canonical", spec.CanonicalText());
  SetAttr(g, "spec_hash", spec.Hash());
  SetAttr(g, "inputs_canonical", spec.InputsText());
  SetAttr(g, "program_version", std::string(SKEWBRIDGE_VERSION));
  SetAttr(g, "source_revision", std::string(SKEWBRIDGE_GIT_REVISION));
  SetAttr(g, "created_utc", created_utc);
  SetAttr(g, "runs", static_cast<std::int64_t>(runs));
  SetAttr(g, "cells", static_cast<std::int64_t>(spec.CellCount()));
  SetAttr(g, "complete", static_cast<std::int64_t>(0));
  std::vector<std::string> axis_order;
  for (const Axis& axis : spec.axes) {
    axis_order.push_back(axis.key);
  }
  SetAttr(g, "axis_order", axis_order);
  std::vector<std::string> response_order;
  for (const ResponseInfo& r : layout.responses) {
    response_order.push_back(r.name);
  }
  SetAttr(g, "response_order", response_order);
  std::vector<std::string> response_links;
  for (const ResponseInfo& r : layout.responses) {
    response_links.push_back(ResponseLinkName(r.name, spec));
  }
  SetAttr(g, "response_links", response_links);
  // The thresholds and rules of the integrators that computed the cells.
  WriteMethodPolicies(g, layout.methods, layout.policies);

  Id fixed = CreateGroup(g, "fixed");
  std::vector<std::string> fixed_keys;
  std::vector<std::string> fixed_units;
  for (const FixedValue& f : spec.fixed) {
    if (f.kind == ParameterKind::kNumber) {
      SetAttr(fixed.get(), f.key, f.value);
    } else {
      SetAttr(fixed.get(), f.key, f.label);
    }
    // An attribute cannot carry attributes: the units go in two parallel lists.
    const ParameterInfo* info = FindParameter(f.key);
    fixed_keys.push_back(f.key);
    fixed_units.push_back(info != nullptr ? std::string(info->unit) : std::string("1"));
  }
  if (!fixed_keys.empty()) {  // an empty string list is not a valid attribute
    SetAttr(fixed.get(), "keys", fixed_keys);
    SetAttr(fixed.get(), "units", fixed_units);
  }

  // The files the cells are computed from, one row each (the specification first).
  Id inputs = CreateGroup(g, "inputs");
  std::vector<std::string> roles;
  std::vector<std::string> files;
  std::vector<std::string> sums;
  std::vector<std::int64_t> sizes;
  for (const InputFile& input : spec.inputs) {
    roles.push_back(input.role);
    files.push_back(input.file);
    sums.push_back(input.sha256);
    sizes.push_back(static_cast<std::int64_t>(input.bytes));
  }
  if (!files.empty()) {  // a spec parsed in memory by a test may list none
    WriteStrings(inputs.get(), "role", roles);
    WriteStrings(inputs.get(), "file", files);
    WriteStrings(inputs.get(), "sha256", sums);
    const hsize_t n = sizes.size();
    Id bytes = CreateDataset(inputs.get(), "bytes", H5T_STD_I64LE, std::span<const hsize_t>(&n, 1),
                             {}, 0, nullptr);
    WriteAll(bytes.get(), H5T_NATIVE_INT64, sizes.data());
    SetAttr(bytes.get(), "units", std::string("byte"));
  }

  Id axes_group = CreateGroup(g, "axes");
  std::vector<Id> scales;
  for (const Axis& axis : spec.axes) {
    const ParameterInfo* info = FindParameter(axis.key);
    if (axis.kind == ParameterKind::kNumber) {
      const hsize_t n = axis.values.size();
      Id ds = CreateDataset(axes_group.get(), axis.key, H5T_IEEE_F64LE,
                            std::span<const hsize_t>(&n, 1), {}, 0, nullptr);
      WriteAll(ds.get(), H5T_NATIVE_DOUBLE, axis.values.data());
      scales.push_back(std::move(ds));
    } else {
      WriteStrings(axes_group.get(), axis.key, axis.labels);
      scales.push_back(OpenDataset(axes_group.get(), axis.key));
    }
    const hid_t s = scales.back().get();
    SetAttr(s, "units", std::string(info->unit));
    SetAttr(s, "description", std::string(info->description));
    SetAttr(s, "symbol", std::string(info->symbol));
    SetAttr(s, "spacing", axis.spacing);
    SetScale(s, axis.key);
    // A second name for the scale in the sweep group: netCDF readers (xarray's h5netcdf engine)
    // see a dimension only in the group that holds it or its ancestors.
    Check(H5Lcreate_hard(axes_group.get(), axis.key.c_str(), g, axis.key.c_str(), H5P_DEFAULT,
                         H5P_DEFAULT),
          "link axes/" + axis.key);
  }

  const std::vector<hsize_t> shape = ShapeOf(spec);
  // Both files use the same chunks, each with a Fletcher-32 checksum; the checkpoint's are
  // uncompressed and allocated at creation so that writes rewrite them in place.
  const int level = final ? kDeflateLevel : 0;
  auto make = [&](hid_t parent, const std::string& name, hid_t type, const void* fill,
                  const std::string& units, const std::string& description) {
    Id ds = CreateDataset(parent, name, type, shape, {}, level, fill);
    SetAttr(ds.get(), "units", units);
    SetAttr(ds.get(), "description", description);
    for (std::size_t k = 0; k < scales.size(); ++k) {
      AttachScale(ds.get(), scales[k].get(), static_cast<unsigned>(k), spec.axes[k].key);
    }
    return ds;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::int32_t not_done = kStatusNotDone;
  const std::int32_t zero32 = 0;
  const std::int64_t zero64 = 0;
  const std::uint8_t zero8 = 0;
  const double zero = 0.0;
  Id responses = CreateGroup(g, "responses");
  for (const ResponseInfo& r : layout.responses) {
    d.responses.push_back(
        make(responses.get(), r.name, H5T_IEEE_F64LE, &nan, r.unit, r.description));
    // ... and the responses beside their coordinates, so that one xarray Dataset holds both;
    // an axis keeps its own name there (ResponseLinkName).
    const std::string link = ResponseLinkName(r.name, spec);
    Check(
        H5Lcreate_hard(responses.get(), r.name.c_str(), g, link.c_str(), H5P_DEFAULT, H5P_DEFAULT),
        "link responses/" + r.name + " as " + link);
  }
  d.status = make(g, "status", H5T_STD_I32LE, &not_done, "1",
                  "cell status code; names in the attributes status_codes / status_names");
  std::vector<std::int32_t> codes;
  std::vector<std::string> names;
  for (const auto& [code, name] : layout.status_names) {
    codes.push_back(code);
    names.push_back(name);
  }
  SetAttr(d.status.get(), "status_codes", codes);
  SetAttr(d.status.get(), "status_names", names);
  d.done = make(g, "done", H5T_STD_U8LE, &zero8, "1",
                "1 when the cell's data is in the file (written after the data it covers)");
  Id stats = CreateGroup(g, "stats");
  d.run = make(stats.get(), "run", H5T_STD_I32LE, &zero32, "1",
               "the run (1 = first, 2.. = resumes) that computed the cell; 0 = not computed");
  d.events = make(stats.get(), "events", H5T_STD_I64LE, &zero64, "1",
                  "contact events of the cell's solver run");
  d.steps = make(stats.get(), "steps", H5T_STD_I64LE, &zero64, "1",
                 "integration steps of the cell's solver run");
  d.wall_s = make(stats.get(), "wall_s", H5T_IEEE_F64LE, &zero, "s",
                  "wall-clock time of the cell's evaluation");
  return d;
}

Datasets OpenLayout(const std::string& path, const std::string& sweep, bool writable,
                    std::vector<std::string>* response_names) {
  Datasets d;
  try {
    d.file = OpenFile(path, writable);
  } catch (const H5Error&) {
    throw InputError::AtLine(path, 0, "cannot open as an HDF5 file");
  }
  if (!HasAttr(d.file.get(), "format") || GetStringAttr(d.file.get(), "format") != kCubeFormat) {
    throw InputError::AtLine(path, 0, "not a skewbridge cube (root attribute format)");
  }
  if (!Exists(d.file.get(), "sweeps") || !Exists(OpenGroup(d.file.get(), "sweeps").get(), sweep)) {
    throw InputError::AtLine(path, 0, "holds no sweep named '" + sweep + "'");
  }
  d.group = OpenGroup(d.file.get(), GroupPath(sweep));
  const hid_t g = d.group.get();
  const std::vector<std::string> order = GetStringListAttr(g, "response_order");
  Id responses = OpenGroup(g, "responses");
  for (const std::string& name : order) {
    d.responses.push_back(OpenDataset(responses.get(), name));
  }
  if (response_names != nullptr) {
    *response_names = order;
  }
  d.status = OpenDataset(g, "status");
  d.done = OpenDataset(g, "done");
  d.run = OpenDataset(g, "stats/run");
  d.events = OpenDataset(g, "stats/events");
  d.steps = OpenDataset(g, "stats/steps");
  d.wall_s = OpenDataset(g, "stats/wall_s");
  return d;
}

std::uint64_t CellsOf(hid_t dataset) {
  std::uint64_t n = 1;
  for (hsize_t s : Shape(dataset)) {
    n *= s;
  }
  return n;
}

void ReadData(const Datasets& d, CubeData& data) {
  data.Reset(CellsOf(d.status.get()), d.responses.size());
  for (std::size_t r = 0; r < d.responses.size(); ++r) {
    ReadAll(d.responses[r].get(), H5T_NATIVE_DOUBLE, data.responses[r].data());
  }
  ReadAll(d.status.get(), H5T_NATIVE_INT32, data.status.data());
  ReadAll(d.done.get(), H5T_NATIVE_UINT8, data.done.data());
  ReadAll(d.run.get(), H5T_NATIVE_INT32, data.run.data());
  ReadAll(d.events.get(), H5T_NATIVE_INT64, data.events.data());
  ReadAll(d.steps.get(), H5T_NATIVE_INT64, data.steps.data());
  ReadAll(d.wall_s.get(), H5T_NATIVE_DOUBLE, data.wall_s.data());
}

std::string ResponseLinkName(const std::string& response, const SweepSpec& spec) {
  static constexpr std::array<std::string_view, 11> kGroupMembers{
      "axes",    "responses",   "fixed",  "stats",     "status", "done",
      "records", "correlation", "inputs", "fragility", "risk"};
  const bool taken =
      spec.FindAxis(response) != nullptr ||
      std::find(kGroupMembers.begin(), kGroupMembers.end(), response) != kGroupMembers.end();
  return taken ? "response_" + response : response;
}

std::string UtcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buffer;
}

}  // namespace skewbridge::jobs::h5
