// Recognising an HDF5 file by its signature, at the offsets the HDF5 specification allows.
#include "solver/common/file_kind.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace skewbridge::file_kind_test {
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

TEST(WhyUnreadable, NamesAMissingFileAndAFolder) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("sb_why_unreadable_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  EXPECT_EQ(WhyUnreadable(dir / "absent.AT2"), "no such file");
  EXPECT_EQ(WhyUnreadable(dir / "no-folder" / "absent.AT2"), "no such file");
  EXPECT_EQ(WhyUnreadable(dir), "a folder, not a file");
  std::filesystem::create_symlink(dir / "absent.AT2", dir / "dangling");
  EXPECT_EQ(WhyUnreadable(dir / "dangling"), "no such file");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace skewbridge::file_kind_test
