#include "amos/report/mask_outputs.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "amos/core/error.h"
#include "amos/io/atomic_file.h"

namespace amos::report {

namespace fs = std::filesystem;

std::vector<std::size_t> evenlySpacedFrames(std::size_t total, std::size_t count) {
  std::vector<std::size_t> frames;
  if (total == 0 || count == 0) return frames;
  if (total <= count) {
    for (std::size_t i = 0; i < total; ++i) frames.push_back(i);
    return frames;
  }
  for (std::size_t i = 0; i < count; ++i) frames.push_back((2 * i + 1) * total / (2 * count));
  return frames;
}

namespace {

void outline(cv::Mat& image, const cv::Mat& mask, const cv::Scalar& colour) {
  if (mask.empty()) return;
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask != 0, contours, cv::RETR_LIST, cv::CHAIN_APPROX_SIMPLE);
  cv::drawContours(image, contours, -1, colour, 2, cv::LINE_8);
}

void label(cv::Mat& image, const std::string& text, cv::Point at, const cv::Scalar& colour) {
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.45, colour, 1, cv::LINE_AA);
}

}  // namespace

cv::Mat renderMaskOverlay(const cv::Mat& bgr, const cv::Mat& dynamic_mask, const cv::Mat& prior_mask,
                          const cv::Mat& truth_mask, const std::string& caption) {
  core::require(!bgr.empty() && bgr.type() == CV_8UC3, "renderMaskOverlay: image must be CV_8UC3");
  for (const cv::Mat* m : {&dynamic_mask, &prior_mask, &truth_mask})
    core::require(m->empty() || (m->size() == bgr.size() && m->channels() == 1),
                  "renderMaskOverlay: masks must be single-channel of the image size");
  const cv::Scalar red(0, 0, 255), yellow(0, 230, 255), green(0, 220, 0);
  cv::Mat out = bgr.clone();
  if (!dynamic_mask.empty()) {
    // Half red over the dynamic pixels: the scene under them stays readable.
    cv::Mat tinted;
    cv::addWeighted(bgr, 0.5, cv::Mat(bgr.size(), CV_8UC3, red), 0.5, 0.0, tinted);
    tinted.copyTo(out, dynamic_mask != 0);
  }
  outline(out, truth_mask, green);
  outline(out, prior_mask, yellow);
  label(out, caption, {8, 18}, cv::Scalar(255, 255, 255));
  int x = 8;
  const int y = out.rows - 10;
  label(out, "dynamic (tint)", {x, y}, red);
  x += 120;
  label(out, "prior (outline)", {x, y}, yellow);
  x += 125;
  if (!truth_mask.empty()) label(out, "true movers (outline)", {x, y}, green);
  return out;
}

std::string frameStem(const std::string& rgb_file) { return fs::path(rgb_file).stem().string(); }

MaskOutputWriter::MaskOutputWriter(const std::string& dir, std::size_t total_frames, std::size_t overlay_count)
    : masks_dir_((fs::path(dir) / "masks").string()),
      overlays_dir_((fs::path(dir) / "overlays").string()),
      overlay_frames_(evenlySpacedFrames(total_frames, overlay_count)) {
  for (const std::string& d : {masks_dir_, overlays_dir_}) {
    std::error_code ec;
    fs::create_directories(d, ec);
    core::require(!ec && fs::is_directory(d), "cannot create " + d + (ec ? ": " + ec.message() : ""));
  }
}

void MaskOutputWriter::add(std::size_t index, const std::string& rgb_file, const cv::Mat& bgr,
                           const cv::Mat& dynamic_mask, const cv::Mat& prior_mask, const cv::Mat& truth_mask) {
  const std::string stem = frameStem(rgb_file);
  cv::Mat mask = dynamic_mask.empty() ? cv::Mat(bgr.size(), CV_8U, cv::Scalar(0)) : cv::Mat(dynamic_mask != 0);
  const std::string mask_path = (fs::path(masks_dir_) / (stem + ".png")).string();
  io::writeImageAtomically(mask_path, mask);
  ++masks_written_;
  if (!std::binary_search(overlay_frames_.begin(), overlay_frames_.end(), index)) return;
  const std::string caption = fmt::format("frame {}  {}  dynamic {:.1f}%", index, stem,
                                          100.0 * cv::countNonZero(mask) / static_cast<double>(mask.total()));
  const std::string overlay_path = (fs::path(overlays_dir_) / (stem + ".png")).string();
  io::writeImageAtomically(overlay_path, renderMaskOverlay(bgr, mask, prior_mask, truth_mask, caption));
  ++overlays_written_;
}

}  // namespace amos::report
