#include "amos/viewer/report_html.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "amos/eval/evaluate.h"
#include "amos/report/run_report.h"
#include "amos/testing/scratch_dir.h"
#include "amos/viewer/base64.h"
#include "amos/viewer/test_run_folder.h"

namespace amos::viewer {
namespace {

std::vector<io::StampedPose> line(int n, double dx) {
  std::vector<io::StampedPose> poses;
  for (int i = 0; i < n; ++i) {
    io::StampedPose p;
    p.timestamp = 1.0 + 0.1 * i;
    p.T_wc.translation() = Eigen::Vector3d(dx * i, 0.01 * std::sin(i), 0.02 * i);
    poses.push_back(p);
  }
  return poses;
}

// The JSON block of the page, as a reader would take it out.
nlohmann::json dataOf(const std::string& html) {
  const std::string open = "<script id=\"amos-report-data\" type=\"application/json\">";
  const std::size_t begin = html.find(open);
  EXPECT_NE(begin, std::string::npos);
  const std::size_t end = html.find("</script>", begin);
  return nlohmann::json::parse(html.substr(begin + open.size(), end - begin - open.size()));
}

TEST(ReportHtml, HoldsTheRunAsParsableJsonAndNeedsNoNetwork) {
  ReportRecorder recorder(2);
  run::RunStart start;
  start.total_frames = 30;
  recorder.onStart(start);
  for (std::size_t i = 0; i < 30; ++i) {
    run::FrameSnapshot f;
    f.index = i;
    f.timestamp = 1.0 + 0.1 * i;
    f.bgr = cv::Mat(48, 64, CV_8UC3, cv::Scalar(40, 90, 160));
    f.dynamic_mask = cv::Mat::zeros(48, 64, CV_8U);
    f.dynamic_mask(cv::Rect(0, 0, 20, 20)).setTo(255);
    f.keypoints = {{5, 5}, {40, 30}, {50, 40}, {10, 12}};
    f.keypoints_removed = 2;
    f.extract_ms = 5;
    f.frame_ms = 30;
    recorder.onFrame(f);
  }
  report::RunInfo info;
  info.evaluation = eval::evaluate(line(30, 0.05), line(30, 0.051));
  recorder.onEnd(line(30, 0.051), info);
  ReportInputs inputs;
  inputs.stats = {{"frames", 30}, {"mode", "full"}};
  inputs.settings_file = "configs/x.yaml";
  inputs.settings_text = "Camera.fx: 500\n# a comment with </script> in it\n";
  inputs.run_options = {{"mode", "full"}};
  const std::string html = reportHtml(reportData(recorder, inputs));

  EXPECT_EQ(html.find("__AMOS_REPORT_DATA__"), std::string::npos);
  // Nothing loads from elsewhere: no external script, style sheet or resource.
  for (const char* external : {"<script src", "<link", "src=\"http", "href=\"http", "url(http", "fetch("})
    EXPECT_EQ(html.find(external), std::string::npos) << external;
  const nlohmann::json d = dataOf(html);
  EXPECT_EQ(d["frames"]["index"].size(), 30u);
  EXPECT_DOUBLE_EQ(d["frames"]["removed_fraction"][0].get<double>(), 0.5);
  EXPECT_EQ(d["trajectory"].size(), 30u);
  EXPECT_EQ(d["ground_truth"].size(), 30u);
  EXPECT_EQ(d["ate"]["error_m"].size(), 30u);
  EXPECT_FALSE(d["rpe"]["t"].empty());
  EXPECT_EQ(d["steps"]["est_m"].size(), 29u);  // frame-to-frame steps (eval/jitter.h)
  EXPECT_NEAR(d["steps"]["gt_m"][0].get<double>(), std::hypot(0.05, 0.01 * std::sin(1.0), 0.02), 1e-12);
  EXPECT_TRUE(d["evaluation"]["jitter"].contains("rpe1_trans_rmse_m"));
  EXPECT_EQ(d["settings"]["text"], inputs.settings_text);
  ASSERT_EQ(d["overlays"].size(), 2u);
  // The embedded overlay is a JPEG of the frame's size.
  const std::string b64 = d["overlays"][0]["jpeg"];
  EXPECT_GT(b64.size(), 100u);
}

// What `amos-slam view` needs of report.html: the ground truth in the map's frame (the estimate's), where the
// evaluation's alignment takes the estimate onto it.
TEST(ReportHtml, KeepsTheGroundTruthInTheMapFrameForTheView) {
  ReportRecorder recorder(0);
  run::RunStart start;
  std::vector<io::StampedPose> truth = line(20, 0.05);
  for (io::StampedPose& p : truth) p.T_wc.translation() += Eigen::Vector3d(3, -1, 2);  // another origin
  start.ground_truth = truth;
  recorder.onStart(start);
  report::RunInfo info;
  info.evaluation = eval::evaluate(truth, line(20, 0.05));
  recorder.onEnd(line(20, 0.05), info);
  const nlohmann::json d = reportData(recorder, {});
  ASSERT_EQ(d["view"]["ground_truth"].size(), 20u);
  // In the map's frame the ground truth lies on the estimate: pose 10 at (0.5, 0.01 sin 10, 0.2).
  EXPECT_NEAR(d["view"]["ground_truth"][10][1].get<double>(), 0.5, 2e-3);
  EXPECT_NEAR(d["view"]["ground_truth"][10][3].get<double>(), 0.2, 2e-3);
  ReportRecorder without_truth(0);
  without_truth.onEnd(line(20, 0.05), report::RunInfo{});
  EXPECT_TRUE(reportData(without_truth, {})["view"].empty());
}

TEST(ReportHtml, ShowsTheOccupancyGridOnlyWhenTheRunLeftOne) {
  const std::filesystem::path dir = amos::testing::scratchDirForThisTest("viewer_report_");
  nlohmann::json without = {{"stats", nlohmann::json::object()}};
  addDenseProducts(dir, without);
  EXPECT_FALSE(without.contains("occupancy"));
  EXPECT_TRUE(without["dense_files"].empty());

  test::writeOccupancy(dir, 30, 20, 0.05);
  test::writeBinaryPly(dir / "mesh.ply", test::floorAndWall(0, 1, 0, 1, 0), true);
  nlohmann::json with = {{"stats", nlohmann::json::object()}};
  addDenseProducts(dir, with);
  ASSERT_TRUE(with["occupancy"].is_object());
  EXPECT_EQ(with["occupancy"]["width"], 30);
  EXPECT_DOUBLE_EQ(with["occupancy"]["resolution"].get<double>(), 0.05);
  EXPECT_EQ(with["dense_files"].size(), 3u);  // mesh.ply, occupancy.pgm, occupancy.yaml
  // The image decodes to the grid.
  const std::string b64 = with["occupancy"]["png"];
  EXPECT_FALSE(b64.empty());
  const std::string html = reportHtml(with);
  EXPECT_NE(html.find("id=\"occupancy-section\""), std::string::npos);

  // A grid that cannot be read: said in the report, not fatal.
  test::writeText(dir / "occupancy.yaml", "image: gone.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n");
  nlohmann::json broken = {{"stats", nlohmann::json::object()}};
  addDenseProducts(dir, broken);
  EXPECT_NE(broken["occupancy"]["error"].get<std::string>().find("gone.pgm"), std::string::npos);
}

TEST(Base64, EncodesAsRfc4648) {
  auto enc = [](const std::string& s) { return base64Encode(std::vector<unsigned char>(s.begin(), s.end())); };
  EXPECT_EQ(enc(""), "");
  EXPECT_EQ(enc("f"), "Zg==");
  EXPECT_EQ(enc("fo"), "Zm8=");
  EXPECT_EQ(enc("foo"), "Zm9v");
  EXPECT_EQ(enc("foobar"), "Zm9vYmFy");
}

}  // namespace
}  // namespace amos::viewer
