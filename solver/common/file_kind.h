#pragma once
/// @file
/// Recognising a file of another kind by its first bytes, to name it in an error message.

#include <string_view>

namespace skewbridge {

/// Whether `bytes` hold the HDF5 format signature at an offset where the HDF5 superblock may
/// stand (0, 512, 1024, 2048, ...): a sweep cube or a run file, not a text input.
bool HasHdf5Signature(std::string_view bytes);

}  // namespace skewbridge
