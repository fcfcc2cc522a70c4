// Record-set manifests: paths relative to the manifest, per-record options and scale, and
// errors that name the manifest line and the key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "records/ground_motion.h"
#include "records/record_set.h"
#include "solver/common/error.h"

namespace skewbridge::records {
namespace {

using ::testing::HasSubstr;

const std::filesystem::path kData = std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) / "records";

std::filesystem::path WriteManifest(const std::string& name, const std::string& text) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "sets";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

std::string ErrorOf(const std::filesystem::path& manifest) {
  try {
    LoadRecordSet(manifest);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(LoadRecordSet, ResolvesPathsAndAppliesScaleAndOptions) {
  const std::string data = kData.string();
  const std::filesystem::path manifest = WriteManifest(
      "two.toml", "name = \"two\"\n[[record]]\nfile = \"" + data +
                      "/NIS090.AT2\"\nscale = 2.0\nlabel = \"Kobe\"\ncomponent = \"EW\"\n"
                      "[[record]]\nfile = \"" +
                      data + "/malformed/valid.AT2\"\nunits = \"g\"\ndt = 0.01\n");
  const RecordSet set = LoadRecordSet(manifest);
  EXPECT_EQ(set.name, "two");
  ASSERT_EQ(set.records.size(), 2u);
  EXPECT_EQ(RecordLabel(set.records[0]), "Kobe");
  EXPECT_EQ(RecordLabel(set.records[1]), "valid.AT2");
  const GroundMotion scaled = LoadRecord(set.records[0]);
  const GroundMotion plain = ReadRecord(kData / "NIS090.AT2");
  ASSERT_EQ(scaled.npts(), plain.npts());
  EXPECT_EQ(scaled.acc_mps2[100], 2.0 * plain.acc_mps2[100]);
  EXPECT_EQ(scaled.component, "EW");
  EXPECT_EQ(set.records[1].options.units, Units::kG);
  EXPECT_EQ(LoadRecord(set.records[1]).npts(), 6u);
}

TEST(LoadRecordSet, RelativePathsAreRelativeToTheManifest) {
  const std::filesystem::path manifest =
      WriteManifest("rel.toml", "[[record]]\nfile = \"x.AT2\"\n");
  const RecordSet set = LoadRecordSet(manifest);
  EXPECT_EQ(set.name, "rel");
  EXPECT_EQ(set.records[0].file, manifest.parent_path() / "x.AT2");
}

TEST(LoadRecordSet, ErrorsNameTheManifestLineAndKey) {
  EXPECT_THAT(ErrorOf(WriteManifest("a.toml", "[[record]]\nfile = \"x\"\nscael = 2.0\n")),
              HasSubstr("a.toml:3: scael: unknown key"));
  EXPECT_THAT(ErrorOf(WriteManifest("b.toml", "[[record]]\nfile = \"x\"\nscale = -1\n")),
              HasSubstr("b.toml:3: scale: must be a number > 0"));
  EXPECT_THAT(ErrorOf(WriteManifest("c.toml", "[[record]]\nlabel = \"x\"\n")),
              HasSubstr("file: is required"));
  EXPECT_THAT(ErrorOf(WriteManifest("d.toml", "[[record]]\nfile = \"x\"\nunits = \"ft/s2\"\n")),
              HasSubstr("d.toml:3: units: unknown units 'ft/s2'"));
  EXPECT_THAT(ErrorOf(WriteManifest("e.toml", "name = \"empty\"\n")),
              HasSubstr("no [[record]] entries"));
  EXPECT_THAT(ErrorOf(WriteManifest("f.toml", "[[record]\nfile = \"x\"\n")), HasSubstr("f.toml:1"));
}

}  // namespace
}  // namespace skewbridge::records
