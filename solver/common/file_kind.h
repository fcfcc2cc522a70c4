#pragma once
/// @file
/// Recognising a file of another kind by its first bytes, and why a file cannot be read, to
/// name either in an error message.

#include <filesystem>
#include <string>
#include <string_view>

namespace skewbridge {

/// Whether `bytes` hold the HDF5 format signature at an offset where the HDF5 superblock may
/// stand (0, 512, 1024, 2048, ...): a sweep cube or a run file, not a text input.
bool HasHdf5Signature(std::string_view bytes);

/// Why `path` cannot be opened for reading, in the words of a message: "no such file" (nothing
/// there, or a dangling link), "a folder, not a file", or "cannot be opened for reading (no
/// permission, or not a regular file)" for anything else that exists.
std::string WhyUnreadable(const std::filesystem::path& path);

}  // namespace skewbridge
