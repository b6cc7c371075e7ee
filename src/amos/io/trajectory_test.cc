#include "amos/io/trajectory.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "amos/core/error.h"
#include "amos/testing/shared_data.h"
#include "amos/testing/scratch_dir.h"

namespace amos::io {
namespace {

namespace fs = std::filesystem;

// A scratch file of this test process (testing::scratchDir).
std::string scratchPath(const std::string& name) {
  static const fs::path dir = testing::scratchDir("amos_trajectory");
  return (dir / name).string();
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

TEST(TumTrajectory, RoundTripKeepsPosesToNanometres) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  std::vector<StampedPose> poses;
  for (int i = 0; i < 50; ++i) {
    StampedPose p;
    p.timestamp = 1305031098.665912 + 0.033 * i;
    p.T_wc = core::expSE3((core::Vector6d() << u(rng), u(rng), u(rng), u(rng) / 3, u(rng) / 3, u(rng) / 3)
                              .finished());
    poses.push_back(p);
  }
  const std::string path = scratchPath("round_trip.txt");
  writeTumTrajectory(path, poses);
  const std::vector<StampedPose> back = readTumTrajectory(path);
  ASSERT_EQ(back.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_NEAR(back[i].timestamp, poses[i].timestamp, 1e-6);  // %.6f of a 1e9 s stamp
    EXPECT_LT((back[i].T_wc.translation() - poses[i].T_wc.translation()).norm(), 2e-9);
    EXPECT_LT((back[i].T_wc.linear() - poses[i].T_wc.linear()).norm(), 1e-8);
  }
}

TEST(TumTrajectory, AcceptsCommentsBlankLinesCommasAndTabs) {
  const std::string path = scratchPath("separators.txt");
  writeText(path,
            "# ground truth trajectory\n"
            "\n"
            "   \n"
            "  # indented comment\n"
            "1.0 1 2 3 0 0 0 1\n"
            "2.0,4,5,6,0,0,0,2\n"          // unnormalised quaternion is normalised
            "3.0\t7\t8\t9\t0\t0\t1\t0\r\n"  // tabs and a Windows line end
            "4.0, +1e-1 , 0 ,0, 0,0,0,1\n");
  const std::vector<StampedPose> poses = readTumTrajectory(path);
  ASSERT_EQ(poses.size(), 4u);
  EXPECT_DOUBLE_EQ(poses[0].timestamp, 1.0);
  EXPECT_EQ(poses[1].T_wc.translation(), Eigen::Vector3d(4, 5, 6));
  EXPECT_LT((poses[1].T_wc.linear() - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  // q = (x 0, y 0, z 1, w 0): 180 degrees about z.
  EXPECT_LT((poses[2].T_wc.linear() - Eigen::Vector3d(-1, -1, 1).asDiagonal().toDenseMatrix()).norm(), 1e-15);
  EXPECT_DOUBLE_EQ(poses[3].T_wc.translation().x(), 0.1);
}

std::string errorOf(const std::string& path, const std::string& role) {
  try {
    readTumTrajectoryWithPoses(path, role);
  } catch (const core::Error& e) {
    return e.what();
  }
  return "";
}

TEST(TumTrajectory, AFileThatMustHoldPosesNamesItselfWhenEmptyOrUnusable) {
  const std::string empty = scratchPath("empty_gt.txt"), comments = scratchPath("comments_gt.txt"),
                    unusable = scratchPath("unusable_gt.txt"), good = scratchPath("good_gt.txt");
  writeText(empty, "");
  writeText(comments, "# timestamp tx ty tz qx qy qz qw\n\n");
  writeText(unusable, "1 0 0 0 0 0 0 0\n2 nan 0 0 0 0 0 1\n");
  writeText(good, "1 0 0 0 0 0 0 1\n");
  EXPECT_TRUE(readTumTrajectory(empty).empty());  // a run that tracked nothing writes such a file
  for (const std::string& path : {empty, comments}) {
    EXPECT_EQ(errorOf(path, "ground-truth file"), "ground-truth file '" + path + "' is empty: it has no pose line");
  }
  EXPECT_NE(errorOf(unusable, "estimate file").find("estimate file '" + unusable + "' has no usable pose: all 2"),
            std::string::npos);
  EXPECT_NE(errorOf(scratchPath("missing_gt.txt"), "ground-truth file").find("ground-truth file"), std::string::npos);
  EXPECT_NE(errorOf(fs::path(good).parent_path().string(), "ground-truth file").find("not a regular file"),
            std::string::npos);
  EXPECT_EQ(readTumTrajectoryWithPoses(good, "ground-truth file").size(), 1u);
}

TEST(TumTrajectory, AnUnreadableFileIsNamedUnreadable) {
  const std::string path = scratchPath("unreadable_gt.txt");
  writeText(path, "1 0 0 0 0 0 0 1\n");
  fs::permissions(path, fs::perms::none);
  if (std::ifstream(path).good()) GTEST_SKIP() << "permissions do not apply to this user (root)";
  EXPECT_NE(errorOf(path, "ground-truth file").find("ground-truth file '" + path + "' cannot be read: "),
            std::string::npos);
}

TEST(TumTrajectory, SkipsZeroQuaternionAndNanLinesLikeTheBenchmark) {
  const std::string path = scratchPath("zero_q.txt");
  writeText(path, "1 0 0 0 0 0 0 0\n2 nan 0 0 0 0 0 1\n3 1 1 1 0 0 0 1\n");
  const std::vector<StampedPose> poses = readTumTrajectory(path);
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_DOUBLE_EQ(poses[0].timestamp, 3.0);
}

TEST(TumTrajectory, MalformedLineNamesFileAndLine) {
  const std::string path = scratchPath("malformed.txt");
  writeText(path, "# header\n1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n");
  try {
    readTumTrajectory(path);
    FAIL() << "no error for a line with 7 fields";
  } catch (const core::Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path + ":3:"), std::string::npos) << message;
    EXPECT_NE(message.find("7 fields"), std::string::npos) << message;
  }
  writeText(path, "1 0 0 0 0 0 0 1\n\n2 0 0 zero 0 0 0 1\n");
  try {
    readTumTrajectory(path);
    FAIL() << "no error for a non-numeric field";
  } catch (const core::Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path + ":3:"), std::string::npos) << message;
    EXPECT_NE(message.find("'zero'"), std::string::npos) << message;
  }
}

TEST(TumTrajectory, ParsedTextGivesWhatTheFileGivesAndNamesThePathInErrors) {
  const std::string text = "# header\n1.0 1 2 3 0 0 0 2\n2.0,4,5,6,0,0,1,0\n3.0 0 0 0 0 0 0 0\n";
  const std::string path = scratchPath("parsed.txt");
  writeText(path, text);
  const std::vector<StampedPose> from_file = readTumTrajectory(path);
  const std::vector<StampedPose> from_text = parseTumTrajectory(text, "named.txt");
  ASSERT_EQ(from_text.size(), 2u);
  ASSERT_EQ(from_file.size(), from_text.size());
  for (std::size_t i = 0; i < from_text.size(); ++i) {
    EXPECT_EQ(from_text[i].timestamp, from_file[i].timestamp);
    EXPECT_EQ(from_text[i].T_wc.matrix(), from_file[i].T_wc.matrix());
  }
  try {
    parseTumTrajectory("1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n", "named.txt");
    FAIL() << "no error for a line with 7 fields";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("named.txt:2:"), std::string::npos) << e.what();
  }
}

TEST(TumTrajectory, MissingFileIsAClearError) {
  const std::string path = scratchPath("does_not_exist.txt");
  try {
    readTumTrajectory(path);
    FAIL() << "no error for a missing file";
  } catch (const core::Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
  }
}

TEST(TumTrajectory, ReadsTheOfficialGroundTruth) {
  AMOS_REQUIRE_DATA("trajectories");
  const std::string path = testing::dataPath("trajectories/rgbd_dataset_freiburg1_xyz_groundtruth.txt");
  const std::vector<StampedPose> poses = readTumTrajectory(path);
  ASSERT_EQ(poses.size(), 3000u);  // 3003 lines, 3 of them comments
  EXPECT_DOUBLE_EQ(poses[0].timestamp, 1305031098.6659);
  EXPECT_EQ(poses[0].T_wc.translation(), Eigen::Vector3d(1.3563, 0.6305, 1.6380));
}

}  // namespace
}  // namespace amos::io
