// Every record of ../shared/records loads through the record-set manifest records/sets/shared.toml
// and matches the collection's MANIFEST.csv: npts exactly, dt, and PGA within the manifest's
// rounding (4 decimals of g).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "records/ground_motion.h"
#include "records/record_set.h"

namespace skewbridge::records::shared_records_test {
namespace {

const std::filesystem::path kShared = std::filesystem::path(SKEWBRIDGE_SHARED_DIR) / "records";
const std::filesystem::path kSetManifest = std::filesystem::path(SKEWBRIDGE_TEST_DATA_DIR) / ".." /
                                           ".." / "records" / "sets" / "shared.toml";

// The reader each collection folder needs, detected by content.
const std::map<std::string, std::string> kFormatOf = {{"at2_nga_west2", "at2"},
                                                      {"at2_peer_legacy", "at2"},
                                                      {"esm_ascii", "esm"},
                                                      {"itsak", "itsak"},
                                                      {"cosmos_v2c", "cosmos"},
                                                      {"csmip_v2", "csmip"},
                                                      {"usgs_smc", "smc"},
                                                      {"smtk_cor_acc", "smtk"},
                                                      {"single_column", "plain"},
                                                      {"multi_value_no_header", "plain"},
                                                      {"two_column_time_acc", "time-acc"}};

// Fields of one CSV line, with RFC 4180 quoting.
std::vector<std::string> CsvFields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

std::map<std::string, std::map<std::string, std::string>> ReadManifest() {
  std::ifstream in(kShared / "MANIFEST.csv");
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = CsvFields(line);
  std::map<std::string, std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> fields = CsvFields(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < fields.size(); ++i) row[header[i]] = fields[i];
    rows[row["file"]] = row;
  }
  return rows;
}

TEST(SharedRecords, EveryFileLoadsAndMatchesTheManifest) {
  if (!std::filesystem::exists(kShared / "MANIFEST.csv")) {
    GTEST_SKIP() << "no shared record collection at " << kShared << "; nothing to check";
  }
  const auto manifest = ReadManifest();
  const RecordSet set = LoadRecordSet(kSetManifest);
  ASSERT_EQ(set.records.size(), manifest.size()) << "shared.toml must list every shared record";
  for (const RecordEntry& entry : set.records) {
    const std::string relative =
        std::filesystem::relative(std::filesystem::weakly_canonical(entry.file),
                                  std::filesystem::weakly_canonical(kShared))
            .generic_string();
    SCOPED_TRACE(relative);
    ASSERT_EQ(manifest.count(relative), 1u);
    const auto& row = manifest.at(relative);
    const GroundMotion m = LoadRecord(entry);
    EXPECT_EQ(m.npts(), std::stoul(row.at("npts")));
    // "not stated (0.02 assumed)": the leading number is what the manifest assumes.
    const std::string dt_text = row.at("dt_s");
    EXPECT_NEAR(m.dt_s, std::stod(dt_text.substr(dt_text.find_first_of("0123456789."))), 1e-12);
    double pga = 0.0;
    for (double a : m.acc_mps2) pga = std::max(pga, std::abs(a));
    EXPECT_NEAR(pga / kStandardGravity_mps2, std::stod(row.at("pga_g")), 0.5e-4 + 1e-9);
    EXPECT_EQ(m.original_units, row.at("units_in_file"));
    EXPECT_EQ(m.format, kFormatOf.at(row.at("format")));
  }
}

// Every pair of ../shared/records/pairs_nga_west2 loads through records/sets/pairs_nga_west2.toml
// as two components of one dt and one length, each matching PAIRS.csv (npts before the padding,
// dt, PGA to the file's 4 decimals of g), the shorter padded with exactly the difference.
TEST(SharedRecords, EveryPairLoadsAndMatchesPairsCsv) {
  const std::filesystem::path folder = kShared / "pairs_nga_west2";
  if (!std::filesystem::exists(folder / "PAIRS.csv")) {
    GTEST_SKIP() << "no shared pair collection at " << folder << "; nothing to check";
  }
  std::ifstream in(folder / "PAIRS.csv");
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = CsvFields(line);
  std::map<std::string, std::map<std::string, std::string>> pairs;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> fields = CsvFields(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < fields.size(); ++i) row[header[i]] = fields[i];
    pairs[row.at("pair")] = row;
  }
  const RecordSet set = LoadRecordSet(kSetManifest.parent_path() / "pairs_nga_west2.toml");
  ASSERT_EQ(set.records.size(), pairs.size());
  ASSERT_EQ(set.records.size(), 50u);
  std::size_t padded_pairs = 0;
  for (const RecordEntry& entry : set.records) {
    SCOPED_TRACE(entry.label);
    ASSERT_TRUE(entry.IsPair());
    ASSERT_EQ(pairs.count(entry.label), 1u);
    const auto& row = pairs.at(entry.label);
    const RecordComponents c = LoadComponents(entry);
    ASSERT_TRUE(c.IsPair());
    const std::size_t n1 = std::stoul(row.at("h1_npts"));
    const std::size_t n2 = std::stoul(row.at("h2_npts"));
    EXPECT_EQ(c.motions[0].npts(), std::max(n1, n2));
    EXPECT_EQ(c.motions[1].npts(), std::max(n1, n2));
    EXPECT_EQ(c.padded_samples[0], std::max(n1, n2) - n1);
    EXPECT_EQ(c.padded_samples[1], std::max(n1, n2) - n2);
    padded_pairs += n1 != n2 ? 1 : 0;
    for (std::size_t k = 0; k < 2; ++k) {
      const std::string h = k == 0 ? "h1_" : "h2_";
      EXPECT_NEAR(c.motions[k].dt_s, std::stod(row.at(h + "dt_s")), 1e-12);
      EXPECT_EQ(c.motions[k].component, row.at(h + "component"));
      double pga = 0.0;
      for (double a : c.motions[k].acc_mps2) pga = std::max(pga, std::abs(a));
      EXPECT_NEAR(pga / kStandardGravity_mps2, std::stod(row.at(h + "pga_g")), 0.5e-4 + 1e-9);
    }
  }
  EXPECT_GT(padded_pairs, 0u);  // RSN107 at least (2630 and 2405 samples)
}

TEST(SharedRecords, FormatIsDetectedByContentNotExtension) {
  if (!std::filesystem::exists(kShared / "esm_ascii" / "KM.AT2")) {
    GTEST_SKIP() << "no shared record collection at " << kShared;
  }
  EXPECT_EQ(ReadRecord(kShared / "esm_ascii" / "KM.AT2").format, "esm");
  ReadOptions options;
  options.units = Units::kG;
  const GroundMotion itsak = ReadRecord(kShared / "itsak" / "A299_T", options);
  EXPECT_EQ(itsak.npts(), 5702u);
  // Value 5703 (-.002137, line 715) precedes the zero padding: dropped, and said so.
  ASSERT_EQ(itsak.notes.size(), 1u);
  EXPECT_NE(itsak.notes[0].find("A299_T:715: dropped 1 non-zero value(s) beyond the declared 5702"),
            std::string::npos);
}

}  // namespace
}  // namespace skewbridge::records::shared_records_test
