#include "amos/synth/image_assets.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "amos/core/error.h"
#include "amos/io/image_codecs.h"

namespace amos::synth {

namespace fs = std::filesystem;

std::vector<PersonCutout> extractCutouts(const cv::Mat& bgr, const cv::Mat& mask, const std::string& source) {
  core::require(bgr.type() == CV_8UC3 && mask.type() == CV_8UC1 && bgr.size() == mask.size(),
                "person cut-out " + source + ": needs an 8-bit colour image and an 8-bit mask of the same size");
  cv::Mat binary = mask > 127;
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(binary, labels, stats, centroids, 8, CV_32S);
  std::vector<PersonCutout> out;
  const double min_area = 0.015 * bgr.total();
  for (int i = 1; i < n; ++i) {
    const cv::Rect box(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                       stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT));
    if (stats.at<int>(i, cv::CC_STAT_AREA) < min_area) continue;
    const bool left = box.x <= 1, right = box.x + box.width >= bgr.cols - 1, top = box.y <= 1;
    const bool bottom = box.y + box.height >= bgr.rows - 1;
    if (left || right || top) continue;  // half a person
    PersonCutout c;
    c.source = source;
    const cv::Rect crop =
        cv::Rect(box.x - 2, box.y - 2, box.width + 4, box.height + 4) & cv::Rect(0, 0, bgr.cols, bgr.rows);
    c.bgr = bgr(crop).clone();
    c.alpha = cv::Mat(labels(crop) == i);
    // Masks bleed onto the background by a pixel or two; trim them.
    cv::erode(c.alpha, c.alpha, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(5, 5)));
    // Seated people are squat (about 1.9 times as tall as wide with the legs bent) and may have their feet cut
    // by the bottom border; a standing person cut there is taller than that and needs legs.
    const double tall = box.height / static_cast<double>(box.width);
    if (tall < 2.1) {
      c.kind = PersonCutout::Kind::kSitting;
      c.visible_fraction = 1.0;
    } else if (bottom) {
      c.kind = PersonCutout::Kind::kUpperBody;
      // A standing person with arms down is about 0.33 times as wide as tall.
      c.visible_fraction = std::clamp(box.height / (box.width / 0.33), 0.4, 0.95);
    } else {
      c.kind = PersonCutout::Kind::kStanding;
      c.visible_fraction = 1.0;
    }
    const int band = std::max(2, c.bgr.rows / 8);
    const cv::Rect lower(0, c.bgr.rows - band, c.bgr.cols, band);
    c.lower_colour = cv::mean(c.bgr(lower), c.alpha(lower));
    if (c.bgr.rows > 512) {  // bound texture memory
      const double f = 512.0 / c.bgr.rows;
      cv::resize(c.bgr, c.bgr, cv::Size(), f, f, cv::INTER_AREA);
      cv::resize(c.alpha, c.alpha, c.bgr.size(), 0, 0, cv::INTER_LINEAR);
    }
    out.push_back(c);
  }
  return out;
}

std::vector<PersonCutout> loadPersonCutouts(const std::string& dir) {
  const fs::path rgb_dir = fs::path(dir) / "rgb", mask_dir = fs::path(dir) / "mask";
  core::require(fs::is_directory(rgb_dir) && fs::is_directory(mask_dir),
                "person cut-outs: " + dir + " must contain rgb/ and mask/ folders with matching file names");
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(rgb_dir))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::vector<PersonCutout> out;
  for (const fs::path& f : files) {
    const fs::path m = mask_dir / f.filename();
    if (!fs::exists(m)) {
      spdlog::warn("person cut-outs: no mask {} for {}, skipped", m.string(), f.string());
      continue;
    }
    const cv::Mat bgr = io::readImage(f.string(), io::kReadColor);
    const cv::Mat mask = io::readImage(m.string(), io::kReadGrayscale);
    if (bgr.empty() || mask.empty() || bgr.size() != mask.size()) {
      spdlog::warn("person cut-outs: cannot use {} / {}, skipped", f.string(), m.string());
      continue;
    }
    for (PersonCutout& c : extractCutouts(bgr, mask, f.string())) out.push_back(std::move(c));
  }
  core::require(!out.empty(), "person cut-outs: no whole (not border-cut) person found in " + dir);
  return out;
}

std::vector<cv::Mat> loadPhotos(const std::string& dir, std::size_t max_count) {
  core::require(fs::is_directory(dir), "photos: " + dir + " is not a folder");
  std::vector<fs::path> files;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it) {
    const std::string name = it->path().filename().string();
    if (it->is_directory() && (name == "depth" || name == "mask" || name == "masks")) {
      it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file()) continue;
    std::string ext = it->path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") files.push_back(it->path());
  }
  std::sort(files.begin(), files.end());
  std::vector<cv::Mat> photos;
  if (!files.empty() && max_count > 0) {
    const std::size_t step = std::max<std::size_t>(1, files.size() / max_count);
    for (std::size_t i = 0; i < files.size() && photos.size() < max_count; i += step) {
      const cv::Mat raw = io::readImage(files[i].string(), io::kReadUnchanged);
      if (raw.empty() || raw.depth() != CV_8U || raw.channels() < 3) continue;
      cv::Mat bgr;
      if (raw.channels() == 4)
        cv::cvtColor(raw, bgr, cv::COLOR_BGRA2BGR);
      else
        bgr = raw;
      if (bgr.cols > 640) cv::resize(bgr, bgr, cv::Size(), 640.0 / bgr.cols, 640.0 / bgr.cols, cv::INTER_AREA);
      photos.push_back(bgr.clone());
    }
  }
  core::require(!photos.empty(), "photos: no 8-bit colour .png/.jpg image found under " + dir);
  return photos;
}

}  // namespace amos::synth
