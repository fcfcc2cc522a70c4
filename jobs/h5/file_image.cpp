// Files built in memory (h5.h: CreateMemoryFile, SaveFileImage): the core driver's memory
// through the file image callbacks, and the image written from it.

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>

#include "jobs/h5/h5.h"

namespace skewbridge::jobs::h5 {

namespace {

// The core driver's memory as file image callbacks (each behaves as its C library namesake, on
// the FileMemory passed as udata): one anonymous mapping that starts on a 2 MiB boundary and is
// a whole number of 2 MiB pages long, advised for transparent huge pages, so that the first
// touch of each 2 MiB faults in one huge page where the kernel has them instead of 512 pages of
// 4 kB. Its first length is the creator's estimate of the file (FileMemory::expected) when
// that is larger than what the driver asks; it grows at least twofold into a new aligned range
// by mremap (which moves page tables, huge pages whole, not bytes). The driver still grows its
// file by its increment and zeroes each new part; those parts lie in memory the mapping holds.
constexpr std::size_t kImagePage = std::size_t{1} << 21;

std::size_t RoundUpToImagePage(std::size_t bytes) {
  return (bytes + kImagePage - 1) / kImagePage * kImagePage;
}

// An anonymous read-write mapping of `bytes` (a multiple of kImagePage) at a multiple of
// kImagePage, or MAP_FAILED: a mapping one page longer, its unaligned head and tail unmapped.
void* MapAligned(std::size_t bytes) {
  if (bytes > SIZE_MAX - kImagePage) {
    return MAP_FAILED;
  }
  void* raw = ::mmap(nullptr, bytes + kImagePage, PROT_READ | PROT_WRITE,
                     MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) {
    return MAP_FAILED;
  }
  const auto at = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t aligned = (at + kImagePage - 1) / kImagePage * kImagePage;
  const std::size_t head = aligned - at;
  if (head > 0) {
    ::munmap(raw, head);
  }
  ::munmap(reinterpret_cast<void*>(aligned + bytes), kImagePage - head);  // never empty
  return reinterpret_cast<void*>(aligned);
}

void* ImageRealloc(void* ptr, std::size_t size, H5FD_file_image_op_t /*op*/, void* udata) {
  auto* memory = static_cast<FileMemory*>(udata);
  if (ptr != memory->base) {
    return nullptr;  // not this file's memory: the callbacks serve one file
  }
  if (ptr != nullptr && size <= memory->capacity) {
    return ptr;
  }
  std::size_t capacity = RoundUpToImagePage(std::max(size, 2 * memory->capacity));
  void* at = MAP_FAILED;
  if (ptr == nullptr && memory->expected > capacity) {
    capacity = RoundUpToImagePage(memory->expected);
    at = MapAligned(capacity);
    if (at == MAP_FAILED) {  // the estimate refused: what the driver asks, grown as it needs
      capacity = RoundUpToImagePage(size);
    }
  }
  if (at == MAP_FAILED) {
    at = MapAligned(capacity);
  }
  if (at == MAP_FAILED) {
    return nullptr;
  }
  if (ptr != nullptr && ::mremap(ptr, memory->capacity, memory->capacity,
                                 MREMAP_MAYMOVE | MREMAP_FIXED, at) == MAP_FAILED) {
    ::munmap(at, capacity);
    return nullptr;
  }
  ::madvise(at, capacity, MADV_HUGEPAGE);  // advice only: 4 kB pages where it is refused
  if (memory->base == nullptr) {
    ++memory->holders;  // the driver's, until its free callback
  }
  memory->base = static_cast<unsigned char*>(at);
  memory->capacity = capacity;
  return at;
}

void* ImageMalloc(std::size_t size, H5FD_file_image_op_t op, void* udata) {
  return ImageRealloc(nullptr, size, op, udata);
}

void* ImageMemcpy(void* dest, const void* src, std::size_t size, H5FD_file_image_op_t /*op*/,
                  void* /*udata*/) {
  return std::memcpy(dest, src, size);
}

herr_t ImageFree(void* ptr, H5FD_file_image_op_t /*op*/, void* udata) {
  auto* memory = static_cast<FileMemory*>(udata);
  if (ptr == nullptr) {
    return 0;
  }
  if (ptr != memory->base || ::munmap(ptr, memory->capacity) != 0) {
    return -1;
  }
  memory->base = nullptr;
  memory->capacity = 0;
  ReleaseFileMemory{}(memory);
  return 0;
}

// Property lists share the pointer without holding the FileMemory: only the driver and the
// MemoryFile do.
void* UdataCopy(void* udata) { return udata; }
herr_t UdataFree(void* /*udata*/) { return 0; }

}  // namespace

void ReleaseFileMemory::operator()(FileMemory* memory) const {
  if (--memory->holders == 0) {
    delete memory;
  }
}

MemoryFile CreateMemoryFile(const std::string& name, std::size_t expected_bytes) {
  SilenceErrorStack();
  MemoryFile out;
  out.memory = FileMemoryHandle(new FileMemory);
  out.memory->expected = expected_bytes;
  Id fapl = UnlockedAccess();
  Check(H5Pset_fapl_core(fapl.get(), 1 << 20, false), "H5Pset_fapl_core " + name);
  H5FD_file_image_callbacks_t callbacks{ImageMalloc, ImageMemcpy, ImageRealloc,    ImageFree,
                                        UdataCopy,   UdataFree,   out.memory.get()};
  Check(H5Pset_file_image_callbacks(fapl.get(), &callbacks), "H5Pset_file_image_callbacks " + name);
  out.file = Id(H5Fcreate(name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose,
                "create file in memory " + name);
  return out;
}

// HDF5's metadata checksum (Jenkins' lookup3), exported by the library though not in its
// public headers.
extern "C" std::uint32_t H5_checksum_metadata(const void* data, std::size_t len,
                                              std::uint32_t initval);

namespace {

// The superblock of the 1.8 object format (version 2, the lower bound of UnlockedAccess):
// signature (8 bytes), version, the sizes of offsets and lengths, the status flags (byte 11),
// four addresses, then the checksum of the bytes before it (Jenkins' lookup3).
constexpr std::size_t kStatusFlagsAt = 11;

// The length of a version-2 superblock's bytes before its checksum, or 0 when `image` does not
// start with one.
std::size_t SuperblockBody(std::span<const char> image) {
  if (image.size() < 64 || image[8] != 2) {
    return 0;
  }
  const std::size_t offsets = static_cast<unsigned char>(image[9]);
  const std::size_t body = 12 + 4 * offsets;
  return offsets == 0 || body + 4 > image.size() ? 0 : body;
}

// The checksum stored after a superblock's `body` bytes (little-endian, as the file stores it).
std::uint32_t StoredChecksum(std::span<const char> image, std::size_t body) {
  std::uint32_t stored = 0;
  std::memcpy(&stored, image.data() + body, 4);
  return stored;
}

// HDF5 1.10 clears the "open for writing" flag of a version-2 superblock in the image it hands
// out but leaves the checksum computed with the flag set, so the image would not open. When the
// stored checksum is exactly that of the flag set, it is recomputed for the bytes as they are.
void RepairSuperblockChecksum(std::vector<char>& image) {
  const std::size_t body = SuperblockBody(image);
  if (body == 0 || image[kStatusFlagsAt] != 0) {
    return;
  }
  const std::uint32_t stored = StoredChecksum(image, body);
  std::vector<char> open_for_write(image.begin(), image.begin() + static_cast<long>(body));
  open_for_write[kStatusFlagsAt] = 1;
  if (H5_checksum_metadata(open_for_write.data(), body, 0) != stored) {
    return;  // not the known case: leave the image as HDF5 made it
  }
  const std::uint32_t fixed = H5_checksum_metadata(image.data(), body, 0);
  std::memcpy(image.data() + body, &fixed, 4);
}

// Writes `bytes` whole to fd (retrying short writes); false with errno on failure.
bool WriteWhole(int fd, const char* bytes, std::size_t size) {
  for (std::size_t at = 0; at < size;) {
    const ssize_t n = ::write(fd, bytes + at, size - at);
    if (n < 0 && errno == EINTR) {
      continue;
    }
    if (n <= 0) {
      if (n == 0) errno = EIO;
      return false;
    }
    at += static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

std::vector<char> CopyFileImage(hid_t file) {
  const ssize_t size = H5Fget_file_image(file, nullptr, 0);
  Check(size < 0 ? -1 : 0, "H5Fget_file_image");
  std::vector<char> image(static_cast<std::size_t>(size));
  Check(H5Fget_file_image(file, image.data(), image.size()) < 0 ? -1 : 0, "H5Fget_file_image");
  RepairSuperblockChecksum(image);
  return image;
}

void SaveFileImage(hid_t id, const FileMemory& memory, const std::string& path,
                   Durability durability) {
  Check(H5Fflush(id, H5F_SCOPE_LOCAL), "H5Fflush (memory) " + path);
  // The image is the driver's memory up to the end of the file's allocated space (what
  // H5Fget_file_image copies), with the superblock as H5Fget_file_image and
  // RepairSuperblockChecksum leave it: status flags cleared, checksum of the bytes as they are.
  const ssize_t size = H5Fget_file_image(id, nullptr, 0);
  Check(size < 0 ? -1 : 0, "H5Fget_file_image " + path);
  const std::size_t bytes = static_cast<std::size_t>(size);
  std::span<const char> image(reinterpret_cast<const char*>(memory.base), bytes);
  const std::size_t body =
      memory.base != nullptr && bytes <= memory.capacity ? SuperblockBody(image) : 0;
  std::vector<char> head;
  std::vector<char> copy;
  if (body != 0 && H5_checksum_metadata(image.data(), body, 0) == StoredChecksum(image, body)) {
    head.assign(image.begin(), image.begin() + static_cast<long>(body + 4));
    head[kStatusFlagsAt] = 0;
    const std::uint32_t sum = H5_checksum_metadata(head.data(), body, 0);
    std::memcpy(head.data() + body, &sum, 4);
    image = image.subspan(body + 4);
  } else {
    copy = CopyFileImage(id);  // not the superblock expected: HDF5's own copy
    image = copy;
  }
  auto fail = [&path](const char* what, int fd) {
    const std::string reason = std::strerror(errno);
    if (fd >= 0) {
      ::close(fd);
    }
    ::unlink(path.c_str());  // nothing half-written stays behind
    throw H5Error(std::string(what) + ": " + reason);
  };
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    fail("create", -1);
  }
  if (!WriteWhole(fd, head.data(), head.size()) || !WriteWhole(fd, image.data(), image.size())) {
    fail("write", fd);
  }
  if (durability == Durability::kOnDisk && ::fsync(fd) != 0) {
    fail("fsync", fd);
  }
  if (::close(fd) != 0) {
    fail("close", -1);
  }
}

}  // namespace skewbridge::jobs::h5
