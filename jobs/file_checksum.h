#pragma once
/// @file
/// SHA-256 checksums of input files (OpenSSL's libcrypto), as `sha256sum` prints them: what a
/// cube records of every file it was computed from (docs/hdf5-layout.md, inputs/).

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace skewbridge::jobs {

/// A file's checksum and size.
struct FileChecksum {
  std::string sha256;       ///< 64 lower-case hex digits
  std::uint64_t bytes = 0;  ///< the file's size [bytes]
};

/// Reads `path` once, in 64 KiB blocks, and returns its SHA-256 and size.
/// @throws InputError naming the file when it cannot be read.
FileChecksum ChecksumFile(const std::filesystem::path& path);

/// The SHA-256 of bytes held in memory (64 lower-case hex digits).
std::string Sha256Hex(std::string_view bytes);

}  // namespace skewbridge::jobs
