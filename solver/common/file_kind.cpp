#include "solver/common/file_kind.h"

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

}  // namespace skewbridge
