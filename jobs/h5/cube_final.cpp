#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "jobs/h5/cube_file.h"
#include "jobs/h5/cube_layout.h"
#include "jobs/h5/cube_study_tables.h"
#include "solver/common/error.h"

namespace skewbridge::jobs::h5 {
namespace {

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
    SaveFileImage(d.file.get(), *d.memory, tmp.string());
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

}  // namespace skewbridge::jobs::h5
