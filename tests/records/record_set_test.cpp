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

// The folder form: every file whose name matches the glob, in byte order of the names, each
// labelled by its file name and read exactly as a [[record]] entry of the same file.
TEST(LoadRecordSet, FolderSetTakesTheMatchingFilesInNameOrder) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "folder-set";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "greek");
  for (const char* name : {"b.AT2", "a.AT2", "c.at2"}) {
    std::filesystem::copy_file(kData / "NIS090.AT2", dir / "greek" / name);
  }
  std::ofstream(dir / "greek" / "notes.txt") << "not a record\n";
  std::filesystem::create_directories(dir / "greek" / "d.AT2");  // a folder is not a record
  std::ofstream(dir / "set.toml") << "name = \"g\"\nfolder = \"greek/\"\npattern = \"*.AT2\"\n"
                                     "scale = 2.0\n";
  const RecordSet set = LoadRecordSet(dir / "set.toml");
  EXPECT_EQ(set.name, "g");
  ASSERT_EQ(set.records.size(), 2u);
  EXPECT_EQ(RecordLabel(set.records[0]), "a.AT2");
  EXPECT_EQ(RecordLabel(set.records[1]), "b.AT2");
  const GroundMotion scaled = LoadRecord(set.records[1]);
  const GroundMotion plain = ReadRecord(kData / "NIS090.AT2");
  ASSERT_EQ(scaled.npts(), plain.npts());
  EXPECT_EQ(scaled.dt_s, plain.dt_s);  // from the AT2 header
  EXPECT_EQ(scaled.acc_mps2[100], 2.0 * plain.acc_mps2[100]);
}

TEST(LoadRecordSet, FolderSetErrorsNameTheManifestLineAndKey) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "sets";
  std::filesystem::create_directories(dir / "empty-folder");
  EXPECT_THAT(ErrorOf(WriteManifest("g1.toml", "folder = \"empty-folder\"\npattern = \"*.AT2\"\n")),
              HasSubstr("g1.toml:2: pattern: no file of"));
  EXPECT_THAT(ErrorOf(WriteManifest("g2.toml", "folder = \"no-such\"\npattern = \"*.AT2\"\n")),
              HasSubstr("g2.toml:1: folder: not a folder"));
  EXPECT_THAT(ErrorOf(WriteManifest("g3.toml", "folder = \"empty-folder\"\npattern = \"[a-\"\n")),
              HasSubstr("g3.toml:2: pattern: '[a-' has an unclosed '['"));
  EXPECT_THAT(ErrorOf(WriteManifest("g4.toml", "folder = \".\"\npattern = \"x/*.AT2\"\n")),
              HasSubstr("g4.toml:2: pattern: 'x/*.AT2' names a folder"));
  EXPECT_THAT(ErrorOf(WriteManifest("g5.toml", "folder = \".\"\npattern = \"\"\n")),
              HasSubstr("g5.toml:2: pattern: empty pattern"));
  EXPECT_THAT(ErrorOf(WriteManifest("g6.toml", "folder = \".\"\n")),
              HasSubstr("g6.toml:1: pattern: is required with folder"));
  EXPECT_THAT(ErrorOf(WriteManifest("g7.toml", "pattern = \"*\"\n")),
              HasSubstr("folder: is required"));
  EXPECT_THAT(ErrorOf(WriteManifest("g8.toml",
                                    "folder = \".\"\npattern = \"*\"\n"
                                    "[[record]]\nfile = \"x\"\n")),
              HasSubstr("g8.toml:3: record: unknown key of a folder set"));
  EXPECT_THAT(ErrorOf(WriteManifest("g9.toml",
                                    "folder = \".\"\npattern = \"*.toml\"\n"
                                    "units = \"ft\"\n")),
              HasSubstr("g9.toml:3: units: unknown units 'ft'"));
}

TEST(GlobMatch, StarQuestionMarkAndClasses) {
  EXPECT_TRUE(GlobMatch("*.AT2", "RSN6_IMPVALL.AT2"));
  EXPECT_FALSE(GlobMatch("*.AT2", "RSN6_IMPVALL.at2"));
  EXPECT_FALSE(GlobMatch("*.AT2", "x.AT2.bak"));
  EXPECT_TRUE(GlobMatch("*", ""));
  EXPECT_TRUE(GlobMatch("A?99_*", "A299_T"));
  EXPECT_FALSE(GlobMatch("A?99_*", "A99_T"));
  EXPECT_TRUE(GlobMatch("*_[LT]", "A299_T"));
  EXPECT_FALSE(GlobMatch("*_[LT]", "A299_V"));
  EXPECT_TRUE(GlobMatch("*_[!LT]", "A299_V"));
  EXPECT_TRUE(GlobMatch("[a-c]*", "b1"));
  EXPECT_FALSE(GlobMatch("[a-c]*", "d1"));
  EXPECT_TRUE(GlobMatch("*a*b*c", "xaybzc"));
  EXPECT_FALSE(GlobMatch("*a*b*c", "xaybzcd"));
  EXPECT_TRUE(GlobMatch("[]]x", "]x"));
  EXPECT_EQ(GlobProblem("*.AT2"), "");
  EXPECT_NE(GlobProblem("[abc"), "");
}

}  // namespace
}  // namespace skewbridge::records
