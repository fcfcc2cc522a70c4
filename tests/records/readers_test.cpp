// The record readers against the text of the files they read: the copies in tests/data (values
// from the shared MANIFEST.csv and the files' own first and last numbers), small snippets of
// every format, and one malformed file per rule of the strict parser.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "records/ground_motion.h"
#include "solver/common/error.h"

namespace skewbridge::records::readers_test {
namespace {

using ::testing::HasSubstr;

const std::filesystem::path kData = std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) / "records";

// The message of the InputError thrown by `fn`, or "" when nothing is thrown.
template <typename Fn>
std::string ErrorOf(Fn&& fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

struct CopiedRecord {
  const char* file;
  const char* format;
  std::size_t npts;   // MANIFEST.csv
  double dt_s;        // MANIFEST.csv
  double pga_g;       // MANIFEST.csv (4 decimals)
  const char* first;  // first number of the file's text
  const char* last;   // last number of the file's text
  double to_mps2;     // the file's units
};

class CopiedRecords : public ::testing::TestWithParam<CopiedRecord> {};

TEST_P(CopiedRecords, MatchManifestAndFileText) {
  const CopiedRecord& c = GetParam();
  const GroundMotion m = ReadRecord(kData / c.file);
  EXPECT_EQ(m.format, c.format);
  EXPECT_EQ(m.npts(), c.npts);
  EXPECT_NEAR(m.dt_s, c.dt_s, 1e-12);
  double pga = 0.0;
  for (double a : m.acc_mps2) pga = std::max(pga, std::abs(a));
  EXPECT_NEAR(pga / kStandardGravity_mps2, c.pga_g, 0.5e-4 + 1e-9);
  EXPECT_EQ(m.acc_mps2.front(), std::stod(c.first) * c.to_mps2);
  EXPECT_EQ(m.acc_mps2.back(), std::stod(c.last) * c.to_mps2);
}

INSTANTIATE_TEST_SUITE_P(
    TestData, CopiedRecords,
    ::testing::Values(CopiedRecord{"NIS090.AT2", "at2", 4096, 0.01, 0.5027, "0.233833E-06",
                                   "0.496963E-04", kStandardGravity_mps2},
                      CopiedRecord{"RSN763_LOMAP_GIL067.AT2", "at2", 7999, 0.005, 0.3585,
                                   "-.8075668E-03", ".3362115E-03", kStandardGravity_mps2},
                      CopiedRecord{"0111a.smc", "smc", 6001, 0.005, 0.1065, "1.5057E+0",
                                   "-2.8745E-1", 0.01},
                      CopiedRecord{"HI.ARS1..HNE.D.20190728.160908.C.ACC.ASC", "esm", 19128, 0.005,
                                   0.0003, "0.000000", "0.000007", 0.01}));

TEST(ReadRecord, At2MetadataComesFromTheHeader) {
  const GroundMotion m = ReadRecord(kData / "RSN763_LOMAP_GIL067.AT2");
  EXPECT_EQ(m.event, "Loma Prieta");
  EXPECT_EQ(m.station, "Gilroy - Gavilan Coll.");
  EXPECT_EQ(m.component, "67");
  EXPECT_EQ(m.original_units, "g");
}

TEST(ParseRecord, At2WithCrCrLfEndingsAndNoFinalNewline) {
  const std::string text =
      "PACIFIC ENGINEERING AND ANALYSIS STRONG-MOTION DATA\r\r\n"
      "NORTHRIDGE 01/17/94 1231, ARLETA, 360\r\r\n"
      "ACCELERATION TIME HISTORY IN UNITS OF G\r\r\n"
      "NPTS=  3, DT= .02000 SEC\r\r\n"
      "   .1297983E-02   .1742817E-02  -.3793137E-02";
  const GroundMotion m = ParseRecord(text, "arl.at2");
  ASSERT_EQ(m.npts(), 3u);
  EXPECT_EQ(m.dt_s, 0.02);
  EXPECT_EQ(m.acc_mps2[2], -.3793137E-02 * kStandardGravity_mps2);
  EXPECT_EQ(m.station, "ARLETA");
}

TEST(ParseRecord, At2OldHeaderSpellingPutsValuesBeforeKeywords) {
  const std::string text =
      "PEER NGA STRONG MOTION DATABASE RECORD\nKOBE 01/16/95 2046, NISHI-AKASHI, 090 (CUE)\n"
      "ACCELERATION TIME HISTORY IN UNITS OF G\n2    0.0100    NPTS, DT\n 0.1E-01 -0.2E-01\n";
  const GroundMotion m = ParseRecord(text, "nis.at2");
  EXPECT_EQ(m.npts(), 2u);
  EXPECT_EQ(m.dt_s, 0.01);
}

TEST(ParseRecord, SplitsNumbersPackedWithoutBlanks) {
  const std::string text =
      "Event Date & Time             : 2009-04-06 01:32:39\n"
      "Station Code / Name           : 2987 / Test\n"
      "Orientation                   : NS\n"
      "Time Increment (s)            : 0.005\n"
      "Number of Data                : 4\n"
      "Accelaration time series in m/s/s\n"
      "-1.3724600E-07-2.6835700E-07 3.9924800E-07\n"
      "-5.2976600E+00\n";
  const GroundMotion m = ParseRecord(text, "x.cor.acc");
  EXPECT_EQ(m.format, "smtk");
  ASSERT_EQ(m.npts(), 4u);
  EXPECT_EQ(m.acc_mps2[0], -1.37246E-07);
  EXPECT_EQ(m.acc_mps2[1], -2.68357E-07);
  EXPECT_EQ(m.acc_mps2[3], -5.29766);
  EXPECT_EQ(m.component, "NS");
}

TEST(ParseRecord, EsmContentIsDetectedWhateverTheExtension) {
  const std::string text =
      "EVENT_NAME: Test\nEVENT_ID: X\nNETWORK: HL\nSTATION_CODE: ABC\nSAMPLING_INTERVAL_S: 0.01\n"
      "NDATA: 3\nSTREAM: HNE\nUNITS: cm/s^2\nUSER5: \n1.5\n-2.5\n100\n";
  const GroundMotion m = ParseRecord(text, "KM.AT2");
  EXPECT_EQ(m.format, "esm");
  EXPECT_EQ(m.acc_mps2, (std::vector<double>{0.015, -0.025, 1.0}));
  EXPECT_EQ(m.component, "HNE");
}

TEST(ParseRecord, ItsakDropsExactZeroPaddingBeyondTheDeclaredCount) {
  const std::string text =
      "A299_T  ITSAK TEST STATION         5 Values\n(8F15.0)             0.005 \n"
      "        .000032        .000534        .000803        .001041        .001243        "
      ".000000        .000000        .000000\n";
  ReadOptions options;
  options.units = Units::kG;
  const GroundMotion m = ParseRecord(text, "A299_T", options);
  EXPECT_EQ(m.format, "itsak");
  ASSERT_EQ(m.npts(), 5u);
  EXPECT_EQ(m.acc_mps2.back(), .001243 * kStandardGravity_mps2);
  EXPECT_EQ(m.dt_s, 0.005);
}

TEST(ParseRecord, ItsakRejectsNonZeroValuesBeyondTheDeclaredCountWithoutPadding) {
  const std::string text =
      "A299_T  ITSAK TEST STATION         5 Values\n(8F15.0)             0.005 \n"
      "        .000032        .000534        .000803        .001041\n"
      "        .001243        .000000        .000001\n";
  ReadOptions options;
  options.units = Units::kG;
  EXPECT_THAT(ErrorOf([&] { ParseRecord(text, "A299_T", options); }),
              HasSubstr("A299_T:4: value 6 lies beyond the declared 5 values"));
}

TEST(ParseRecord, ItsakNotesAFewSamplesBeforeThePaddingAndDropsThem) {
  const std::string text =
      "A299_T  ITSAK TEST STATION         3 Values\n(8F15.0)             0.005 \n"
      "        .000032        .000534        .000803        .001041        .000000\n";
  ReadOptions options;
  options.units = Units::kG;
  const GroundMotion m = ParseRecord(text, "A299_T", options);
  EXPECT_EQ(m.npts(), 3u);
  ASSERT_EQ(m.notes.size(), 1u);
  EXPECT_THAT(m.notes[0], HasSubstr("A299_T:3: dropped 1 non-zero value(s) beyond the declared 3"));
}

TEST(ParseRecord, ItsakNeedsUnitsFromTheUser) {
  const std::string text = "A299_T  STATION  1 Values\n(8F15.0)  0.005\n  .1\n";
  EXPECT_THAT(ErrorOf([&] { ParseRecord(text, "A299_T"); }), HasSubstr("does not state its units"));
}

TEST(ParseRecord, CosmosTakesDtFromRealHeaderValue62InMilliseconds) {
  std::string text = "Corrected acceleration    (Format v01.20 with 13 text lines)\n";
  text += "Record of Test Earthquake\n";
  for (int i = 3; i <= 13; ++i) text += "text line\n";
  text += "  10 Integer-header values follow on   1 lines, Format= (10I8)\n";
  text += "       2       1       4     120       1    -999    -999      11    -999    -999\n";
  text += " 100 Real-header values follow on  20 lines, Format= (5F15.6)\n";
  for (int row = 0; row < 20; ++row) {
    for (int col = 0; col < 5; ++col) {
      text += (row * 5 + col == 61) ? "      10.000000" : "    -999.000000";
    }
    text += "\n";
  }
  text += "   1 Comment line(s) follow, each starting with a \"|\":\n| comment\n";
  text += "       3 acceleration pts, approx  0 secs, units=cm/sec2(04),Format=(1E15.6)\n";
  text += "   3.437285e-04\n  -1.0e+02\n   2.0e+00\nEnd-of-data for ChanHNE acceleration\n";
  const GroundMotion m = ParseRecord(text, "x.V2c");
  EXPECT_EQ(m.format, "cosmos");
  EXPECT_EQ(m.dt_s, 0.01);
  EXPECT_EQ(m.acc_mps2, (std::vector<double>{3.437285e-04 * 0.01, -1.0, 0.02}));
  EXPECT_EQ(m.component, "HNE");
}

std::string CsmipChannel(int channel, const std::string& values) {
  std::string text = "CORRECTED ACCELEROGRAM   36456-S4384-83123.01       CHAN  " +
                     std::to_string(channel) + ":  90 DEG\n";
  text +=
      "UNCORRECTED\nCOALINGA EARTHQUAKE\nMAY 2\nid\nSTATION NO. 36456\nPARKFIELD FAULT ZONE 14\n";
  text += "CHAN  " + std::to_string(channel) + ":  90 DEG\n";
  text += "  3 POINTS OF ACCEL DATA EQUALLY SPACED AT  .020 SEC.  (UNITS: CM/SEC/SEC)\n";
  text += values;
  text += "  3 POINTS OF VELOC DATA EQUALLY SPACED AT  .020 SEC.  (UNITS: CM/SEC)\n";
  text += "     1.000     2.000     3.000\n";
  text += "/&  ----------  END OF DATA FOR CHANNEL  " + std::to_string(channel) + "  ----------\n";
  return text;
}

TEST(ParseRecord, CsmipReadsTheRequestedChannelOfPackedFields) {
  const std::string text = CsmipChannel(1, "    -3.038 -1234.567     2.288\n") +
                           CsmipChannel(2, "   -1.000-1234.567     9.000\n");
  ReadOptions options;
  options.channel = 2;
  const GroundMotion m = ParseRecord(text, "x.V2", options);
  EXPECT_EQ(m.format, "csmip");
  EXPECT_EQ(m.acc_mps2, (std::vector<double>{-0.01, -12.34567, 0.09}));
  EXPECT_EQ(m.station, "PARKFIELD FAULT ZONE 14");
  options.channel = 3;
  EXPECT_THAT(ErrorOf([&] { ParseRecord(text, "x.V2", options); }),
              HasSubstr("channel 3 not found"));
}

TEST(ParseRecord, HeaderlessValuesNeedDtAndUnitsFromTheUser) {
  const std::string text = "0.1 0.2 0.3\r\n-0.4";
  EXPECT_THAT(ErrorOf([&] { ParseRecord(text, "v.txt"); }), HasSubstr("does not state its units"));
  ReadOptions options;
  options.units = Units::kMetresPerSecond2;
  EXPECT_THAT(ErrorOf([&] { ParseRecord(text, "v.txt", options); }), HasSubstr("give dt"));
  options.dt_s = 0.02;
  const GroundMotion m = ParseRecord(text, "v.txt", options);
  EXPECT_EQ(m.format, "plain");
  EXPECT_EQ(m.acc_mps2, (std::vector<double>{0.1, 0.2, 0.3, -0.4}));
  EXPECT_EQ(m.dt_s, 0.02);
}

TEST(ParseRecord, TimeAccelerationPairsGiveDt) {
  const std::string text = "   0.0000  -4.0\n   0.0050  2.0\n   0.0100  1.0\n";
  ReadOptions options;
  options.units = Units::kCentimetresPerSecond2;
  const GroundMotion m = ParseRecord(text, "t.txt", options);
  EXPECT_EQ(m.format, "time-acc");
  EXPECT_EQ(m.dt_s, 0.005);
  EXPECT_EQ(m.acc_mps2, (std::vector<double>{-0.04, 0.02, 0.01}));
  options.dt_s = 0.01;
  EXPECT_THAT(ErrorOf([&] { ParseRecord(text, "t.txt", options); }),
              HasSubstr("t.txt:1: the file states dt = 0.005 s but dt = 0.01 s was given"));
}

TEST(ParseRecord, TimeAccelerationRejectsAnUnevenGrid) {
  ReadOptions options;
  options.units = Units::kG;
  options.format = Format::kTimeSeries;
  EXPECT_THAT(ErrorOf([&] { ParseRecord("0 1\n0.01 2\n0.03 3\n", "t.txt", options); }),
              HasSubstr("t.txt:2: time 0.01 is off the uniform grid of dt = 0.015 s"));
}

TEST(ParseRecord, UnitsStatedInTheFileWinOverNothingButMustAgreeWithTheUser) {
  ReadOptions options;
  options.units = Units::kCentimetresPerSecond2;
  EXPECT_THAT(ErrorOf([&] { ReadRecord(kData / "NIS090.AT2", options); }),
              HasSubstr("NIS090.AT2:3: the file states units g but cm/s^2 were given"));
}

// One malformed file per rule: the message names the file and the line, and says what is wrong.
struct Malformed {
  const char* file;
  const char* message;  // "FILE:LINE: problem" (prefix of the problem)
};

class MalformedFiles : public ::testing::TestWithParam<Malformed> {};

TEST_P(MalformedFiles, ErrorNamesFileLineAndProblem) {
  const std::filesystem::path path = kData / "malformed" / GetParam().file;
  EXPECT_THAT(ErrorOf([&] { ReadRecord(path); }),
              HasSubstr(path.string() + ":" + GetParam().message));
}

INSTANTIATE_TEST_SUITE_P(
    OneRuleEach, MalformedFiles,
    ::testing::Values(
        Malformed{"truncated.AT2", "4: header declares NPTS = 6 but the file holds 4 values"},
        Malformed{"npts_mismatch.AT2", "4: header declares NPTS = 7 but the file holds 6 values"},
        Malformed{"garbage_token.AT2", "6: '.6x00000E-01' is not a finite number"},
        Malformed{"zero_dt.AT2", "4: dt must be > 0 s"},
        Malformed{"nan.AT2", "5: NaN is not an acceleration"},
        Malformed{"empty.AT2", "1: the file is empty"},
        Malformed{"unknown_units.AT2", "3: unknown units 'FURLONGS/FORTNIGHT2'"}));

TEST(ReadRecord, ValidTwinOfTheMalformedFilesLoads) {
  const GroundMotion m = ReadRecord(kData / "malformed" / "valid.AT2");
  EXPECT_EQ(m.npts(), 6u);
  EXPECT_EQ(m.acc_mps2[2], -.03 * kStandardGravity_mps2);
}

TEST(ReadRecord, MissingFileIsAnInputError) {
  EXPECT_THAT(ErrorOf([&] { ReadRecord(kData / "no-such-file.AT2"); }),
              HasSubstr("no-such-file.AT2: record file: no such file"));
}

TEST(ParseUnits, AcceptsTheCommonSpellings) {
  EXPECT_EQ(ParseUnits("G"), Units::kG);
  EXPECT_EQ(ParseUnits("m/s^2"), Units::kMetresPerSecond2);
  EXPECT_EQ(ParseUnits("M/S/S"), Units::kMetresPerSecond2);
  EXPECT_EQ(ParseUnits("gal"), Units::kCentimetresPerSecond2);
  EXPECT_EQ(ParseUnits("CM/SEC/SEC"), Units::kCentimetresPerSecond2);
  EXPECT_FALSE(ParseUnits("ft/s2").has_value());
}

}  // namespace
}  // namespace skewbridge::records::readers_test
