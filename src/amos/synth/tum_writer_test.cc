#include "amos/synth/tum_writer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "amos/core/error.h"

namespace amos::synth {
namespace {

namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
  const fs::path dir = fs::path(AMOS_BINARY_DIR) / "synth_test_output" / name;
  fs::remove_all(dir);
  return dir;
}

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::vector<std::string>> rows(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::vector<std::string>> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::vector<std::string> cols;
    std::string c;
    while (ss >> c) cols.push_back(c);
    out.push_back(cols);
  }
  return out;
}

SequenceOptions options() {
  SequenceOptions o;
  o.preset = "walking_xyz";
  o.seed = 5;
  o.frames = 3;
  o.metres_per_texel = 0.008;
  return o;
}

TEST(TumWriter, WritesTheTumLayoutWithMasksAndGroundTruth) {
  const fs::path dir = freshDir("layout");
  const SequenceSummary s = renderSequence(options(), dir.string());
  EXPECT_EQ(s.frames, 3);
  const SequenceGenerator gen(options());
  for (const char* index : {"rgb.txt", "depth.txt", "masks.txt"}) {
    const auto r = rows(dir / index);
    ASSERT_EQ(r.size(), 3u) << index;
    for (std::size_t k = 0; k < r.size(); ++k) {
      EXPECT_EQ(r[k][0], formatTimestamp(gen.timestamp(static_cast<int>(k))));
      EXPECT_TRUE(fs::exists(dir / r[k][1])) << r[k][1];
    }
  }
  const auto gt = rows(dir / "groundtruth.txt");
  const auto assoc = rows(dir / "associations.txt");
  ASSERT_EQ(gt.size(), 3u);
  ASSERT_EQ(assoc.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    const SyntheticFrame f = gen.render(k);
    const auto& g = gt[static_cast<std::size_t>(k)];
    ASSERT_EQ(g.size(), 8u);
    const Eigen::Quaterniond q(std::stod(g[7]), std::stod(g[4]), std::stod(g[5]), std::stod(g[6]));
    const core::SE3 T = core::makeSE3(q, Eigen::Vector3d(std::stod(g[1]), std::stod(g[2]), std::stod(g[3])));
    EXPECT_LT(core::translationNorm(T.inverse() * f.T_wc), 2e-6);
    EXPECT_LT(core::rotationAngle(T.inverse() * f.T_wc), 1e-7);
    const cv::Mat depth =
        cv::imread((dir / rows(dir / "depth.txt")[static_cast<std::size_t>(k)][1]).string(), cv::IMREAD_UNCHANGED);
    const cv::Mat mask =
        cv::imread((dir / rows(dir / "masks.txt")[static_cast<std::size_t>(k)][1]).string(), cv::IMREAD_UNCHANGED);
    const cv::Mat rgb =
        cv::imread((dir / rows(dir / "rgb.txt")[static_cast<std::size_t>(k)][1]).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(depth.type(), CV_16UC1);
    ASSERT_EQ(mask.type(), CV_16UC1);
    ASSERT_EQ(rgb.type(), CV_8UC3);
    EXPECT_EQ(cv::norm(depth, f.depth_raw, cv::NORM_INF), 0);
    EXPECT_EQ(cv::norm(mask, f.mask, cv::NORM_INF), 0);
    EXPECT_EQ(cv::norm(rgb, f.bgr, cv::NORM_INF), 0);
  }
  const nlohmann::json j = nlohmann::json::parse(readAll(dir / "instances.json"));
  EXPECT_EQ(j["instances"]["1"]["class"], "person");
  EXPECT_EQ(j["instances"]["1"]["name"], "walker_across");
  EXPECT_EQ(j["instances"]["2"]["class"], "person");
  EXPECT_EQ(j["sequence"]["static_counterpart"], "static_xyz");
  EXPECT_EQ(j["sequence"]["frames"], 3);
}

TEST(TumWriter, SameOptionsGiveByteIdenticalFiles) {
  const fs::path a = freshDir("same_a"), b = freshDir("same_b");
  renderSequence(options(), a.string());
  renderSequence(options(), b.string());
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(a)) {
    if (!entry.is_regular_file()) continue;
    const fs::path other = b / fs::relative(entry.path(), a);
    ASSERT_TRUE(fs::exists(other)) << other;
    EXPECT_EQ(readAll(entry.path()), readAll(other)) << entry.path();
    ++files;
  }
  EXPECT_EQ(files, 3 * 3 + 8);  // 3 frames x (rgb, depth, mask) + 6 index files + static_surface.ply, swept_volume.ply
}

TEST(TumWriter, UnwritableOutputIsAnError) {
  EXPECT_THROW(renderSequence(options(), "/proc/amos_synth_cannot_write_here"), core::Error);
}

}  // namespace
}  // namespace amos::synth
