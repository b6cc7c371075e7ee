#include "amos/synth/contact_sheet.h"

#include <fmt/format.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "amos/core/error.h"

namespace amos::synth {

void ContactSheetOptions::check() const {
  core::require(columns >= 1 && columns <= 32, "contact sheet: columns must be in [1, 32]");
  core::require(tile_width >= 64 && tile_width <= 1280, "contact sheet: tile_width must be in [64, 1280]");
}

cv::Scalar instanceColour(std::uint16_t id) {
  static const cv::Scalar palette[] = {cv::Scalar(0, 0, 255),   cv::Scalar(0, 255, 0),   cv::Scalar(255, 0, 0),
                                       cv::Scalar(0, 255, 255), cv::Scalar(255, 0, 255), cv::Scalar(255, 255, 0),
                                       cv::Scalar(0, 128, 255), cv::Scalar(255, 128, 0)};
  return id == 0 ? cv::Scalar(0, 0, 0) : palette[(id - 1) % 8];
}

namespace {
void label(cv::Mat& tile, const std::string& text, int row) {
  const cv::Point org(6, 18 + 20 * row);
  cv::putText(tile, text, org, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
  cv::putText(tile, text, org, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
}
}  // namespace

cv::Mat contactSheet(const SequenceGenerator& generator, const ContactSheetOptions& options) {
  options.check();
  const core::CameraIntrinsics& k = generator.intrinsics();
  const int tw = options.tile_width, th = tw * k.height / k.width;
  const int n = std::min(options.columns, generator.frameCount());
  const int header = 30;
  cv::Mat sheet(header + 3 * th, n * tw, CV_8UC3, cv::Scalar(40, 40, 40));
  std::string legend =
      fmt::format("{}  seed {}  {} frames  camera {}", generator.preset().name, generator.options().seed,
                  generator.frameCount(), toString(generator.preset().motion));
  for (const InstanceInfo& info : generator.instances())
    legend += fmt::format("  [{}] {} ({})", info.id, info.name, info.category);
  cv::putText(sheet, legend, cv::Point(8, 20), cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(255, 255, 255), 1,
              cv::LINE_AA);
  for (int c = 0; c < n; ++c) {
    const int index = n == 1 ? 0 : static_cast<int>(static_cast<long>(c) * (generator.frameCount() - 1) / (n - 1));
    const SyntheticFrame f = generator.render(index);
    cv::Mat colour, depth_vis, overlay;
    cv::resize(f.bgr, colour, cv::Size(tw, th), 0, 0, cv::INTER_AREA);
    cv::Mat depth8;
    f.depth.convertTo(depth8, CV_8U, 255.0 / 5.0);
    cv::applyColorMap(depth8, depth_vis, cv::COLORMAP_TURBO);
    depth_vis.setTo(cv::Scalar(0, 0, 0), f.depth_raw == 0);
    cv::resize(depth_vis, depth_vis, cv::Size(tw, th), 0, 0, cv::INTER_NEAREST);
    overlay = f.bgr * 0.45;
    for (const InstanceInfo& info : generator.instances()) {
      const cv::Mat m = f.mask == info.id;
      if (cv::countNonZero(m) == 0) continue;
      cv::Mat tint(overlay.size(), CV_8UC3, instanceColour(info.id));
      cv::Mat blended;
      cv::addWeighted(f.bgr, 0.4, tint, 0.6, 0, blended);
      blended.copyTo(overlay, m);
    }
    cv::resize(overlay, overlay, cv::Size(tw, th), 0, 0, cv::INTER_NEAREST);
    label(colour, fmt::format("frame {}  t={:.2f}s", index, index / generator.options().sensor.fps), 0);
    label(depth_vis, "depth 0-5 m", 0);
    std::string moving = "moving:";
    for (std::uint16_t id : f.moving) moving += fmt::format(" {}", id);
    label(overlay, f.moving.empty() ? "masks (nothing moving)" : "masks, " + moving, 0);
    colour.copyTo(sheet(cv::Rect(c * tw, header, tw, th)));
    depth_vis.copyTo(sheet(cv::Rect(c * tw, header + th, tw, th)));
    overlay.copyTo(sheet(cv::Rect(c * tw, header + 2 * th, tw, th)));
  }
  return sheet;
}

}  // namespace amos::synth
