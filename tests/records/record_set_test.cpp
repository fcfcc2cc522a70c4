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

namespace skewbridge::records::record_set_test {
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

// A pair: two files of one station, H1 and H2, beside single records in one [[record]] array;
// the shorter component is padded with zeros at its end, and the padding is said.
TEST(LoadRecordSet, PairsGiveTwoComponentsOfOneLength) {
  const RecordSet set = LoadRecordSet(kData / "pairs" / "pairs.toml");
  ASSERT_EQ(set.records.size(), 3u);
  EXPECT_TRUE(set.records[0].IsPair());
  EXPECT_FALSE(set.records[1].IsPair());
  EXPECT_EQ(RecordLabel(set.records[0]), "RSN107");
  EXPECT_EQ(RecordLabel(set.records[1]), "NIS090.AT2");
  EXPECT_EQ(RecordLabel(set.records[2]), "RSN430_SMART1.25_25M01");  // the files' common start

  const RecordComponents pair = LoadComponents(set.records[0]);
  ASSERT_TRUE(pair.IsPair());
  const GroundMotion h1 = ReadRecord(kData / "pairs" / "RSN107_OROVILLE_B-OAP180.AT2");
  const GroundMotion h2 = ReadRecord(kData / "pairs" / "RSN107_OROVILLE_B-OAP270.AT2");
  ASSERT_EQ(h1.npts(), 2630u);  // PAIRS.csv
  ASSERT_EQ(h2.npts(), 2405u);
  for (const GroundMotion& m : pair.motions) {
    EXPECT_EQ(m.npts(), 2630u);
    EXPECT_EQ(m.dt_s, 0.005);
    EXPECT_EQ(m.station, "Oroville Airport");
  }
  EXPECT_EQ(pair.motions[0].component, "180");
  EXPECT_EQ(pair.motions[1].component, "270");
  EXPECT_EQ(pair.padded_samples[0], 0u);
  EXPECT_EQ(pair.padded_samples[1], 225u);
  EXPECT_EQ(pair.motions[0].acc_mps2, h1.acc_mps2);
  for (std::size_t i = 0; i < 2630; ++i) {
    ASSERT_EQ(pair.motions[1].acc_mps2[i], i < 2405 ? h2.acc_mps2[i] : 0.0) << i;
  }
  ASSERT_EQ(pair.motions[1].notes.size(), 1u);
  EXPECT_THAT(pair.motions[1].notes[0],
              HasSubstr("RSN107_OROVILLE_B-OAP270.AT2: padded with 225 zero sample(s) at the end "
                        "to the 2630 samples of its pair's H1"));
  EXPECT_TRUE(pair.motions[0].notes.empty());

  const RecordComponents single = LoadComponents(set.records[1]);
  ASSERT_FALSE(single.IsPair());
  EXPECT_EQ(single.motions[0].acc_mps2, LoadRecord(set.records[1]).acc_mps2);
  // A consumer of one component is told it met a pair, never given H1 alone.
  try {
    LoadRecord(set.records[0]);
    ADD_FAILURE() << "a pair read as one record";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("record 'RSN107' is a pair of two horizontal components"));
  }
}

// The readers' strictness holds for both files; a pair of two time steps is refused with one
// line naming both files; scale and the manifest's components apply to both.
TEST(LoadRecordSet, PairsAreReadAsStrictlyAsSingleRecords) {
  const std::string pairs = (kData / "pairs").string();
  const std::string h1 = pairs + "/RSN430_SMART1.25_25M01EW.AT2";
  const RecordSet scaled = LoadRecordSet(WriteManifest(
      "p1.toml", "[[record]]\nh1 = \"" + h1 + "\"\nh2 = \"" + pairs +
                     "/RSN430_SMART1.25_25M01NS.AT2\"\nscale = 3\ncomponent_h1 = \"E\"\n"
                     "component_h2 = \"N\"\n"));
  const RecordComponents three = LoadComponents(scaled.records[0]);
  const GroundMotion ns = ReadRecord(pairs + "/RSN430_SMART1.25_25M01NS.AT2");
  EXPECT_EQ(three.motions[1].acc_mps2[500], 3.0 * ns.acc_mps2[500]);
  EXPECT_EQ(three.motions[0].component, "E");
  EXPECT_EQ(three.motions[1].component, "N");
  EXPECT_EQ(three.padded_samples[0] + three.padded_samples[1], 0u);

  auto error_of_pair = [&](const std::string& name, const std::string& second) {
    try {
      LoadComponents(LoadRecordSet(WriteManifest(name, "[[record]]\nh1 = \"" + h1 + "\"\nh2 = \"" +
                                                           second + "\"\n"))
                         .records[0]);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_THAT(error_of_pair("p2.toml", (kData / "malformed" / "truncated.AT2").string()),
              HasSubstr("truncated.AT2:4: header declares NPTS = 6 but the file holds 4"));
  // The H2 file of RSN430 with its DT changed from .0100 to .0050.
  std::ifstream in(pairs + "/RSN430_SMART1.25_25M01NS.AT2");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("DT=   .0100"), 11, "DT=   .0050");
  const std::filesystem::path other_dt =
      std::filesystem::path(::testing::TempDir()) / "sets" / "NS-dt0.005.AT2";
  std::ofstream(other_dt) << text;
  const std::string dt_error = error_of_pair("p3.toml", other_dt.string());
  EXPECT_THAT(dt_error, HasSubstr(h1 + ", " + other_dt.string() +
                                  ": the two components of a pair have different time steps "
                                  "(0.01 s and 0.005 s)"));
  EXPECT_EQ(dt_error.find('\n'), std::string::npos);
  EXPECT_THAT(error_of_pair("p4.toml", (kData / "NIS090.AT2").string()),
              HasSubstr("the two components of a pair are of different stations"));
}

TEST(LoadRecordSet, PairErrorsNameTheManifestLineAndKey) {
  EXPECT_THAT(ErrorOf(WriteManifest("q1.toml", "[[record]]\nh1 = \"a\"\n")),
              HasSubstr("q1.toml:1: h2: is required for a pair"));
  EXPECT_THAT(
      ErrorOf(WriteManifest("q2.toml", "[[record]]\nh1 = \"a\"\nh2 = \"b\"\nfile = \"c\"\n")),
      HasSubstr("q2.toml:4: file: a pair names its files h1 and h2"));
  EXPECT_THAT(ErrorOf(WriteManifest("q3.toml", "[[record]]\nfile = \"a\"\ncomponent_h2 = \"N\"\n")),
              HasSubstr("q3.toml:3: component_h2: only for a pair"));
  EXPECT_THAT(ErrorOf(WriteManifest("q4.toml", "[[record]]\nh1 = \"a\"\nh2 = \"./a\"\n")),
              HasSubstr("q4.toml:3: h2: is the file of h1"));
  EXPECT_THAT(ErrorOf(WriteManifest("q5.toml",
                                    "[[record]]\nh1 = \"a\"\nh2 = \"b\"\n"
                                    "[[record]]\nfile = \"a\"\n")),
              HasSubstr("duplicate record label 'a'"));
}

// Two file names of one station pair by name when they differ in one run without a separator.
TEST(PairsByName, TheComponentIsOneRunWithoutASeparator) {
  EXPECT_TRUE(PairsByName("RSN107_OROVILLE_B-OAP180.AT2", "RSN107_OROVILLE_B-OAP270.AT2"));
  EXPECT_TRUE(PairsByName("RSN430_SMART1.25_25M01EW.AT2", "RSN430_SMART1.25_25M01NS.AT2"));
  EXPECT_TRUE(PairsByName("RSN1196_CHICHI_CHY027-E.AT2", "RSN1196_CHICHI_CHY027-N.AT2"));
  EXPECT_TRUE(PairsByName("IT.AQK..HNE.D.ASC", "IT.AQK..HNN.D.ASC"));
  EXPECT_FALSE(PairsByName("RSN107_A180.AT2", "RSN149_B090.AT2"));  // two stations
  EXPECT_FALSE(PairsByName("RSN107_A180.AT2", "RSN107_A180.AT2"));  // one file
  EXPECT_FALSE(PairsByName("A.AT2", "A1.AT2"));                     // one side empty
  EXPECT_FALSE(PairsByName("X_E.AT2", "Y-N.AT2"));
}

// A folder set of pairs, by name or through a table, is the set of [[record]] pairs: the same
// files as H1 and H2, the same components read, the table's labels; a pattern that leaves a
// pair out leaves it out of the table's set too.
TEST(LoadRecordSet, FolderPairsAreTheRecordFormsPairs) {
  const std::filesystem::path pairs = kData / "pairs";
  const std::string folder = pairs.string();
  const RecordSet tables = LoadRecordSet(WriteManifest(
      "fp1.toml", "[[record]]\nh1 = \"" + folder + "/RSN107_OROVILLE_B-OAP180.AT2\"\nh2 = \"" +
                      folder + "/RSN107_OROVILLE_B-OAP270.AT2\"\n[[record]]\nh1 = \"" + folder +
                      "/RSN430_SMART1.25_25M01EW.AT2\"\nh2 = \"" + folder +
                      "/RSN430_SMART1.25_25M01NS.AT2\"\n"));
  const RecordSet by_name = LoadRecordSet(WriteManifest(
      "fp2.toml", "folder = \"" + folder + "\"\npattern = \"RSN*.AT2\"\npairs = true\n"));
  const RecordSet by_table = LoadRecordSet(WriteManifest(
      "fp3.toml", "folder = \"" + folder + "\"\npattern = \"*.AT2\"\npairs = \"PAIRS.csv\"\n"));
  EXPECT_TRUE(by_name.pairs_table.empty());
  EXPECT_EQ(by_table.pairs_table, pairs / "PAIRS.csv");
  for (const RecordSet* set : {&by_name, &by_table}) {
    ASSERT_EQ(set->records.size(), 2u);
    for (std::size_t r = 0; r < 2; ++r) {
      const RecordEntry& want = tables.records[r];
      const RecordEntry& got = set->records[r];
      EXPECT_TRUE(std::filesystem::equivalent(got.file, want.file)) << got.file;
      EXPECT_TRUE(std::filesystem::equivalent(got.file_h2, want.file_h2)) << got.file_h2;
      const RecordComponents a = LoadComponents(want);
      const RecordComponents b = LoadComponents(got);
      ASSERT_TRUE(b.IsPair());
      EXPECT_EQ(b.motions[0].acc_mps2, a.motions[0].acc_mps2);
      EXPECT_EQ(b.motions[1].acc_mps2, a.motions[1].acc_mps2);
      EXPECT_EQ(b.padded_samples, a.padded_samples);
    }
  }
  EXPECT_EQ(RecordLabel(by_name.records[0]), RecordLabel(tables.records[0]));
  EXPECT_EQ(RecordLabel(by_name.records[1]), "RSN430_SMART1.25_25M01");
  EXPECT_EQ(RecordLabel(by_table.records[0]), "RSN107");  // the table's pair column
  EXPECT_EQ(RecordLabel(by_table.records[1]), "RSN430");
  const RecordSet one = LoadRecordSet(WriteManifest(
      "fp4.toml", "folder = \"" + folder + "\"\npattern = \"RSN4*\"\npairs = \"PAIRS.csv\"\n"));
  ASSERT_EQ(one.records.size(), 1u);
  EXPECT_EQ(RecordLabel(one.records[0]), "RSN430");
}

// Each way a folder's files fail to make pairs is refused with one line naming the file, the
// table's line or the key.
TEST(LoadRecordSet, FolderPairErrorsNameTheFileAndTheLine) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "folder-pairs";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "f");
  const std::filesystem::path pairs = kData / "pairs";
  for (const char* name : {"RSN107_OROVILLE_B-OAP180.AT2", "RSN107_OROVILLE_B-OAP270.AT2",
                           "RSN430_SMART1.25_25M01EW.AT2"}) {
    std::filesystem::copy_file(pairs / name, dir / "f" / name);
  }
  auto error_of = [&dir](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    try {
      for (const RecordEntry& e : LoadRecordSet(dir / name).records) LoadComponents(e);
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string by_name = "folder = \"f\"\npattern = \"*.AT2\"\npairs = true\n";
  EXPECT_THAT(error_of("n1.toml", by_name),
              HasSubstr("n1.toml:3: pairs: unpaired file RSN430_SMART1.25_25M01EW.AT2 of "));
  // A third component of RSN107: ambiguous by name.
  std::filesystem::copy_file(pairs / "RSN107_OROVILLE_B-OAP180.AT2",
                             dir / "f" / "RSN107_OROVILLE_B-OAPUP.AT2");
  EXPECT_THAT(error_of("n2.toml", by_name),
              HasSubstr("n2.toml:3: pairs: file RSN107_OROVILLE_B-OAP180.AT2 pairs by name with "
                        "both RSN107_OROVILLE_B-OAP270.AT2 and RSN107_OROVILLE_B-OAPUP.AT2"));
  std::filesystem::remove(dir / "f" / "RSN107_OROVILLE_B-OAPUP.AT2");
  // RSN430's H2 with another time step: refused when the pair is read, both files named.
  std::ifstream in(pairs / "RSN430_SMART1.25_25M01NS.AT2");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("DT=   .0100"), 11, "DT=   .0050");
  std::ofstream(dir / "f" / "RSN430_SMART1.25_25M01NS.AT2") << text;
  EXPECT_THAT(error_of("n3.toml", by_name),
              HasSubstr("RSN430_SMART1.25_25M01NS.AT2: the two components of a pair have "
                        "different time steps (0.01 s and 0.005 s)"));
  std::filesystem::remove(dir / "f" / "RSN430_SMART1.25_25M01NS.AT2");

  const std::string header = "pair,station,h1_file,h2_file\n";
  const std::string rsn107 =
      "RSN107,Oroville,RSN107_OROVILLE_B-OAP180.AT2,"
      "RSN107_OROVILLE_B-OAP270.AT2\n";
  auto with_table = [&](const std::string& name, const std::string& table) {
    std::ofstream(dir / "f" / "P.csv") << table;
    return error_of(name, "folder = \"f\"\npattern = \"*\"\npairs = \"P.csv\"\n");
  };
  EXPECT_THAT(with_table("t1.toml", header + rsn107),
              HasSubstr("t1.toml:3: pairs: unpaired file RSN430_SMART1.25_25M01EW.AT2 of "));
  EXPECT_THAT(with_table("t2.toml", header + rsn107 +
                                        "RSN430,\"SMART1, M01\",RSN430_SMART1.25_"
                                        "25M01EW.AT2,RSN430_SMART1.25_25M01NS.AT2\n"),
              HasSubstr("P.csv:3: no file RSN430_SMART1.25_25M01NS.AT2 in "));
  EXPECT_THAT(with_table("t3.toml", "pair,h1_file\n"),
              HasSubstr("P.csv:1: no column h2_file in the header"));
  EXPECT_THAT(with_table("t4.toml", header + rsn107 +
                                        "X,x,RSN107_OROVILLE_B-OAP270.AT2,"
                                        "RSN430_SMART1.25_25M01EW.AT2\n"),
              HasSubstr("P.csv:3: RSN107_OROVILLE_B-OAP270.AT2 is also a component of the pair "
                        "of line 2"));
  EXPECT_THAT(with_table("t5.toml", header + "A,a,b\n"),
              HasSubstr("P.csv:2: 3 fields, the header has 4"));
  std::ofstream(dir / "f" / "P.csv") << header + rsn107;
  EXPECT_THAT(error_of("t6.toml", "folder = \"f\"\npattern = \"*180.AT2\"\npairs = \"P.csv\"\n"),
              HasSubstr("P.csv:2: h1_file 'RSN107_OROVILLE_B-OAP180.AT2' matches pattern "
                        "'*180.AT2' and h2_file 'RSN107_OROVILLE_B-OAP270.AT2' does not"));
  EXPECT_THAT(error_of("t7.toml", "folder = \"f\"\npattern = \"*\"\npairs = \"Q.csv\"\n"),
              HasSubstr("t7.toml:3: pairs: not a file: "));
  EXPECT_THAT(error_of("t8.toml", "folder = \"f\"\npattern = \"*\"\npairs = 2\n"),
              HasSubstr("t8.toml:3: pairs: must be true (pairs by file name) or the name of a "
                        "CSV table"));
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
}  // namespace skewbridge::records::record_set_test
