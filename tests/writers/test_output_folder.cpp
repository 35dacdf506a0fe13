// The output folder deletes only the files an earlier run listed as its own (docs/output.md).
#include "writers/output_folder.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

namespace fs = std::filesystem;
using unsatmpm::is_output_file_name;
using unsatmpm::OutputFolder;

namespace test_output_folder {

class OutputFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device seed;
    root_ = fs::temp_directory_path() / ("unsatmpm_folder_test_" + std::to_string(seed()));
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  static void write(const fs::path& file, const std::string& text) { std::ofstream(file) << text; }
  fs::path root_;
};

TEST(OutputFileName, OutputNamesOnly) {
  for (const char* name : {"points_0000.vtu", "grid_0012.vtu", "points_last_good.vtu", "points.pvd",
                           "run_summary.json", "effective_case.yaml", "checkpoint.bin"})
    EXPECT_TRUE(is_output_file_name(name)) << name;
  for (const char* name : {"", "points_.vtu", "points_00a1.vtu", "../points_0000.vtu",
                           "sub/points.pvd", "thesis.docx", "points_0000.vtu.bak", "."})
    EXPECT_FALSE(is_output_file_name(name)) << name;
}

TEST_F(OutputFolderTest, ListsWhatItWritesAndReplacesOnlyThat) {
  const fs::path dir = root_ / "run";
  {
    OutputFolder folder(dir);
    write(folder.file("points_0000.vtu"), "a");
    write(folder.file("run_summary.json"), "{}");
    EXPECT_TRUE(fs::exists(dir / OutputFolder::lock_name));
    EXPECT_THROW(folder.file("notes.txt"), std::logic_error);
  }
  EXPECT_FALSE(fs::exists(dir / OutputFolder::lock_name));
  write(dir / "points_0000.vtu.tmp", "partial");  // a write cut short by a kill
  {
    OutputFolder again(dir);
    EXPECT_FALSE(again.found_stale_lock());
    EXPECT_FALSE(fs::exists(dir / "points_0000.vtu"));
    EXPECT_FALSE(fs::exists(dir / "points_0000.vtu.tmp"));
    EXPECT_FALSE(fs::exists(dir / "run_summary.json"));
  }
}

TEST_F(OutputFolderTest, RefusesForeignEntriesAndTouchesNothing) {
  const fs::path dir = root_ / "run";
  { OutputFolder(dir).file("points_0000.vtu"); }
  write(dir / "points_0000.vtu", "a");
  fs::create_directory(dir / "points_0001.vtu");  // an output name, but a folder
  EXPECT_THROW(OutputFolder{dir}, std::runtime_error);
  EXPECT_TRUE(fs::exists(dir / "points_0000.vtu"));
  EXPECT_TRUE(fs::is_directory(dir / "points_0001.vtu"));
  EXPECT_FALSE(fs::exists(dir / OutputFolder::lock_name));
}

TEST_F(OutputFolderTest, AManifestNotOfOursIsRefused) {
  const fs::path dir = root_ / "run";
  fs::create_directories(dir);
  write(dir / OutputFolder::manifest_name, "points_0000.vtu\n");
  write(dir / "points_0000.vtu", "a");
  try {
    OutputFolder folder(dir);
    FAIL() << "a manifest without the header was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not a manifest written by unsatmpm"), std::string::npos);
  }
  EXPECT_TRUE(fs::exists(dir / "points_0000.vtu"));
}

TEST_F(OutputFolderTest, AStaleLockIsReportedAndALiveOneRefused) {
  const fs::path dir = root_ / "run";
  { OutputFolder first(dir); }
  write(dir / OutputFolder::lock_name, "12345");  // left by a run that was killed
  {
    OutputFolder folder(dir);
    EXPECT_TRUE(folder.found_stale_lock());
    // A second claim while this one lives: flock locks are per open file, so this holds even
    // within one process.
    try {
      OutputFolder second(dir);
      FAIL() << "a held folder was claimed twice";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("in use by another unsatmpm run"), std::string::npos);
    }
  }
}

// A resumed run claims its own folder: the same checks and lock, every listed file kept, only
// the temporary files of unfinished writes removed; a folder without a checkpoint is refused.
TEST_F(OutputFolderTest, AResumeKeepsTheRunsFilesAndDropsItsUnfinishedWrites) {
  const fs::path dir = root_ / "run";
  {
    OutputFolder folder(dir);
    write(folder.file("points_0000.vtu"), "frame");
    write(folder.file("checkpoint.bin"), "state");
    write(folder.file("points_0001.vtu").string() + ".tmp", "partial");  // killed mid-write
  }
  write(dir / "checkpoint.bin.tmp", "partial");
  {
    OutputFolder folder(dir, OutputFolder::Claim::resume);
    EXPECT_TRUE(fs::exists(dir / "points_0000.vtu"));
    EXPECT_TRUE(fs::exists(dir / "checkpoint.bin"));
    EXPECT_FALSE(fs::exists(dir / "checkpoint.bin.tmp"));
    EXPECT_FALSE(fs::exists(dir / "points_0001.vtu.tmp"));
    write(folder.file("points_0001.vtu"), "frame");
    // A second claim while this one holds the lock is refused.
    EXPECT_THROW(OutputFolder(dir, OutputFolder::Claim::resume), std::runtime_error);
  }
  // The manifest lists each file once, the one written after the resume too.
  std::ifstream manifest(dir / OutputFolder::manifest_name);
  std::string line;
  int checkpoints = 0, frames = 0;
  while (std::getline(manifest, line))
    checkpoints += line == "checkpoint.bin", frames += line == "points_0001.vtu";
  EXPECT_EQ(checkpoints, 1);
  EXPECT_EQ(frames, 1);
}

TEST_F(OutputFolderTest, AResumeNeedsAFolderWithACheckpoint) {
  EXPECT_THROW(OutputFolder(root_ / "missing", OutputFolder::Claim::resume), std::runtime_error);
  EXPECT_FALSE(fs::exists(root_ / "missing"));
  const fs::path dir = root_ / "run";
  {
    OutputFolder folder(dir);
    write(folder.file("points_0000.vtu"), "frame");
  }
  try {
    OutputFolder folder(dir, OutputFolder::Claim::resume);
    FAIL() << "claimed a folder without a checkpoint";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("holds no checkpoint"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::exists(dir / "points_0000.vtu"));
  { OutputFolder(dir).file("checkpoint.bin"); }
  write(dir / "thesis.docx", "mine");
  EXPECT_THROW(OutputFolder(dir, OutputFolder::Claim::resume), std::runtime_error);
  EXPECT_TRUE(fs::exists(dir / "thesis.docx"));
}

}  // namespace test_output_folder
