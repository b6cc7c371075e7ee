#include "node_report.h"

#include <chrono>

#include "amos/core/error.h"
#include "amos/viewer/report_html.h"
#include "amos/core/whole_file.h"

namespace amos::node {
namespace {

std::string fileText(const std::filesystem::path& path) {
  std::string text = core::readWholeFile(path).value_or(std::string());
  core::require(!text.empty(), "report.html: cannot read " + path.string());
  return text;
}

}  // namespace

NodeReport::NodeReport(std::string settings_file, std::string mode, std::string sequence)
    : settings_file_(std::move(settings_file)), mode_(std::move(mode)), sequence_(std::move(sequence)) {
  run::RunStart start;  // a live source: no frame count, no map to watch, no ground truth
  start.sequence = sequence_;
  start.mode = mode_;
  recorder_.onStart(start);
}

void NodeReport::add(const FrameResult& result, const cv::Mat& bgr) {
  viewer::ReportFrame frame;
  frame.index = result.frame;
  frame.timestamp = result.timestamp;
  frame.state = toString(result.state);
  frame.extract_ms = result.extract_ms;
  frame.build_ms = result.build_ms;
  frame.track_ms = result.track_ms;
  frame.keypoints = result.keypoints;
  frame.removed = result.keypoints_removed;
  const auto now = std::chrono::steady_clock::now();
  std::lock_guard lock(mutex_);
  // As run's: the wall time since the frame before was done (1000 / the instantaneous rate).
  if (last_done_) frame.frame_ms = std::chrono::duration<double, std::milli>(now - *last_done_).count();
  last_done_ = now;
  recorder_.addFrame(std::move(frame), bgr, result.dynamic_mask, {});
}

void NodeReport::write(const std::filesystem::path& dir, const std::vector<StampedPose>& trajectory) {
  std::vector<io::StampedPose> poses;
  poses.reserve(trajectory.size());
  for (const StampedPose& p : trajectory) poses.push_back({p.timestamp, core::SE3(p.T_wc)});
  viewer::ReportInputs inputs;
  inputs.stats = nlohmann::json::parse(fileText(dir / "stats.json"));
  inputs.settings_file = settings_file_;
  inputs.settings_text = fileText(settings_file_);
  inputs.run_options = {{"mode", mode_}, {"source", "ros"}, {"sequence", sequence_}};
  std::lock_guard lock(mutex_);
  recorder_.onEnd(poses, report::RunInfo{});
  viewer::writeReportHtml(dir, recorder_, inputs);
}

}  // namespace amos::node
