#include "amos/io/atomic_file.h"

#include <gtest/gtest.h>

#include "amos/testing/scratch_dir.h"

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "amos/core/error.h"

namespace amos::io {
namespace {

namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
  return amos::testing::scratchDir("amos_atomic_file_test_" + name);
}

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(AtomicFile, ReplacesTheFileAndLeavesNoTemporaryName) {
  const fs::path dir = freshDir("replace");
  const std::string path = (dir / "stats.json").string();
  writeFileAtomically(path, "old\n");
  writeFileAtomically(path, "new\n");
  EXPECT_EQ(readAll(path), "new\n");
  EXPECT_FALSE(fs::exists(partialPath(path)));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

// A write that cannot finish (here: the final name is a folder, so the rename fails) keeps what was there and
// removes its temporary file.
TEST(AtomicFile, AFailedWriteLeavesNoPartialFile) {
  const fs::path dir = freshDir("failed");
  fs::create_directories(dir / "trajectory.txt" / "in_the_way");
  try {
    writeFileAtomically((dir / "trajectory.txt").string(), "1 2 3\n");
    FAIL() << "expected a core::Error";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("trajectory.txt"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_directory(dir / "trajectory.txt" / "in_the_way"));
  EXPECT_FALSE(fs::exists(partialPath((dir / "trajectory.txt").string())));
  EXPECT_THROW(writeFileAtomically((dir / "no_such_folder" / "x.txt").string(), "x"), core::Error);
  fs::remove_all(dir);
}

TEST(AtomicFile, ImagesAreEncodedByTheirExtension) {
  const fs::path dir = freshDir("image");
  cv::Mat mask(6, 8, CV_8U, cv::Scalar(0));
  mask(cv::Rect(2, 1, 3, 4)).setTo(255);
  const std::string path = (dir / "1.000000.png").string();
  writeImageAtomically(path, mask);
  const cv::Mat back = cv::imread(path, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(back.type(), CV_8UC1);
  EXPECT_EQ(cv::norm(back, mask, cv::NORM_INF), 0.0);
  EXPECT_FALSE(fs::exists(partialPath(path)));
  EXPECT_THROW(writeImageAtomically((dir / "x.unknown_format").string(), mask), core::Error);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace amos::io
