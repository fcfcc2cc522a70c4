#include "jobs/h5/cube_file.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <ctime>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <type_traits>

#include "jobs/h5/event_policy_attrs.h"
#include "jobs/h5/h5.h"
#include "solver/common/error.h"
#include "spectra/limit_states.h"

namespace skewbridge::jobs::h5 {
namespace {

constexpr int kDeflateLevel = 4;

std::string GroupPath(const std::string& sweep) { return "sweeps/" + sweep; }

std::vector<hsize_t> ShapeOf(const SweepSpec& spec) {
  std::vector<hsize_t> shape;
  for (std::size_t n : spec.Shape()) {
    shape.push_back(n);
  }
  return shape;
}

// The datasets of one sweep group, opened or created.
struct Datasets {
  Id file;
  Id group;
  std::vector<Id> responses;
  Id status, done, run, events, steps, wall_s;
};

struct Writable {
  hid_t dataset;
  hid_t mem_type;
  std::size_t size;
  const void* data;
};

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
  d.file = CreateMemoryFile(path);
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
  // The event-driven integrator's thresholds and rules that computed the cells.
  WriteEventPolicy(g, spectra::EvaluatorEventPolicy());

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

// HDF5's Fletcher-32 (H5_checksum_fletcher32): 16-bit words read big-endian, sums reduced
// every 360 words, an odd last byte as the high half of a word.
std::uint32_t Fletcher32(const unsigned char* data, std::size_t bytes) {
  std::size_t words = bytes / 2;
  std::uint32_t sum1 = 0;
  std::uint32_t sum2 = 0;
  while (words > 0) {
    std::size_t block = std::min<std::size_t>(words, 360);
    words -= block;
    do {
      sum1 += (static_cast<std::uint32_t>(data[0]) << 8) | static_cast<std::uint32_t>(data[1]);
      data += 2;
      sum2 += sum1;
    } while (--block > 0);
    sum1 = (sum1 & 0xffff) + (sum1 >> 16);
    sum2 = (sum2 & 0xffff) + (sum2 >> 16);
  }
  if (bytes % 2 != 0) {
    sum1 += static_cast<std::uint32_t>(*data) << 8;
    sum2 += sum1;
    sum1 = (sum1 & 0xffff) + (sum1 >> 16);
    sum2 = (sum2 & 0xffff) + (sum2 >> 16);
  }
  sum1 = (sum1 & 0xffff) + (sum1 >> 16);
  sum2 = (sum2 & 0xffff) + (sum2 >> 16);
  return (sum2 << 16) | sum1;
}

// A per-cell dataset of the final cube as a source of chunk jobs: its chunk grid, its fill
// value (HDF5 fills the part of an edge chunk outside the extent with it before filtering)
// and the cube's array in memory (the native byte order is the file's, little-endian).
struct ChunkSource {
  hid_t dataset = -1;
  std::size_t size = 0;
  const char* data = nullptr;
  std::vector<hsize_t> shape, chunk, grid;
  std::vector<char> fill;
  std::uint64_t chunks = 1;

  ChunkSource(hid_t ds, hid_t mem_type, std::size_t element_size, const void* values)
      : dataset(ds), size(element_size), data(static_cast<const char*>(values)), shape(Shape(ds)) {
    Id dcpl(H5Dget_create_plist(ds), H5Pclose, "H5Dget_create_plist");
    chunk.resize(shape.size());
    Check(H5Pget_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()), "H5Pget_chunk");
    fill.resize(size);
    Check(H5Pget_fill_value(dcpl.get(), mem_type, fill.data()), "H5Pget_fill_value");
    for (std::size_t k = 0; k < shape.size(); ++k) {
      grid.push_back((shape[k] + chunk[k] - 1) / chunk[k]);
      chunks *= grid.back();
    }
  }

  // The chunk's offset in the dataset (element coordinates) for chunk j of the grid.
  std::vector<hsize_t> Offset(std::uint64_t j) const {
    std::vector<hsize_t> offset(shape.size());
    for (std::size_t k = shape.size(); k-- > 0;) {
      offset[k] = (j % grid[k]) * chunk[k];
      j /= grid[k];
    }
    return offset;
  }

  // The job of chunk j (MakeChunkJob's message, built in place: one copy of the cube's bytes):
  // the element size, then the chunk with the fill value everywhere and the cube's rows over
  // the part inside the extent.
  std::vector<char> Job(std::uint64_t j) const {
    const std::size_t rank = shape.size();
    const std::vector<hsize_t> offset = Offset(j);
    std::size_t elements = 1;
    for (hsize_t c : chunk) elements *= c;
    std::vector<char> job(1 + elements * size);
    job[0] = static_cast<char>(size);
    char* const raw = job.data() + 1;
    std::vector<hsize_t> extent(rank);  // the part of the chunk inside the dataset
    std::size_t inside = 1;
    for (std::size_t k = 0; k < rank; ++k) {
      extent[k] = std::min(chunk[k], shape[k] - offset[k]);
      inside *= extent[k];
    }
    if (inside < elements) {  // an edge chunk
      for (std::size_t e = 0; e < elements; ++e) {
        std::memcpy(raw + e * size, fill.data(), size);
      }
    }
    if (inside == 0) return job;
    // One memcpy per row along the last axis: walk the other axes of the chunk's extent.
    std::vector<hsize_t> at(rank, 0);
    while (true) {
      std::uint64_t in_chunk = 0;
      std::uint64_t in_cube = 0;
      for (std::size_t k = 0; k < rank; ++k) {
        in_chunk = in_chunk * chunk[k] + at[k];
        in_cube = in_cube * shape[k] + offset[k] + at[k];
      }
      std::memcpy(raw + in_chunk * size, data + in_cube * size, extent[rank - 1] * size);
      std::size_t k = rank - 1;
      while (k-- > 0) {
        if (++at[k] < extent[k]) break;
        at[k] = 0;
      }
      if (k == static_cast<std::size_t>(-1)) break;
    }
    return job;
  }
};

// The per-cell datasets through the farm: each chunk filtered elsewhere, written back as
// stored bytes (H5Dwrite_chunk, filter mask 0: every filter of the pipeline applied).
void WriteChunksThroughFarm(const std::vector<Writable>& datasets, const ChunkFarm& farm) {
  std::vector<ChunkSource> sources;
  std::vector<std::uint64_t> first;  // the first job of each dataset
  std::uint64_t count = 0;
  for (const Writable& w : datasets) {
    sources.emplace_back(w.dataset, w.mem_type, w.size, w.data);
    first.push_back(count);
    count += sources.back().chunks;
  }
  auto locate = [&](std::size_t i) {
    const std::size_t s =
        static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), i) - first.begin()) -
        1;
    return std::make_pair(s, static_cast<std::uint64_t>(i - first[s]));
  };
  farm(
      count,
      [&](std::size_t i) {
        const auto [s, j] = locate(i);
        return sources[s].Job(j);
      },
      [&](std::size_t i, std::span<const char> stored) {
        const auto [s, j] = locate(i);
        const std::vector<hsize_t> offset = sources[s].Offset(j);
        Check(H5Dwrite_chunk(sources[s].dataset, H5P_DEFAULT, 0, offset.data(), stored.size(),
                             stored.data()),
              "H5Dwrite_chunk " + ObjectName(sources[s].dataset));
      });
}

void SetDoublesAttr(hid_t obj, const std::string& name, const std::vector<double>& values) {
  const hsize_t n = values.size();
  Id space = Dataspace(std::span<const hsize_t>(&n, 1));
  Id attr(H5Acreate2(obj, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
          H5Aclose, "create attribute " + name);
  Check(H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, values.data()), "write attribute " + name);
}

// A contiguous dataset of the given shape, written whole, with units and description.
template <typename T>
Id WriteArray(hid_t parent, const std::string& name, const std::vector<hsize_t>& shape,
              const std::vector<T>& values, const std::string& units,
              const std::string& description) {
  const bool is_double = std::is_same_v<T, double>;
  Id ds = CreateDataset(parent, name, is_double ? H5T_IEEE_F64LE : H5T_STD_I64LE, shape, {}, 0,
                        nullptr);
  WriteAll(ds.get(), is_double ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64, values.data());
  SetAttr(ds.get(), "units", units);
  SetAttr(ds.get(), "description", description);
  return ds;
}

void WriteRecordTable(hid_t sweep_group, const StudyTables& study) {
  Id g = CreateGroup(sweep_group, "records");
  SetAttr(g.get(), "source", study.records_source);
  SetAttr(g.get(), "set", study.records_set);
  SetAttr(g.get(), "count", static_cast<std::int64_t>(study.records.size()));
  const std::vector<hsize_t> shape{study.records.size()};
  std::vector<std::string> label;
  std::vector<std::string> file;
  std::vector<std::string> component;
  std::vector<std::int64_t> npts;
  std::vector<double> scale, dt, pga, pgv, pgd, tm, wg, le, arias, d595, cav, sa_t1, avgsa;
  for (const SweepRecord& r : study.records) {
    label.push_back(r.label);
    file.push_back(r.file);
    component.push_back(r.motion.component);
    npts.push_back(static_cast<std::int64_t>(r.motion.npts()));
    scale.push_back(r.scale);
    dt.push_back(r.motion.dt_s);
    pga.push_back(r.measures.pga_mps2);
    pgv.push_back(r.measures.pgv_mps);
    pgd.push_back(r.measures.pgd_m);
    tm.push_back(r.measures.mean_period_s);
    wg.push_back(r.measures.omega_g_radps);
    le.push_back(r.measures.persistency_m);
    arias.push_back(r.measures.arias_mps);
    d595.push_back(r.measures.significant_duration_s);
    cav.push_back(r.measures.cav_mps);
    sa_t1.push_back(r.sa_t1_mps2);
    avgsa.push_back(r.avgsa_mps2);
  }
  // T1 is one for the sweep (else NaN and the cells hold theirs): the group says which.
  const SweepRecord& first = study.records.front();
  SetAttr(g.get(), "T1_s", first.t1_s);
  SetAttr(g.get(), "spectral_xi", first.spectral_xi);
  WriteStrings(g.get(), "label", label);
  WriteStrings(g.get(), "file", file);
  WriteStrings(g.get(), "component", component);
  WriteArray(g.get(), "scale", shape, scale, "1", "the manifest's factor on the accelerations");
  WriteArray(g.get(), "dt_s", shape, dt, "s", "sample interval");
  WriteArray(g.get(), "npts", shape, npts, "1", "number of samples");
  WriteArray(g.get(), "pga_mps2", shape, pga, "m/s^2", "peak ground acceleration = a_g");
  WriteArray(g.get(), "pgv_mps", shape, pgv, "m/s", "peak ground velocity");
  WriteArray(g.get(), "pgd_m", shape, pgd, "m", "peak ground displacement");
  WriteArray(g.get(), "T_m_s", shape, tm, "s", "mean period [Rathje et al. 1998]");
  WriteArray(g.get(), "w_g_radps", shape, wg, "rad/s", "w_g = 2 pi / T_m");
  WriteArray(g.get(), "L_e_m", shape, le, "m", "persistency PGA / w_g^2");
  WriteArray(g.get(), "arias_mps", shape, arias, "m/s", "Arias intensity");
  WriteArray(g.get(), "D5_95_s", shape, d595, "s", "significant duration 5-95 % of Arias");
  WriteArray(g.get(), "CAV_mps", shape, cav, "m/s",
             "cumulative absolute velocity int |a| dt over the record [EPRI 1988]");
  const std::string where_t1 =
      " at the sweep's fundamental period T1 (attribute T1_s) and damping spectral_xi; NaN "
      "when the cells' T1 differ (the cells store T1 and im) or the family has no model";
  WriteArray(g.get(), "Sa_T1_mps2", shape, sa_t1, "m/s^2",
             "pseudo-spectral acceleration Sa(T1)" + where_t1);
  WriteArray(g.get(), "AvgSa_mps2", shape, avgsa, "m/s^2",
             "AvgSa(T1): geometric mean of Sa over " + std::to_string(records::kAvgSaPeriodCount) +
                 " periods equally spaced in 0.2-3 T1 [Eads et al. 2015]" + where_t1);
  // The table's rows are the record axis: attach its scale to every column (select by label).
  if (Exists(sweep_group, "axes/record")) {
    Id record_axis = OpenDataset(sweep_group, "axes/record");
    for (const std::string& column : ListChildren(g.get())) {
      Id ds = OpenDataset(g.get(), column);
      AttachScale(ds.get(), record_axis.get(), 0, "record");
    }
  }
}

void WriteCorrelation(hid_t sweep_group, const CorrelationTable& table,
                      const std::vector<double>& band_edges) {
  Id g = CreateGroup(sweep_group, "correlation");
  SetAttr(g.get(), "x", std::string("L_e"));
  SetAttr(g.get(), "y", table.y);
  SetAttr(g.get(), "over", std::string("record"));
  SetAttr(g.get(), "axis_order", table.axis_order);
  // Without the response band (not stored, or a family without it) there are no groups.
  if (!band_edges.empty()) SetDoublesAttr(g.get(), "band_edges", band_edges);
  SetAttr(g.get(), "min_band_records", kMinBandRecords);
  SetAttr(g.get(), "loglog",
          std::string("log10(theta_m) = intercept + slope log10(L_e), least squares; "
                      "r2 = 1 - SS_res/SS_tot"));
  std::vector<hsize_t> shape(table.shape.begin(), table.shape.end());
  std::vector<hsize_t> band_shape = shape;
  band_shape.push_back(table.bands);
  std::vector<Id> scales;
  for (const std::string& key : table.axis_order) {
    scales.push_back(OpenDataset(sweep_group, "axes/" + key));
  }
  auto attach = [&](const Id& ds) {
    for (std::size_t k = 0; k < scales.size(); ++k) {
      AttachScale(ds.get(), scales[k].get(), static_cast<unsigned>(k), table.axis_order[k]);
    }
  };
  attach(WriteArray(g.get(), "n", shape, table.n, "1",
                    "cells used: status ok, theta_m and L_e finite"));
  attach(WriteArray(g.get(), "pearson_theta_Le", shape, table.pearson, "1",
                    "Pearson r of (L_e, theta_m) over the records"));
  attach(WriteArray(g.get(), "spearman_theta_Le", shape, table.spearman, "1",
                    "Spearman rho of (L_e, theta_m), ties given their average rank"));
  attach(WriteArray(g.get(), "loglog_n", shape, table.loglog_n, "1",
                    "cells with theta_m > 0 and L_e > 0"));
  attach(WriteArray(g.get(), "loglog_slope", shape, table.loglog_slope, "1",
                    "slope of log10 theta_m against log10 L_e (least squares)"));
  attach(WriteArray(g.get(), "loglog_intercept", shape, table.loglog_intercept, "1",
                    "intercept of log10 theta_m = intercept + slope log10 L_e (L_e in m)"));
  attach(WriteArray(g.get(), "loglog_r2", shape, table.loglog_r2, "1",
                    "R^2 of the log-log fit, 1 - SS_res / SS_tot"));
  WriteStrings(g.get(), "reason", table.reason);
  if (table.bands == 0) return;
  const std::string per_band = " per w0x/w_g group (last dimension), NaN below min_band_records";
  attach(WriteArray(g.get(), "band_n", band_shape, table.band_n, "1",
                    "cells used per w0x/w_g group (last dimension)"));
  attach(WriteArray(g.get(), "band_pearson_theta_Le", band_shape, table.band_pearson, "1",
                    "Pearson r" + per_band));
  attach(WriteArray(g.get(), "band_spearman_theta_Le", band_shape, table.band_spearman, "1",
                    "Spearman rho" + per_band));
  attach(WriteArray(g.get(), "band_loglog_slope", band_shape, table.band_loglog_slope, "1",
                    "log-log slope" + per_band));
  attach(WriteArray(g.get(), "band_loglog_intercept", band_shape, table.band_loglog_intercept, "1",
                    "log-log intercept" + per_band));
  attach(WriteArray(g.get(), "band_loglog_r2", band_shape, table.band_loglog_r2, "1",
                    "log-log R^2" + per_band));
}

void WriteFragility(hid_t sweep_group, const std::vector<FragilityStudy>& studies) {
  Id g = CreateGroup(sweep_group, "fragility");
  const FragilityStudy& first = studies.front();
  std::vector<std::string> names;
  for (const FragilityStudy& f : studies) names.push_back(f.ls.name);
  SetAttr(g.get(), "limit_states", names);
  SetAttr(g.get(), "method", std::string(first.table.stripe_axis.empty() ? "cloud" : "stripes"));
  SetAttr(g.get(), "im", first.im);
  SetAttr(g.get(), "im_units", first.im_units);
  SetAttr(g.get(), "im_description", first.im_description);
  SetAttr(g.get(), "stripe_axis", first.table.stripe_axis);
  SetAttr(g.get(), "axis_order", first.table.axis_order);
  SetAttr(g.get(), "model",
          std::string("P(exceeded | IM = x) = Phi(ln(x / theta) / beta), lognormal"));
  SetAttr(g.get(), "likelihood",
          std::string("binomial over the cells, maximised by Newton's method; standard errors "
                      "from the observed information [Baker 2015, Earthquake Spectra "
                      "31(1):579-599]"));
  SetAttr(g.get(), "cloud",
          std::string("ln(D / C) = cloud_intercept + cloud_slope ln(IM), least squares; "
                      "cloud_theta = exp(-intercept / slope), cloud_beta = sigma / slope "
                      "[Cornell et al. 2002]"));
  SetAttr(g.get(), "bootstrap",
          std::string("records drawn with replacement (std::mt19937_64, seed per combination "
                      "seeded from bootstrap_seed and its index), percentiles 2.5 and 97.5"));
  SetAttr(g.get(), "bootstrap_resamples",
          static_cast<std::int64_t>(first.table.bootstrap_resamples));
  SetAttr(g.get(), "bootstrap_seed", static_cast<std::int64_t>(first.table.bootstrap_seed));
  SetAttr(g.get(), "confidence", 0.95);
  std::vector<Id> scales;
  for (const std::string& key : first.table.axis_order) {
    scales.push_back(OpenDataset(sweep_group, "axes/" + key));
  }
  for (const FragilityStudy& f : studies) {
    const FragilityTable& t = f.table;
    Id ls = CreateGroup(g.get(), f.ls.name);
    SetAttr(ls.get(), "kind", spectra::LimitStateKindName(f.ls.kind));
    SetAttr(ls.get(), "threshold", f.ls.threshold);
    SetAttr(ls.get(), "demand_units", f.demand_unit);
    if (!f.ls.seat_m.empty()) SetDoublesAttr(ls.get(), "seat_m", f.ls.seat_m);
    if (f.ls.kind == spectra::LimitStateKind::kResponse)
      SetAttr(ls.get(), "response", f.ls.response);
    std::vector<hsize_t> shape;
    for (const std::size_t n : t.shape) shape.push_back(n);
    if (shape.empty()) shape.push_back(1);
    auto attach = [&](const Id& ds) {
      for (std::size_t k = 0; k < scales.size(); ++k) {
        AttachScale(ds.get(), scales[k].get(), static_cast<unsigned>(k), t.axis_order[k]);
      }
    };
    auto put = [&](const std::string& name, const auto& values, std::string units,
                   const std::string& description) {
      if (units == "g") units = f.im_units;  // the unit of the IM
      attach(WriteArray(ls.get(), name, shape, values, units, description));
    };
    put("theta", t.theta, "g", "maximum-likelihood median IM of exceedance");
    put("beta", t.beta, "1", "maximum-likelihood dispersion (log standard deviation)");
    put("se_ln_theta", t.se_ln_theta, "1", "standard error of ln theta (observed information)");
    put("se_beta", t.se_beta, "1", "standard error of beta (observed information)");
    put("cov_ln_theta_beta", t.cov_ln_theta_beta, "1", "covariance of (ln theta, beta)");
    put("theta_lo", t.theta_lo, "g", "95 % interval of theta: exp(ln theta - 1.96 se_ln_theta)");
    put("theta_hi", t.theta_hi, "g", "95 % interval of theta: exp(ln theta + 1.96 se_ln_theta)");
    put("beta_lo", t.beta_lo, "1", "95 % interval of beta: beta - 1.96 se_beta");
    put("beta_hi", t.beta_hi, "1", "95 % interval of beta: beta + 1.96 se_beta");
    put("boot_theta_lo", t.boot_theta_lo, "g", "2.5 % of theta over the bootstrap resamples");
    put("boot_theta_hi", t.boot_theta_hi, "g", "97.5 % of theta over the bootstrap resamples");
    put("boot_beta_lo", t.boot_beta_lo, "1", "2.5 % of beta over the bootstrap resamples");
    put("boot_beta_hi", t.boot_beta_hi, "1", "97.5 % of beta over the bootstrap resamples");
    put("boot_used", t.boot_used, "1", "bootstrap resamples that gave a fit (NaN bounds below 20)");
    put("n_cells", t.n_cells, "1", "cells used: done, status ok");
    put("n_exceeded", t.n_exceeded, "1", "cells among them that exceeded the limit state");
    put("cloud_n", t.cloud_n, "1", "cells of the cloud fit: D / C > 0 and IM > 0, finite");
    put("cloud_excluded", t.cloud_excluded, "1", "cells left out of the cloud fit");
    put("cloud_intercept", t.cloud_intercept, "1",
        "intercept of ln(D / C) on ln(IM) (IM in im_units)");
    put("cloud_slope", t.cloud_slope, "1", "slope of ln(D / C) on ln(IM)");
    put("cloud_sigma", t.cloud_sigma, "1", "residual standard deviation of ln(D / C)");
    put("cloud_theta", t.cloud_theta, "g", "cloud median IM of D = C");
    put("cloud_beta", t.cloud_beta, "1", "cloud dispersion sigma / slope");
    WriteStrings(ls.get(), "reason", t.reason);
    WriteStrings(ls.get(), "cloud_reason", t.cloud_reason);
    if (t.stripes == 0) continue;
    std::vector<hsize_t> stripe_shape(t.shape.begin(), t.shape.end());
    stripe_shape.push_back(t.stripes);
    Id stripe_scale = OpenDataset(sweep_group, "axes/" + t.stripe_axis);
    auto put_stripes = [&](const std::string& name, const auto& values, std::string units,
                           const std::string& description) {
      if (units == "g") units = f.im_units;
      Id ds = WriteArray(ls.get(), name, stripe_shape, values, units, description);
      attach(ds);
      AttachScale(ds.get(), stripe_scale.get(), static_cast<unsigned>(t.shape.size()),
                  t.stripe_axis);
    };
    put_stripes("stripe_im", t.stripe_im, "g", "geometric mean IM of the stripe's cells");
    put_stripes("stripe_n", t.stripe_n, "1", "cells of the stripe used");
    put_stripes("stripe_exceeded", t.stripe_exceeded, "1", "cells of the stripe that exceeded");
  }
}

void WriteIdaFragility(hid_t sweep_group, const std::vector<IdaFragilityStudy>& studies) {
  Id g = CreateGroup(sweep_group, "fragility");
  const IdaFragilityStudy& first = studies.front();
  std::vector<std::string> names;
  for (const IdaFragilityStudy& f : studies) names.push_back(f.ls.name);
  SetAttr(g.get(), "limit_states", names);
  SetAttr(g.get(), "method", std::string("ida"));
  SetAttr(g.get(), "im", std::string("ida_capacity"));
  SetAttr(g.get(), "im_units", first.im_units);
  SetAttr(g.get(), "im_description",
          std::string("each record's capacity: the lowest intensity of its hunt-and-fill "
                      "search at which the limit state is exceeded [Vamvatsikos and Cornell "
                      "2002, 2004]"));
  SetAttr(g.get(), "axis_order", first.axis_order);
  SetAttr(g.get(), "model",
          std::string("P(exceeded | IM = x) = Phi(ln(x / theta) / beta), lognormal"));
  SetAttr(
      g.get(), "fit",
      std::string("every capacity finite: theta = exp(mean of ln IM_c), beta = standard "
                  "deviation of ln IM_c with n - 1, over the records' capacities [Baker "
                  "2015, Earthquake Spectra 31(1):579-599]; n_censored > 0: the "
                  "maximum-likelihood theta and beta (n) of the lognormal with the records "
                  "that never reach the limit state right-censored at their highest run "
                  "(note), a capacity beyond records.max_scale censored at it (n_scaled_too_far); "
                  "NaN (with the reason) when fewer than 2 capacities are finite"));
  std::vector<Id> scales;
  for (const std::string& key : first.axis_order) {
    scales.push_back(OpenDataset(sweep_group, "axes/" + key));
  }
  for (const IdaFragilityStudy& f : studies) {
    Id ls = CreateGroup(g.get(), f.ls.name);
    SetAttr(ls.get(), "kind", spectra::LimitStateKindName(f.ls.kind));
    SetAttr(ls.get(), "threshold", f.ls.threshold);
    if (!f.ls.seat_m.empty()) SetDoublesAttr(ls.get(), "seat_m", f.ls.seat_m);
    if (f.ls.kind == spectra::LimitStateKind::kResponse)
      SetAttr(ls.get(), "response", f.ls.response);
    std::vector<hsize_t> shape;
    for (const std::size_t n : f.shape) shape.push_back(n);
    if (shape.empty()) shape.push_back(1);
    auto put = [&](const std::string& name, const auto& values, const std::string& units,
                   const std::string& description) {
      Id ds = WriteArray(ls.get(), name, shape, values, units, description);
      for (std::size_t k = 0; k < scales.size(); ++k) {
        AttachScale(ds.get(), scales[k].get(), static_cast<unsigned>(k), f.axis_order[k]);
      }
    };
    put("theta", f.theta, f.im_units,
        "median capacity: exp(mean ln IM_c), or the censored maximum likelihood's");
    put("beta", f.beta, "1",
        "dispersion: standard deviation of ln IM_c (n - 1), or the censored maximum "
        "likelihood's");
    put("n_records", f.n, "1", "records with a finite capacity (cells done, status ok)");
    put("n_censored", f.censored, "1",
        "records not reaching the limit state up to ida.max_im (censored in the fit)");
    WriteStrings(ls.get(), "reason", f.reason);
    put("n_scaled_too_far", f.too_far, "1",
        "capacities reached at a scale factor above records.max_scale: censored at max_scale "
        "(in n_censored)");
    WriteStrings(ls.get(), "note", f.note);
  }
}

void WriteStudyTables(const Datasets& d, const CubeLayout& layout, const StudyTables& study) {
  for (std::size_t r = 0; r < layout.responses.size(); ++r) {
    if (layout.responses[r].name == "band" && !study.band_edges.empty()) {
      SetDoublesAttr(d.responses[r].get(), "band_edges", study.band_edges);
    }
  }
  if (!study.records.empty()) WriteRecordTable(d.group.get(), study);
  if (!study.im.measure.empty()) {
    SetAttr(d.group.get(), "im_measure", study.im.measure);
    SetAttr(d.group.get(), "im_description", spectra::IntensityDescription(study.im));
    SetAttr(d.group.get(), "im_units", spectra::IntensityUnit(study.im));
    SetAttr(d.group.get(), "im_scaled", static_cast<std::int64_t>(study.im.scale ? 1 : 0));
    SetAttr(
        d.group.get(), "max_scale",
        study.im.max_scale > 0.0 ? study.im.max_scale : std::numeric_limits<double>::infinity());
    if (study.scaled_too_far >= 0)
      SetAttr(d.group.get(), "scaled_too_far_count", study.scaled_too_far);
  }
  if (study.correlation) WriteCorrelation(d.group.get(), *study.correlation, study.band_edges);
  if (!study.fragility.empty()) WriteFragility(d.group.get(), study.fragility);
  if (!study.ida_fragility.empty()) WriteIdaFragility(d.group.get(), study.ida_fragility);
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
    SaveFileImage(image.file.get(), path.string());
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

namespace {

// Ranks waiting in the farm are released by a call with no jobs when the cube took another
// path (no cells) or failed before its chunks were handed out.
void ReleaseFarm(const ChunkFarm* farm, bool farmed) {
  if (farm != nullptr && !farmed) {
    (*farm)(
        0, [](std::size_t) { return std::vector<char>{}; },
        [](std::size_t, std::span<const char>) {});
  }
}

}  // namespace

std::vector<char> FilterFinalChunk(std::span<const char> raw, std::size_t element_size) {
  SB_DEMAND(element_size > 0 && raw.size() % element_size == 0, "a chunk of partial elements");
  // Shuffle (H5Z_filter_shuffle): byte b of element e goes to b * elements + e; a no-op for
  // one-byte elements.
  const std::size_t elements = raw.size() / element_size;
  std::vector<unsigned char> shuffled(raw.size());
  if (element_size > 1 && elements > 1) {
    for (std::size_t e = 0; e < elements; ++e) {
      for (std::size_t b = 0; b < element_size; ++b) {
        shuffled[b * elements + e] = static_cast<unsigned char>(raw[e * element_size + b]);
      }
    }
  } else {
    std::memcpy(shuffled.data(), raw.data(), raw.size());
  }
  // Deflate (H5Z_filter_deflate: compress2 into a compressBound buffer).
  uLongf packed = compressBound(static_cast<uLong>(shuffled.size()));
  std::vector<char> out(packed + 4);
  const int status = compress2(reinterpret_cast<Bytef*>(out.data()), &packed, shuffled.data(),
                               static_cast<uLong>(shuffled.size()), kDeflateLevel);
  SB_DEMAND(status == Z_OK, "zlib compress2 failed");
  // Fletcher-32 of the stored bytes, appended little-endian (H5Z_filter_fletcher32).
  const std::uint32_t sum = Fletcher32(reinterpret_cast<const unsigned char*>(out.data()), packed);
  for (int k = 0; k < 4; ++k) {
    out[packed + static_cast<std::size_t>(k)] = static_cast<char>((sum >> (8 * k)) & 0xff);
  }
  out.resize(packed + 4);
  return out;
}

std::vector<char> MakeChunkJob(std::span<const char> raw, std::size_t element_size) {
  SB_DEMAND(element_size > 0 && element_size < 256, "element size out of range");
  std::vector<char> job(raw.size() + 1);
  job[0] = static_cast<char>(element_size);
  std::memcpy(job.data() + 1, raw.data(), raw.size());
  return job;
}

std::vector<char> RunChunkJob(std::span<const char> job) {
  if (job.empty() || static_cast<unsigned char>(job[0]) == 0 ||
      (job.size() - 1) % static_cast<unsigned char>(job[0]) != 0) {
    throw std::runtime_error("not a chunk job (empty, or a partial element)");
  }
  return FilterFinalChunk(job.subspan(1), static_cast<unsigned char>(job[0]));
}

void CheckpointFile::Close() { impl_.reset(); }

void WriteFinalCube(const std::filesystem::path& path, const SweepSpec& spec,
                    const CubeLayout& layout, const CubeData& data, std::int32_t runs,
                    const std::string& created_utc,
                    const std::map<std::int32_t, std::string>& examples, const StudyTables* study,
                    const ChunkFarm* farm, bool cells_collectively) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  bool farmed = false;
  try {
    Datasets d = CreateLayout(tmp.string(), spec, layout, true, runs, created_utc);
    std::vector<Writable> per_cell = DataOf(d, data);
    per_cell.push_back({d.done.get(), H5T_NATIVE_UINT8, 1, data.done.data()});
    // A dataset of extent zero is contiguous (no chunks): nothing to farm, nothing to write.
    const bool chunked = spec.CellCount() > 0;
    if (cells_collectively) {
      // Written later by every rank (WriteFinalCellsCollective); the chunks are allocated then.
    } else if (farm != nullptr && chunked) {
      farmed = true;
      WriteChunksThroughFarm(per_cell, *farm);
    } else {
      for (const Writable& w : per_cell) {
        WriteAll(w.dataset, w.mem_type, w.data);
      }
    }
    if (study != nullptr) WriteStudyTables(d, layout, *study);
    std::vector<std::string> example_column;
    for (const auto& entry : layout.status_names) {
      const auto it = examples.find(entry.first);
      example_column.push_back(it == examples.end() ? "" : it->second);
    }
    SetAttr(d.group.get(), "status_examples", example_column);
    const bool all_done =
        std::all_of(data.done.begin(), data.done.end(), [](std::uint8_t v) { return v != 0; });
    SetAttr(d.group.get(), "completed_utc", UtcNow());
    SetAttr(d.group.get(), "complete",
            static_cast<std::int64_t>(all_done && !cells_collectively ? 1 : 0));
    SaveFileImage(d.file.get(), tmp.string());
  } catch (const H5Error& e) {
    ReleaseFarm(farm, farmed);
    throw H5Error(tmp.string() + ": " + e.what());
  } catch (...) {
    ReleaseFarm(farm, farmed);
    throw;
  }
  ReleaseFarm(farm, farmed);
  if (cells_collectively) {
    return;  // complete = 1 and the rename come after the cells (CompleteFinalCube)
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    throw H5Error("rename " + tmp.string() + " to " + path.string() + ": " + ec.message());
  }
}

std::string WriteFinalCellsCollective(const std::filesystem::path& path, const SweepSpec& spec,
                                      const CubeLayout& layout, const FinalCells& mine,
                                      const std::function<bool(bool)>& all_ok) {
  const std::string tmp = path.string() + ".tmp";
  const CubeData& data = mine.data;
  SB_DEMAND(data.Cells() == mine.cells.size() && data.responses.size() == layout.responses.size(),
            "final cells do not fit the layout");
  std::string error;
  auto attempt = [&](auto&& step) {
    if (error.empty()) {
      try {
        step();
      } catch (const H5Error& e) {
        error = tmp + ": " + e.what();
      }
    }
    return all_ok(error.empty());
  };
  // Local work first (a rank failing alone must not leave the others in a collective call):
  // one selection serves every per-cell dataset, all of the cube's shape.
  Id selection;
  if (!attempt([&] { selection = CellsSelection(ShapeOf(spec), mine.cells); })) {
    return error.empty() ? tmp + ": the collective write failed on another rank" : error;
  }
  // MPI-IO opens the file on every rank at once, and an open failing on some ranks only can
  // hang inside MPI_File_open: every rank first checks that it sees the file.
  if (!attempt([&] {
        std::error_code ec;
        if (!std::filesystem::exists(tmp, ec)) {
          throw H5Error(
              "not visible from every rank (the final cube's collective write needs "
              "its folder on a filesystem shared by all ranks)");
        }
      })) {
    return error.empty() ? tmp + ": the collective write failed on another rank" : error;
  }
  Id file;
  if (!attempt([&] { file = OpenFileParallel(tmp); })) {
    return error.empty() ? tmp + ": the collective write failed on another rank" : error;
  }
  const std::string group = GroupPath(spec.name) + "/";
  struct Column {
    std::string name;
    hid_t mem_type;
    const void* values;
  };
  std::vector<Column> columns;
  for (std::size_t r = 0; r < layout.responses.size(); ++r) {
    columns.push_back(
        {"responses/" + layout.responses[r].name, H5T_NATIVE_DOUBLE, data.responses[r].data()});
  }
  columns.push_back({"status", H5T_NATIVE_INT32, data.status.data()});
  columns.push_back({"stats/run", H5T_NATIVE_INT32, data.run.data()});
  columns.push_back({"stats/events", H5T_NATIVE_INT64, data.events.data()});
  columns.push_back({"stats/steps", H5T_NATIVE_INT64, data.steps.data()});
  columns.push_back({"stats/wall_s", H5T_NATIVE_DOUBLE, data.wall_s.data()});
  columns.push_back({"done", H5T_NATIVE_UINT8, data.done.data()});
  // Every rank takes the same steps: all_ok answers alike everywhere, so all stop together.
  bool all_good = true;
  for (const Column& c : columns) {
    all_good = attempt([&] {
      Id ds = OpenDataset(file.get(), group + c.name);
      WriteSelectedCollective(ds.get(), c.mem_type, selection.get(), mine.cells.size(), c.values);
    });
    if (!all_good) break;
  }
  if (all_good) {
    all_good = attempt([&] { Check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "H5Fflush (MPI-IO)"); });
  }
  file = Id();  // collective close
  if (!all_good && error.empty()) {
    return tmp + ": the collective write failed on another rank";
  }
  return error;
}

void CompleteFinalCube(const std::filesystem::path& path, const SweepSpec& spec) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  try {
    Id file = OpenFile(tmp.string(), true);
    Id g = OpenGroup(file.get(), GroupPath(spec.name));
    SetAttr(g.get(), "complete", static_cast<std::int64_t>(1));
    g = Id();
    FlushToDisk(file.get());
  } catch (const H5Error& e) {
    throw H5Error(tmp.string() + ": " + e.what());
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    throw H5Error("rename " + tmp.string() + " to " + path.string() + ": " + ec.message());
  }
}

namespace {

// Runs a reader, naming the file in an HDF5 failure (a damaged chunk fails its checksum).
template <typename F>
auto NamingFile(const std::filesystem::path& path, F&& read) -> decltype(read()) {
  try {
    return read();
  } catch (const H5Error& e) {
    throw H5Error(path.string() + ": " + e.what());
  }
}

std::vector<double> ReadSweepArrayIn(const std::filesystem::path& path, const std::string& sweep,
                                     const std::string& dataset) {
  const Datasets d = OpenLayout(path.string(), sweep, false, nullptr);
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
  Id ds = OpenDataset(d.group.get(), dataset);
  std::size_t n = 1;
  for (hsize_t extent : Shape(ds.get())) n *= extent;
  std::vector<double> out(n);
  ReadAll(ds.get(), H5T_NATIVE_DOUBLE, out.data());
  return out;
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

std::vector<std::vector<char>> ReadStoredChunks(const std::filesystem::path& path,
                                                const std::string& sweep,
                                                const std::string& dataset) {
  return NamingFile(path, [&] {
    const Datasets d = OpenLayout(path.string(), sweep, false, nullptr);
    if (!Exists(d.group.get(), dataset)) {
      throw InputError::AtLine(path.string(), 0,
                               "sweep '" + sweep + "' holds no dataset '" + dataset + "'");
    }
    Id ds = OpenDataset(d.group.get(), dataset);
    Id type(H5Dget_type(ds.get()), H5Tclose, "H5Dget_type " + dataset);
    const ChunkSource grid(ds.get(), type.get(), H5Tget_size(type.get()), nullptr);
    std::vector<std::vector<char>> out;
    for (std::uint64_t j = 0; j < grid.chunks; ++j) {
      const std::vector<hsize_t> offset = grid.Offset(j);
      hsize_t bytes = 0;
      Check(H5Dget_chunk_storage_size(ds.get(), offset.data(), &bytes),
            "H5Dget_chunk_storage_size " + dataset);
      std::vector<char> stored(bytes);
      std::uint32_t mask = 0;
      Check(H5Dread_chunk(ds.get(), H5P_DEFAULT, offset.data(), &mask, stored.data()),
            "H5Dread_chunk " + dataset);
      SB_DEMAND(mask == 0, "a chunk stored with a filter skipped");
      out.push_back(std::move(stored));
    }
    return out;
  });
}

std::vector<SweepSummary> SummarizeCube(const std::filesystem::path& path) {
  return NamingFile(path, [&] { return SummarizeCubeIn(path); });
}

CubeData ReadCubeData(const std::filesystem::path& path, const std::string& sweep,
                      std::vector<std::string>* response_names) {
  return NamingFile(path, [&] { return ReadCubeDataIn(path, sweep, response_names); });
}

std::string ResponseLinkName(const std::string& response, const SweepSpec& spec) {
  static constexpr std::array<std::string_view, 10> kGroupMembers{
      "axes", "responses", "fixed",       "stats",  "status",
      "done", "records",   "correlation", "inputs", "fragility"};
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
