#include "solver/common/file_kind.h"

#include <system_error>

namespace skewbridge {

bool HasHdf5Signature(std::string_view bytes) {
  // HDF5 File Format Specification, "Format Signature": \211 H D F \r \n \032 \n.
  constexpr std::string_view kSignature("\x89HDF\r\n\x1a\n", 8);
  for (std::size_t offset = 0; offset + kSignature.size() <= bytes.size();
       offset = offset == 0 ? 512 : 2 * offset) {
    if (bytes.substr(offset, kSignature.size()) == kSignature) {
      return true;
    }
  }
  return false;
}

std::string WhyUnreadable(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found) return "no such file";
  if (status.type() == std::filesystem::file_type::directory) return "a folder, not a file";
  return "cannot be opened for reading (no permission, or not a regular file)";
}

}  // namespace skewbridge
