// Recognising an HDF5 file by its signature, at the offsets the HDF5 specification allows.
#include "solver/common/file_kind.h"

#include <gtest/gtest.h>

#include <string>

namespace skewbridge {
namespace {

const std::string kSignature("\x89HDF\r\n\x1a\n", 8);

TEST(HasHdf5Signature, AtTheSuperblockOffsets) {
  EXPECT_TRUE(HasHdf5Signature(kSignature + "rest of the superblock"));
  EXPECT_TRUE(HasHdf5Signature(std::string(512, ' ') + kSignature));   // after a user block
  EXPECT_TRUE(HasHdf5Signature(std::string(2048, ' ') + kSignature));  // 512 * 2^2
  EXPECT_FALSE(HasHdf5Signature(std::string(100, ' ') + kSignature));  // not a valid offset
}

TEST(HasHdf5Signature, TextIsNotHdf5) {
  EXPECT_FALSE(HasHdf5Signature(""));
  EXPECT_FALSE(HasHdf5Signature("[deck]\nm = 1.0\n"));
  EXPECT_FALSE(HasHdf5Signature(kSignature.substr(0, 7)));                // cut short
  EXPECT_FALSE(HasHdf5Signature("HDF\r\n\x1a\n" + std::string(8, ' ')));  // without \211
}

}  // namespace
}  // namespace skewbridge
