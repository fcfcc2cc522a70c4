#pragma once
/// @file
/// A thin RAII layer over the HDF5 C API, private to jobs/h5: every call is checked and a
/// failure throws H5Error naming the call and the object. Only the files of jobs/h5 include it.

#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "jobs/h5/h5_error.h"

namespace skewbridge::jobs::h5 {

/// The reason of the last failed HDF5 call, from the library's error stack (which it clears):
/// the system's errno text when a file driver failed (e.g. "No space left on device"), a
/// checksum mismatch, or the most specific description.
std::string ErrorReason();
/// Throws H5Error("what: reason") when status < 0; returns status otherwise.
herr_t Check(herr_t status, std::string_view what);
/// Throws when id < 0 (an invalid identifier); returns id otherwise.
hid_t CheckId(hid_t id, std::string_view what);

/// Owns one HDF5 identifier and closes it with the matching H5?close.
class Id {
 public:
  using Closer = herr_t (*)(hid_t);
  Id() = default;
  /// Takes ownership of a checked identifier. @throws H5Error when id < 0.
  Id(hid_t id, Closer closer, std::string_view what) : id_(CheckId(id, what)), closer_(closer) {}
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  Id(Id&& other) noexcept : id_(other.id_), closer_(other.closer_) { other.id_ = -1; }
  /// Closes the identifier held, then takes over other's.
  Id& operator=(Id&& other) noexcept;
  /// Closes the identifier (a close failure cannot be reported from a destructor).
  ~Id();
  /// The raw identifier for C API calls.
  hid_t get() const { return id_; }

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

/// The path of an object in its file, for messages ("" when HDF5 cannot tell).
std::string ObjectName(hid_t obj);

/// Silences HDF5's automatic error stack printing (libraries never print); errors are thrown.
void SilenceErrorStack();

/// The file access of every cube file: no file locks (readers may open a running sweep's
/// checkpoint), the 1.8 object format (checksummed metadata) or later.
Id UnlockedAccess();
/// A file created (truncating) or opened; @throws H5Error.
Id CreateFile(const std::string& path);
/// Where a file built in memory (CreateMemoryFile) lies: an anonymous mapping that HDF5's core
/// driver grows through the file image callbacks (aligned to 2 MiB for huge pages where the
/// kernel gives them: a cube of 30 000 cells is tens of megabytes, and each 4 kB page's first
/// touch is a fault), so that SaveFileImage writes the bytes from where HDF5 put them.
struct FileMemory {
  unsigned char* base = nullptr;  ///< the mapping, nullptr before the first write
  std::size_t capacity = 0;       ///< its length [byte]
  std::size_t expected = 0;       ///< the creator's estimate of the file's length, 0: none [byte]
  /// The holders: the MemoryFile's handle, and the driver while it holds the mapping (its free
  /// callback at the file's close releases it), so that either may go first.
  int holders = 1;
};
/// Releases one holder of a FileMemory, deleting it with the last.
struct ReleaseFileMemory {
  /// Drops the handle's hold.
  void operator()(FileMemory* memory) const;
};
/// The handle of a file's memory held by its creator.
using FileMemoryHandle = std::unique_ptr<FileMemory, ReleaseFileMemory>;
/// A file held in memory and its memory.
struct MemoryFile {
  FileMemoryHandle memory;
  Id file;
};
/// A file held in memory (HDF5's core driver, no backing store), to be written out whole by
/// SaveFileImage; `name` is only a label. Its first mapping is `expected_bytes` long (an estimate
/// of the whole file, so that it need not grow; untouched pages cost no memory) when that is
/// more than the driver asks. @throws H5Error.
MemoryFile CreateMemoryFile(const std::string& name, std::size_t expected_bytes = 0);
/// Opens an existing file read-only or read-write; @throws H5Error when not an HDF5 file.
Id OpenFile(const std::string& path, bool writable);
/// Collective over MPI_COMM_WORLD: opens an existing file read-write through MPI-IO (parallel
/// HDF5; the communicator comes with <hdf5.h> of the parallel build). @throws H5Error.
Id OpenFileParallel(const std::string& path);
/// A dataspace of `shape` selecting the given cells (row-major linear indices, increasing) as
/// the union of the boxes of their runs of consecutive cells; nothing selected when empty.
Id CellsSelection(std::span<const hsize_t> shape, std::span<const std::uint64_t> cells);
/// Collective (parallel HDF5): writes `count` packed values (in increasing cell order) into the
/// cells selected in `file_space` (CellsSelection); every rank calls it, with or without cells.
void WriteSelectedCollective(hid_t dataset, hid_t mem_type, hid_t file_space, std::uint64_t count,
                             const void* packed);
/// Creates a group (intermediate groups too).
Id CreateGroup(hid_t parent, const std::string& name);
/// Opens a group. @throws H5Error when absent.
Id OpenGroup(hid_t parent, const std::string& name);
/// Whether a link of this name exists directly under parent.
bool Exists(hid_t parent, const std::string& name);
/// Names of the links directly under a group, in name order.
std::vector<std::string> ListChildren(hid_t group);

/// A simple dataspace of the given shape.
Id Dataspace(std::span<const hsize_t> shape);
/// A variable-length UTF-8 string type.
Id StringType();

/// Chunks of about 8192 elements holding whole rows along the last axis.
std::vector<hsize_t> DefaultChunk(std::span<const hsize_t> shape);
/// Creates a dataset, chunked (DefaultChunk when chunk is empty) with the Fletcher-32 checksum
/// that H5Dread verifies: deflate_level > 0 adds shuffle + deflate(level); deflate_level 0
/// allocates every chunk at creation (later writes only rewrite chunks in place). A dataset
/// with an extent of zero or of variable-length strings (which HDF5 cannot filter) is
/// contiguous, without checksum. fill may be nullptr.
Id CreateDataset(hid_t parent, const std::string& name, hid_t type, std::span<const hsize_t> shape,
                 std::span<const hsize_t> chunk, int deflate_level, const void* fill);
/// Opens a dataset. @throws H5Error when absent.
Id OpenDataset(hid_t parent, const std::string& name);
/// The shape of a dataset.
std::vector<hsize_t> Shape(hid_t dataset);
/// Writes a whole dataset from memory of the given type.
void WriteAll(hid_t dataset, hid_t mem_type, const void* data);
/// Reads a whole dataset into memory of the given type.
void ReadAll(hid_t dataset, hid_t mem_type, void* data);
/// Writes the listed cells (row-major linear indices into the dataset) from a full-size
/// in-memory array of element size `elem_size`.
void WriteCells(hid_t dataset, hid_t mem_type, std::size_t elem_size, const void* full,
                std::span<const std::uint64_t> cells);
/// A 1-D dataset of strings.
void WriteStrings(hid_t parent, const std::string& name, const std::vector<std::string>& v);
/// Reads a 1-D dataset of variable-length strings.
std::vector<std::string> ReadStrings(hid_t dataset);

/// Writes a scalar UTF-8 string attribute (replacing one of the same name).
void SetAttr(hid_t obj, const std::string& name, const std::string& value);
/// Writes a scalar int64 attribute (replacing one of the same name).
void SetAttr(hid_t obj, const std::string& name, std::int64_t value);
/// Writes a scalar float64 attribute (replacing one of the same name).
void SetAttr(hid_t obj, const std::string& name, double value);
/// Writes a 1-D attribute of UTF-8 strings (replacing one of the same name).
void SetAttr(hid_t obj, const std::string& name, const std::vector<std::string>& values);
/// Writes a 1-D int32 attribute (replacing one of the same name).
void SetAttr(hid_t obj, const std::string& name, const std::vector<std::int32_t>& values);
/// Reads a scalar string attribute. @throws H5Error when absent or not a string.
std::string GetStringAttr(hid_t obj, const std::string& name);
/// Reads a scalar integer attribute. @throws H5Error when absent or not convertible.
std::int64_t GetIntAttr(hid_t obj, const std::string& name);
/// Reads a scalar floating-point attribute. @throws H5Error when absent or not convertible.
double GetDoubleAttr(hid_t obj, const std::string& name);
/// Whether the attribute `name` of obj holds strings. @throws H5Error when absent.
bool IsStringAttr(hid_t obj, const std::string& name);
/// Reads a 1-D string attribute. @throws H5Error when absent or not strings.
std::vector<std::string> GetStringListAttr(hid_t obj, const std::string& name);
/// Reads a 1-D integer attribute as int32. @throws H5Error when absent or not convertible.
std::vector<std::int32_t> GetIntListAttr(hid_t obj, const std::string& name);
/// Whether obj has an attribute of this name.
bool HasAttr(hid_t obj, const std::string& name);

/// Makes `scale` a dimension scale named `name` and attaches it to dimension dim of dataset.
void AttachScale(hid_t dataset, hid_t scale, unsigned dim, const std::string& label);
/// Marks a dataset as a dimension scale.
void SetScale(hid_t scale, const std::string& name);

/// Opens every object of a file and reads every attribute, so that damaged metadata (whose
/// checksums HDF5 verifies on read) is found before a file is opened for writing.
/// @throws H5Error naming the failure.
void ReadAllMetadata(hid_t file);

/// Whether SaveFileImage waits for the bytes to reach the disk (fsync) before it returns.
enum class Durability {
  kOnDisk,   ///< fsync: the file survives a crash of the machine
  kWritten,  ///< handed to the system only: a later fsync of the file makes it durable
};

/// Writes the bytes of a file built in memory (CreateMemoryFile: the file and its memory) to
/// `path` with plain writes,
/// then fsync unless `durability` is kWritten: the bytes of H5Fget_file_image (the superblock's
/// status flags cleared, its checksum made to match), written from the driver's memory with
/// only the superblock copied. A failure (a full disk) removes what was written
/// and throws H5Error naming the system call and the system's reason (the caller adds the path);
/// HDF5 itself never meets the failing write, since a failed flush leaves its metadata cache
/// unable to close the file (and its shutdown then crashes).
void SaveFileImage(hid_t file, const FileMemory& memory, const std::string& path,
                   Durability durability = Durability::kOnDisk);
/// The bytes of a flushed memory file as H5Fget_file_image copies them out, the superblock's
/// checksum repaired: what SaveFileImage writes (the reference it is checked against, and its
/// way when the driver's memory does not start with the superblock it expects).
std::vector<char> CopyFileImage(hid_t file);

/// H5Fflush, then fsync of the file descriptor, so the bytes survive a crash of the process
/// and of the machine.
void FlushToDisk(hid_t file);

}  // namespace skewbridge::jobs::h5
