#pragma once
/// @file
/// Sweep cubes in HDF5 (docs/hdf5-layout.md): the checkpoint file FILE.partial that a running
/// sweep fills cell by cell (cube_checkpoint.cpp), the final compressed FILE (cube_final.cpp),
/// and readers for inspect and tests (cube_reader.cpp). Free of <hdf5.h>; failures of HDF5 calls
/// throw h5::H5Error.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "jobs/cube.h"
#include "jobs/h5/h5_error.h"
#include "jobs/study.h"
#include "jobs/sweep_spec.h"

namespace skewbridge::jobs::h5 {

/// The format name stored in the root attribute "format".
inline constexpr const char* kCubeFormat = "skewbridge-cube";
/// The version stored in the root attribute "format_version".
inline constexpr std::int64_t kCubeFormatVersion = 1;

/// The checkpoint file of a running sweep: uncompressed chunks with Fletcher-32 checksums,
/// every chunk allocated at creation, so that after creation only raw bytes change in place
/// and a process killed at any moment leaves a readable file whose done mask never covers
/// missing data.
class CheckpointFile {
 public:
  /// Creates (truncating) the file with all metadata, axes and fill values, and flushes it.
  /// @throws H5Error on I/O failure.
  static CheckpointFile Create(const std::filesystem::path& path, const SweepSpec& spec,
                               const CubeLayout& layout);
  /// Opens an existing checkpoint for resume, refusing a different specification, reads
  /// its cells into `data` (not-done cells reset to fill values) and starts run number
  /// runs + 1. Every refusal is decided read-only, so a refused file is left unchanged.
  /// Every dataset is read through its Fletcher-32 checksum, and every done cell must carry a
  /// status of the layout's table and the number of a past run.
  /// @throws InputError for a foreign file, a different spec hash or axis order, a missing
  /// or differently shaped dataset of `layout` (e.g. responses/band in a file of an older
  /// program version), a chunk failing its checksum, or a done cell without computed data
  /// (corruption), naming the file and the dataset.
  static CheckpointFile Resume(const std::filesystem::path& path, const SweepSpec& spec,
                               const CubeLayout& layout, CubeData& data);

  CheckpointFile(CheckpointFile&&) noexcept;
  CheckpointFile& operator=(CheckpointFile&&) noexcept;
  ~CheckpointFile();

  /// The number of this run (1 for a fresh sweep).
  std::int32_t Run() const;
  /// The creation time of the sweep (UTC, ISO 8601), kept across resumes.
  std::string CreatedUtc() const;
  /// Writes the listed cells: data, flush + fsync, then their done flags, flush + fsync
  /// (a crash in between loses those cells, never marks missing ones as done).
  void Write(const CubeData& data, std::span<const std::uint64_t> cells);
  /// Closes the file.
  void Close();

 private:
  struct Impl;
  explicit CheckpointFile(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// The bytes HDF5 stores for one chunk of a final-cube dataset: the raw chunk (native = file
/// byte order, little-endian) byte-shuffled by `element_size`, deflated at the final cube's
/// level (zlib compress2, as HDF5's deflate filter), then its Fletcher-32 checksum appended
/// (HDF5's filter order and encoding), ready for a direct chunk write with filter mask 0.
/// Pure computation (no HDF5 call): any process or thread may run it.
std::vector<char> FilterFinalChunk(std::span<const char> raw, std::size_t element_size);
/// One chunk to filter as one message: the element size (one byte) then the raw chunk.
std::vector<char> MakeChunkJob(std::span<const char> raw, std::size_t element_size);
/// FilterFinalChunk applied to a message of MakeChunkJob. @throws std::runtime_error when the
/// message is empty or its length is not a multiple of its element size.
std::vector<char> RunChunkJob(std::span<const char> job);

/// Runs `count` chunk jobs (job(i) makes the message of job i, MakeChunkJob) through
/// RunChunkJob, anywhere (other ranks: Transport::Farm), and hands each result to done(i,
/// bytes) on the calling process, in any order; done may throw, and the farm still ends.
using ChunkFarm =
    std::function<void(std::size_t count, const std::function<std::vector<char>(std::size_t)>& job,
                       const std::function<void(std::size_t, std::span<const char>)>& done)>;

/// Writes the final cube: chunked (contiguous along the last axis), shuffle + deflate +
/// Fletcher-32 checksum, the
/// attribute complete = 1 written last. Writes path + ".tmp" and renames it to path.
/// examples: one message per failure status (status -> "cell N: text"), stored as the sweep
/// group's attribute status_examples, aligned with the status dataset's status_codes.
/// study (may be null): the record table, the band edges and the correlation statistics
/// (MakeStudyTables), written as the groups records/ and correlation/ and the attribute
/// band_edges of responses/band.
/// farm (may be null): filters the chunks of the per-cell datasets (the 0.65-1 us per cell of
/// deflate) elsewhere, each written back with a direct chunk write; the file's bytes are those
/// of the serial path (HDF5's own filters), which runs when farm is null. It is called exactly
/// once, with count 0 when an error comes first, so that ranks waiting in it are released.
/// @throws H5Error on I/O failure.
void WriteFinalCube(const std::filesystem::path& path, const SweepSpec& spec,
                    const CubeLayout& layout, const CubeData& data, std::int32_t runs,
                    const std::string& created_utc,
                    const std::map<std::int32_t, std::string>& examples = {},
                    const StudyTables* study = nullptr, const ChunkFarm* farm = nullptr,
                    bool cells_collectively = false);

/// The cells one rank writes into the final cube collectively, in increasing cell order:
/// cells[i] is the linear index of row i of data (data.Cells() == cells.size()).
struct FinalCells {
  std::vector<std::uint64_t> cells;  ///< increasing linear cell indices
  CubeData data;                     ///< their columns, in the cube layout's response order
};

/// Collective over every rank of MPI_COMM_WORLD, after rank 0 wrote path + ".tmp" with
/// WriteFinalCube(..., cells_collectively = true): each rank writes its cells into the
/// per-cell datasets with parallel HDF5's filtered collective writes (each chunk gathered to
/// one rank, filtered there, written through MPI-IO), so that no rank handles more than its
/// share of the cube. all_ok(mine) must be collective and return whether every rank passed
/// true; it is called after each step so that the ranks stop together. Returns "" or the
/// failure (the same success on every rank; the text of this rank's failure, if any).
std::string WriteFinalCellsCollective(const std::filesystem::path& path, const SweepSpec& spec,
                                      const CubeLayout& layout, const FinalCells& mine,
                                      const std::function<bool(bool)>& all_ok);

/// Rank 0, after WriteFinalCellsCollective: sets complete = 1 in path + ".tmp", flushes it to
/// disk and renames it to path. @throws H5Error on I/O failure.
void CompleteFinalCube(const std::filesystem::path& path, const SweepSpec& spec);

/// The stored (filtered) bytes of every chunk of one dataset of a sweep, in the order of the
/// chunk grid (row-major), as HDF5 keeps them on disk: for tests comparing the two write paths.
/// @throws InputError when the file, sweep or dataset is absent.
std::vector<std::vector<char>> ReadStoredChunks(const std::filesystem::path& path,
                                                const std::string& sweep,
                                                const std::string& dataset);

/// One axis as stored in a cube.
struct AxisSummary {
  std::string name;
  std::string unit;
  std::size_t size = 0;
  std::vector<double> values;       ///< Numeric axes.
  std::vector<std::string> labels;  ///< Label axes.
};

/// One parameter held constant over a sweep (`fixed/` of the cube), as stored.
struct FixedSummary {
  std::string key;   ///< The parameter key (jobs::KnownParameters()).
  std::string unit;  ///< "1" when dimensionless, "" for labels, else e.g. "deg", "s".
  bool is_label = false;
  double value = 0.0;  ///< For numbers, in `unit`.
  std::string label;   ///< For labels.
};

/// A sweep group as `skewbridge inspect` reports it.
struct SweepSummary {
  std::string name;
  std::string family;
  std::string spec_hash;
  std::string spec_canonical;    ///< SweepSpec::CanonicalText when the sweep was begun.
  std::string inputs_canonical;  ///< SweepSpec::InputsText then ("" in older cubes).
  std::string spec_text;         ///< The specification file verbatim (SweepSpec::text).
  std::string spec_source;       ///< Where the sweep read it (SweepSpec::source), for its folder.
  std::string created_utc;
  std::string program_version;
  bool complete = false;
  std::int64_t runs = 0;
  std::vector<AxisSummary> axes;
  std::vector<FixedSummary> fixed;    ///< In the order of fixed/ keys.
  std::vector<std::string> children;  ///< Names of the sweep group's members (groups, datasets).
  std::vector<ResponseInfo> responses;
  std::uint64_t cells = 0;
  std::uint64_t done = 0;
  std::map<std::string, std::uint64_t> done_by_status;  ///< Status name -> done cells.
  std::map<std::string, std::string> status_examples;   ///< Status name -> one message.
  /// The files the cells were computed from (inputs/: role, file relative to the spec's folder,
  /// sha256 and bytes when the sweep was begun; `path` left empty); none in older cubes.
  std::vector<InputFile> inputs;
};

/// Reads the summary of every sweep in a cube (final or checkpoint).
/// @throws InputError when the file is not a skewbridge cube; H5Error naming the file, the
/// object and the reason when a read fails (e.g. a chunk failing its checksum).
std::vector<SweepSummary> SummarizeCube(const std::filesystem::path& path);

/// Reads the per-cell arrays of one sweep, with the response names in stored order.
/// @throws InputError when the file or sweep is absent.
CubeData ReadCubeData(const std::filesystem::path& path, const std::string& sweep,
                      std::vector<std::string>* response_names);

/// Reads a numeric dataset of a sweep group as float64, flattened row-major, e.g.
/// "correlation/pearson_theta_Le" or "records/L_e_m".
/// @throws InputError when the file, sweep or dataset is absent.
std::vector<double> ReadSweepArray(const std::filesystem::path& path, const std::string& sweep,
                                   const std::string& dataset);

/// Reads a one-dimensional string dataset of a sweep group, e.g. "fragility/unseating/reason".
/// @throws InputError when the file, sweep or dataset is absent.
std::vector<std::string> ReadSweepStrings(const std::filesystem::path& path,
                                          const std::string& sweep, const std::string& dataset);

/// The name of a response's second link in the sweep group, beside the axis scales (the
/// xarray view): the response's name, or "response_" + name when an axis or a member of the
/// sweep group (axes, status, records, ...) has that name. responses/<name> always holds it.
std::string ResponseLinkName(const std::string& response, const SweepSpec& spec);

/// Current UTC time as "YYYY-MM-DDTHH:MM:SSZ".
std::string UtcNow();

}  // namespace skewbridge::jobs::h5
