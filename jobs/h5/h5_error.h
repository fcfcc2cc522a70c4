#pragma once
/// @file
/// The error type of the HDF5 layer, usable without <hdf5.h>.

#include <stdexcept>
#include <string>

namespace skewbridge::jobs::h5 {

/// An HDF5 call failed (I/O error, corrupt or foreign file); the message names the call and
/// the object. Callers that got the path from the user convert it to InputError.
class H5Error : public std::runtime_error {
 public:
  /// @param message "what was attempted on which object".
  explicit H5Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace skewbridge::jobs::h5
