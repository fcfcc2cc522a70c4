// The excitation-file reader of model files against an independent reading of the same text
// (istringstream), and its refusals.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "records/excitations.h"
#include "solver/common/error.h"

namespace skewbridge::records::signal_file_test {
namespace {

std::string Message(std::string_view text, std::optional<double> dt_s, double to_mps2 = 1.0) {
  try {
    ParseExcitationSamples(text, "sig.txt", dt_s, to_mps2);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ExcitationSamples, ReadsThePilotSignalAsAPlainStreamDoes) {
  const std::filesystem::path path = std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) / ".." / ".." /
                                     "docs" / "examples" / "pilot-signal.txt";
  const ExcitationSamples s = ReadExcitationSamples(path, std::nullopt, 2.0);
  std::ifstream in(path);
  std::vector<double> expected;
  double t = 0.0, a = 0.0;
  while (in >> t >> a) expected.push_back(2.0 * a);
  ASSERT_GT(expected.size(), 400u);
  ASSERT_EQ(s.values_mps2.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    ASSERT_EQ(s.values_mps2[k], expected[k]) << k;
  }
  EXPECT_EQ(s.dt_s, 0.01);
}

TEST(ExcitationSamples, CommasCommentsAndCrLfAreTheSameSamples) {
  const ExcitationSamples plain = ParseExcitationSamples("0 1\n0.5 2\n1.0 -3\n", "a", {}, 1.0);
  const ExcitationSamples other =
      ParseExcitationSamples("# t, a\r\n0,1\r\n\r\n0.5, 2\r\n1.0 ,-3", "b", 0.5, 1.0);
  EXPECT_EQ(plain.values_mps2, (std::vector<double>{1.0, 2.0, -3.0}));
  EXPECT_EQ(other.values_mps2, plain.values_mps2);
  EXPECT_EQ(plain.dt_s, 0.5);
  EXPECT_EQ(other.dt_s, 0.5);
}

TEST(ExcitationSamples, AcceptsATimeColumnRoundedToItsPrintedDigits) {
  // dt = 1/3 s printed with three decimals: steps of 0.333 and 0.334 s are one grid.
  const ExcitationSamples s =
      ParseExcitationSamples("0.000 0\n0.333 1\n0.667 0\n1.000 -1\n", "a", {}, 1.0);
  EXPECT_NEAR(s.dt_s, 1.0 / 3.0, 1e-9);
}

TEST(ExcitationSamples, KeepsAStepTooLargeToRoundToTheNanosecond) {
  // 1e300 s times 1e9 overflows: the step is the file's own, finite, not the rounding's inf.
  const ExcitationSamples s = ParseExcitationSamples("0.00 0.0\n0.01e302 0\n", "a", {}, 1e300);
  EXPECT_EQ(s.dt_s, 1e300);
  EXPECT_EQ(s.values_mps2, (std::vector<double>{0.0, 0.0}));
}

TEST(ExcitationSamples, RefusesEachMalformedLineWhereItStands) {
  EXPECT_EQ(Message("0 0\n0.01 0.1 7\n", {}),
            "sig.txt:2: 3 columns where the first data line (line 1) has 2 (time in s, "
            "acceleration); allowed: the same columns on every data line");
  EXPECT_EQ(Message("0 0\n0.01 0.123xyz\n", {}),
            "sig.txt:2: '0.123xyz' in column 2 (acceleration) is not a finite number; allowed: "
            "finite decimal numbers such as -1.234e-02");
  EXPECT_EQ(Message("0 0\n0.01 0.1\n0.02 0\n0.03 0\n", 0.02),
            "sig.txt:2: the time column steps by 0.01 s but the model file gives "
            "excitation.dt_s = 0.02 s; allowed: no dt_s, or the step of the time column");
  EXPECT_EQ(Message("0 0\n0.01 0.1\n4.00 nan\n", 0.01),
            "sig.txt:3: 'nan' in column 2 (acceleration) is NaN; allowed: finite decimal numbers "
            "such as -1.234e-02");
  EXPECT_EQ(Message("0\n1e300\n", 0.01, 1e10),
            "sig.txt:2: acceleration 1e+300 times units and scale (1e+10) is not a finite "
            "number in m/s^2");
  EXPECT_EQ(Message("0x10 0\n", {}),
            "sig.txt:1: '0x10' in column 1 (time, s) is not a finite number; allowed: finite "
            "decimal numbers such as -1.234e-02");
  EXPECT_EQ(Message("", 0.01), "sig.txt: no samples (only blank or '#' lines)");
}

}  // namespace
}  // namespace skewbridge::records::signal_file_test
