#include "amos/report/output_folder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "amos/core/error.h"

namespace amos::report {
namespace {

namespace fs = std::filesystem;

fs::path freshRoot(const std::string& name) {
  const fs::path root = fs::path(AMOS_BINARY_DIR) / "test_outputs" / "output_folder" / name;
  fs::remove_all(root);
  fs::create_directories(root);
  return root;
}

std::string errorOf(const std::string& dir, bool overwrite) {
  try {
    prepareOutputFolder(dir, overwrite);
  } catch (const core::Error& e) {
    return e.what();
  }
  return "";
}

void touch(const fs::path& path) { std::ofstream(path) << "x\n"; }

TEST(OutputFolder, CreatesTheFolderAndLeavesNothingInIt) {
  const fs::path out = freshRoot("create") / "a" / "b";
  prepareOutputFolder(out.string(), false);
  ASSERT_TRUE(fs::is_directory(out));
  EXPECT_TRUE(fs::is_empty(out));
  prepareOutputFolder(out.string(), false);  // an empty folder is fine, again and again
}

TEST(OutputFolder, APathUnderARegularFileNamesThatFile) {
  const fs::path root = freshRoot("under_file");
  touch(root / "notes.txt");
  const std::string under = errorOf((root / "notes.txt" / "run").string(), false);
  EXPECT_NE(under.find("notes.txt' is a file"), std::string::npos) << under;
  const std::string itself = errorOf((root / "notes.txt").string(), false);
  EXPECT_NE(itself.find("is a file, not a folder"), std::string::npos) << itself;
}

// /proc/self is a folder that nobody, root included, can create files in.
TEST(OutputFolder, AnUnwritableFolderIsAnError) {
  const std::string message = errorOf("/proc/self", false);
  EXPECT_NE(message.find("cannot write into output folder '/proc/self'"), std::string::npos) << message;
}

TEST(OutputFolder, AnEarlierRunIsRefusedWithoutOverwrite) {
  for (const std::string name : {"trajectory.txt", "stats.json", "masks"}) {
    const fs::path out = freshRoot("earlier_" + name);
    if (name == "masks") {
      fs::create_directories(out / name);
    } else {
      touch(out / name);
    }
    const std::string message = errorOf(out.string(), false);
    EXPECT_NE(message.find("holds an earlier run (" + name + ")"), std::string::npos) << message;
    EXPECT_NE(message.find("--overwrite"), std::string::npos) << message;
    EXPECT_TRUE(fs::exists(out / name));
  }
}

TEST(OutputFolder, OverwriteRemovesOnlyTheEarlierRunsOutputs) {
  const fs::path out = freshRoot("overwrite");
  for (const std::string& name : runOutputNames()) {
    if (name == "masks" || name == "overlays") {
      fs::create_directories(out / name);
      touch(out / name / "1.0.png");
    } else {
      touch(out / name);
    }
  }
  touch(out / "trajectory.txt.partial");  // left by a run killed while writing
  touch(out / "notes.txt");
  fs::create_directories(out / "plots");
  prepareOutputFolder(out.string(), true);
  for (const std::string& name : runOutputNames()) EXPECT_FALSE(fs::exists(out / name)) << name;
  EXPECT_FALSE(fs::exists(out / "trajectory.txt.partial"));
  EXPECT_TRUE(fs::exists(out / "notes.txt"));
  EXPECT_TRUE(fs::is_directory(out / "plots"));
}

}  // namespace
}  // namespace amos::report
