#pragma once
// report.html among the node's outputs: the viewer module's page (viewer/report_html.h), as `amos-slam run` writes
// it, of the frames the node tracked, recorded from amos::Slam's FrameResult (the node is a client of the public
// API: no run::FrameSnapshot). Built with the viewer module (AMOS_BUILD_VIEWER); without it the node writes no
// report.html. What the node's page lacks beside run's: the keypoints on the mask overlays (FrameResult has their
// counts, not their places), the evaluation (the node has no ground truth) and the map points removed as dynamic.
#include <chrono>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "amos/slam.h"
#include "amos/viewer/report_recorder.h"

namespace amos::node {

class NodeReport {
 public:
  NodeReport(std::string settings_file, std::string mode, std::string sequence);
  // A tracked frame and its colour image (the tracking thread).
  void add(const FrameResult& result, const cv::Mat& bgr);
  // Writes <dir>/report.html from the frames so far, `trajectory` and <dir>/stats.json (written before). Any
  // thread; throws core::Error naming the file.
  void write(const std::filesystem::path& dir, const std::vector<StampedPose>& trajectory);

 private:
  std::string settings_file_, mode_, sequence_;
  std::mutex mutex_;
  viewer::ReportRecorder recorder_;  // guarded by mutex_
  std::optional<std::chrono::steady_clock::time_point> last_done_;  // guarded by mutex_
};

}  // namespace amos::node
