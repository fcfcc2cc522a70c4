// The files a grid's cells read (spectra::GridInputFiles): the model file, the excitation file
// it names, the record-set manifest and the record files of the records the grid names, each
// once, in that order; a missing excitation file is refused naming the model file, a missing
// record file naming the set's line.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "solver/common/error.h"
#include "spectra/inputs.h"

namespace skewbridge::spectra::inputs_test {
namespace {

namespace fs = std::filesystem;

constexpr const char* kDeck = R"([deck]
m = 500e3
I_m = "uniform"
L = 30.0
W = 12.0
skew_deg = 30.0
[substructure]
kind = "uncoupled"
w0 = 10.0
W0 = 12.0
xi = 0.05
[abutments]
set = "both"
gap_m = 0.03
eps_N = 0.5
mu = 0.0
[excitation]
kind = "sampled"
file = "exc/g.txt"
dt_s = 0.01
units = "mps2"
direction = "x"
)";

class GridInputsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / "sb_grid_inputs_test";
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "exc");
    fs::create_directories(dir_ / "recs");
    std::ofstream(dir_ / "deck.toml") << kDeck;
    std::ofstream(dir_ / "exc" / "g.txt") << "0.0\n1.0\n0.0\n";
    std::ofstream(dir_ / "recs" / "a.txt") << "0.0\n";
    std::ofstream(dir_ / "recs" / "b.txt") << "0.0\n";
    // Labels A and A2 read one file (two components of one record would): listed once.
    std::ofstream(dir_ / "set.toml")
        << "name = \"s\"\n"
        << "[[record]]\nfile = \"recs/a.txt\"\nlabel = \"A\"\nunits = \"g\"\ndt = 0.01\n"
        << "[[record]]\nfile = \"recs/a.txt\"\nlabel = \"A2\"\nunits = \"g\"\ndt = 0.01\n"
        << "[[record]]\nfile = \"recs/b.txt\"\nlabel = \"B\"\nunits = \"g\"\ndt = 0.01\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  CellGrid Grid(std::vector<std::string> labels) const {
    CellGrid grid;
    grid.source = "spec.toml";
    grid.family = "model-file";
    grid.model_file = "deck.toml";
    grid.model_path = dir_ / "deck.toml";
    grid.record_set = "set.toml";
    grid.record_set_path = dir_ / "set.toml";
    Axis axis;
    axis.key = "record";
    axis.kind = ParameterKind::kLabel;
    axis.labels = std::move(labels);
    grid.axes.push_back(axis);
    return grid;
  }

  fs::path dir_;
};

TEST_F(GridInputsTest, ListsTheModelItsExcitationTheManifestAndTheRecordsNamed) {
  const std::vector<GridInput> inputs = GridInputFiles(Grid({"A", "A2"}));
  ASSERT_EQ(inputs.size(), 4u);
  EXPECT_EQ(inputs[0].role, "model");
  EXPECT_EQ(inputs[0].path, dir_ / "deck.toml");
  EXPECT_EQ(inputs[1].role, "excitation");
  EXPECT_EQ(inputs[1].path.lexically_normal(), (dir_ / "exc" / "g.txt").lexically_normal());
  EXPECT_EQ(inputs[2].role, "record-set");
  EXPECT_EQ(inputs[3].role, "record");
  EXPECT_EQ(inputs[3].path.lexically_normal(), (dir_ / "recs" / "a.txt").lexically_normal());
  // B joins only when the grid names it.
  const std::vector<GridInput> all = GridInputFiles(Grid({"A", "B"}));
  ASSERT_EQ(all.size(), 5u);
  EXPECT_EQ(all[4].path.lexically_normal(), (dir_ / "recs" / "b.txt").lexically_normal());
}

TEST_F(GridInputsTest, RefusesAMissingExcitationFileNamingTheModelFile) {
  fs::remove(dir_ / "exc" / "g.txt");
  try {
    GridInputFiles(Grid({"A"}));
    FAIL() << "a missing excitation file was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("deck.toml: excitation.file: file not found"));
  }
}

TEST_F(GridInputsTest, RefusesAMissingRecordFileAtItsLineOfTheSet) {
  fs::remove(dir_ / "recs" / "b.txt");
  // A record the grid does not name may be missing: the sweep never reads it.
  EXPECT_EQ(GridInputFiles(Grid({"A"})).size(), 4u);
  try {
    GridInputFiles(Grid({"A", "B"}));
    FAIL() << "a missing record file was accepted";
  } catch (const InputError& e) {
    // B's [[record]] table is on line 12 of the set (name, then two tables of five lines).
    EXPECT_THAT(e.what(), ::testing::HasSubstr("set.toml:12: record 'B': no such file: "));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("b.txt"));
  }
}

TEST_F(GridInputsTest, APulseGridWithoutAModelReadsNoFile) {
  CellGrid grid;
  grid.family = "subsystem";
  Axis axis;
  axis.key = "pulse";
  axis.kind = ParameterKind::kLabel;
  axis.labels = {"cosine"};
  grid.axes.push_back(axis);
  EXPECT_TRUE(GridInputFiles(grid).empty());
}

}  // namespace
}  // namespace skewbridge::spectra::inputs_test
