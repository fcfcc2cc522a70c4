// The writer's lock and the output-path checks, in one process: flock locks belong to open
// file descriptions, so a second OutputLock on the same output conflicts with the first just
// as a second process would.
#include "jobs/output_lock.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <string>

#include "solver/common/error.h"

namespace skewbridge::jobs {
namespace {

namespace fs = std::filesystem;

class OutputLockTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("sb_lock_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

std::string Message(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST_F(OutputLockTest, SecondWriterIsRefusedNamingTheHolder) {
  const fs::path out = dir_ / "cube.h5";
  OutputLock first(out);
  std::ifstream in(LockPath(out));
  std::string pid, host;
  in >> pid >> host;
  EXPECT_EQ(pid, std::to_string(::getpid()));
  const std::string message = Message([&] { OutputLock second(out); });
  EXPECT_NE(message.find(out.string() + ": is being written by another sweep (process " + pid +
                         " on host " + host),
            std::string::npos)
      << message;
}

TEST_F(OutputLockTest, ReleaseRemovesTheFileAndFreesTheOutput) {
  const fs::path out = dir_ / "cube.h5";
  { OutputLock first(out); }
  EXPECT_FALSE(fs::exists(LockPath(out)));
  OutputLock again(out);
  EXPECT_TRUE(fs::exists(LockPath(out)));
}

TEST_F(OutputLockTest, StaleLockFileOfADeadProcessIsTakenOver) {
  const fs::path out = dir_ / "cube.h5";
  std::ofstream(LockPath(out)) << "999999 gone-host\n";
  OutputLock lock(out);
  std::ifstream in(LockPath(out));
  std::string pid;
  in >> pid;
  EXPECT_EQ(pid, std::to_string(::getpid()));
}

TEST_F(OutputLockTest, UnusableOutputPathsAreRefused) {
  EXPECT_NE(Message([] { CheckOutputPath(""); }).find("--out: FILE: is empty"), std::string::npos);
  EXPECT_NE(Message([&] { CheckOutputPath(dir_); }).find("is a folder"), std::string::npos);
  fs::create_directories(dir_ / "x.h5.partial");
  EXPECT_NE(Message([&] { CheckOutputPath(dir_ / "x.h5"); }).find("x.h5.partial: is a folder"),
            std::string::npos);
  EXPECT_NE(Message([&] { CheckOutputPath(dir_ / "none" / "c.h5"); }).find("does not exist"),
            std::string::npos);
  EXPECT_EQ(Message([&] { CheckOutputPath(dir_ / "c.h5"); }), "");
}

}  // namespace
}  // namespace skewbridge::jobs
