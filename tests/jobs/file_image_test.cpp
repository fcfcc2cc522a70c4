// A file built in memory and written from the core driver's own memory (jobs/h5/h5.h,
// SaveFileImage) against the bytes HDF5 copies out of it (H5Fget_file_image, CopyFileImage): the
// same bytes for a file of a few kilobytes and for one of tens of megabytes whose memory grew
// several times, and a file that HDF5 opens and reads back value for value.

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "jobs/h5/h5.h"

namespace skewbridge::jobs::h5::file_image_test {
namespace {

std::vector<char> ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A memory file as a checkpoint is made: attributes, a group, chunked datasets with Fletcher-32
// allocated at creation and filled (NaN), one of them then written with `cells` values.
struct Built {
  MemoryFile image;
  std::vector<double> values;
};

Built Build(const std::string& label, hsize_t rows, int datasets, std::size_t expected = 0) {
  Built b{CreateMemoryFile(label, expected), {}};
  const hid_t file = b.image.file.get();
  SetAttr(file, "format", std::string("file-image-test"));
  Id group = CreateGroup(file, "sweeps/one");
  SetAttr(group.get(), "cells", static_cast<std::int64_t>(rows * 300));
  const std::vector<hsize_t> shape{rows, 20, 15};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < datasets; ++k) {
    Id ds = CreateDataset(group.get(), "r" + std::to_string(k), H5T_IEEE_F64LE, shape, {}, 0, &nan);
    SetAttr(ds.get(), "units", std::string("m"));
    if (k == 1) {
      b.values.resize(rows * 300);
      for (std::size_t i = 0; i < b.values.size(); ++i) {
        b.values[i] = std::sin(0.001 * static_cast<double>(i)) * 1e-3;
      }
      WriteAll(ds.get(), H5T_NATIVE_DOUBLE, b.values.data());
    }
  }
  return b;
}

constexpr std::size_t kHugePage = std::size_t{1} << 21;

// Builds and saves the file; returns the length of its memory's mapping at the end [byte].
std::size_t ExpectSavedIsHdf5sImage(hsize_t rows, int datasets, const std::string& name,
                                    std::size_t expected = 0) {
  const std::string path = ::testing::TempDir() + name;
  Built b = Build(path, rows, datasets, expected);
  // The mapping starts on a 2 MiB boundary and is whole 2 MiB pages, however it grew.
  const auto base = reinterpret_cast<std::uintptr_t>(b.image.memory->base);
  EXPECT_EQ(base % kHugePage, 0u);
  const std::size_t capacity = b.image.memory->capacity;
  EXPECT_EQ(capacity % kHugePage, 0u);
  SaveFileImage(b.image.file.get(), *b.image.memory, path);
  const std::vector<char> reference = CopyFileImage(b.image.file.get());
  const std::vector<char> saved = ReadBytes(path);
  EXPECT_EQ(saved.size(), reference.size());
  EXPECT_TRUE(saved == reference) << "the saved file differs from H5Fget_file_image's bytes";
  b = Built{};  // the file closed, its memory unmapped

  Id file = OpenFile(path, false);
  EXPECT_EQ(GetStringAttr(file.get(), "format"), "file-image-test");
  Id ds = OpenDataset(file.get(), "sweeps/one/r1");
  std::vector<double> back(rows * 300);
  ReadAll(ds.get(), H5T_NATIVE_DOUBLE, back.data());  // through every chunk's checksum
  std::vector<double> expected(rows * 300);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    expected[i] = std::sin(0.001 * static_cast<double>(i)) * 1e-3;
  }
  EXPECT_EQ(back, expected);
  Id other = OpenDataset(file.get(), "sweeps/one/r0");
  ReadAll(other.get(), H5T_NATIVE_DOUBLE, back.data());
  EXPECT_TRUE(std::isnan(back.front()) && std::isnan(back.back()));
  std::filesystem::remove(path);
  return capacity;
}

TEST(SaveFileImage, ASmallFileIsTheBytesOfH5FgetFileImage) {
  ExpectSavedIsHdf5sImage(2, 3, "file_image_small.h5");
}

TEST(SaveFileImage, AFileOfTensOfMegabytesIsTheBytesOfH5FgetFileImage) {
  // 100 datasets of 100 x 300 doubles: 24 MB, the memory grown from nothing several times
  // (1 MiB increments doubled: 32 MiB or more at the end).
  EXPECT_GE(ExpectSavedIsHdf5sImage(100, 100, "file_image_large.h5"), 16 * kHugePage);
}

TEST(SaveFileImage, AFileWithinItsEstimateIsMappedOnceAtTheEstimate) {
  // The same 24 MB file with an estimate of 26 MiB: mapped at 26 MiB from the first write and
  // never grown (a growth would at least double it), the same bytes as HDF5's image.
  EXPECT_EQ(ExpectSavedIsHdf5sImage(100, 100, "file_image_estimated.h5", 26u << 20),
            13 * kHugePage);
}

TEST(SaveFileImage, AnEstimateTooLargeToMapFallsBackToGrowing) {
  // An estimate no machine maps (2^62 bytes): the driver's own sizes, grown as it needs.
  EXPECT_LT(ExpectSavedIsHdf5sImage(2, 3, "file_image_refused.h5", std::size_t{1} << 62),
            std::size_t{1} << 30);
}

}  // namespace
}  // namespace skewbridge::jobs::h5::file_image_test
