#pragma once
/// @file
/// The datasets of a sweep group (docs/hdf5-layout.md), shared by the checkpoint
/// (cube_checkpoint.cpp), the final cube (cube_final.cpp) and the readers (cube_reader.cpp):
/// the group created with its metadata, axes and per-cell datasets, or opened whole. Private to
/// jobs/h5 (it includes h5.h): only jobs/h5/cube_*.cpp include it.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "jobs/cube.h"
#include "jobs/h5/cube_file.h"
#include "jobs/h5/h5.h"
#include "jobs/sweep_spec.h"

namespace skewbridge::jobs::h5 {

/// The zlib level of the final cube's deflate filter (the checkpoint's chunks are not deflated).
inline constexpr int kDeflateLevel = 4;

/// The path of a sweep's group in a cube: "sweeps/<sweep>".
inline std::string GroupPath(const std::string& sweep) { return "sweeps/" + sweep; }

/// The shape of the sweep's cube (one extent per axis, in axis order) as HDF5 extents.
std::vector<hsize_t> ShapeOf(const SweepSpec& spec);

/// The datasets of one sweep group, opened or created.
struct Datasets {
  FileMemoryHandle memory;    ///< the memory of a cube being created (CreateMemoryFile)
  Id file;                    ///< the cube (in memory while it is being created)
  Id group;                   ///< sweeps/<name>
  std::vector<Id> responses;  ///< responses/<name>, in the layout's response order
  Id status, done, run, events, steps, wall_s;  ///< the per-cell status, flags and statistics
};

/// One per-cell dataset with the column in memory written into it.
struct Writable {
  hid_t dataset;     ///< the dataset (not owned)
  hid_t mem_type;    ///< the HDF5 type of the column in memory
  std::size_t size;  ///< bytes per element
  const void* data;  ///< the column, one element per cell in linear cell order
};

/// The per-cell datasets but `done`, each with its column of `data`.
std::vector<Writable> DataOf(const Datasets& d, const CubeData& data);

/// Creates a sweep group with every attribute, the fixed values, the inputs table, the axes
/// (dimension scales) and the per-cell datasets at their fill values, in an in-memory file that
/// SaveFileImage writes out whole. final: chunks deflated at kDeflateLevel, else uncompressed
/// and allocated at creation (the checkpoint's, rewritten in place). Both carry Fletcher-32.
/// @throws H5Error on an HDF5 failure.
Datasets CreateLayout(const std::string& path, const SweepSpec& spec, const CubeLayout& layout,
                      bool final, std::int32_t runs, const std::string& created_utc);

/// Opens the sweep group `sweep` of an existing cube and its per-cell datasets in the stored
/// response order (returned in response_names when not null).
/// @throws InputError when the file is not an HDF5 file, not a skewbridge cube, or has no such
/// sweep; H5Error when a dataset is missing.
Datasets OpenLayout(const std::string& path, const std::string& sweep, bool writable,
                    std::vector<std::string>* response_names);

/// The number of elements of a dataset (the cells of a per-cell dataset).
std::uint64_t CellsOf(hid_t dataset);

/// Reads every per-cell dataset of `d` into `data`, reset to their cell and response counts.
void ReadData(const Datasets& d, CubeData& data);

/// Runs a reader, naming the file in an HDF5 failure (a damaged chunk fails its checksum).
template <typename F>
auto NamingFile(const std::filesystem::path& path, F&& read) -> decltype(read()) {
  try {
    return read();
  } catch (const H5Error& e) {
    throw H5Error(path.string() + ": " + e.what());
  }
}

}  // namespace skewbridge::jobs::h5
