#include "amos/synth/texture_painting.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "amos/synth/procedural_textures.h"

namespace amos::synth::textures {

// Public (declared in procedural_textures.h), but defined here because every painting helper picks colours with it.
cv::Scalar randomColour(Random& rng, double sat_lo, double sat_hi, double val_lo, double val_hi) {
  cv::Mat hsv(1, 1, CV_8UC3,
              cv::Scalar(rng.uniformInt(0, 179), rng.uniform(sat_lo, sat_hi) * 255, rng.uniform(val_lo, val_hi) * 255));
  cv::Mat bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
  return cv::Scalar(c[0], c[1], c[2]);
}

namespace paint {

int px(double metres, double metres_per_texel) {
  return std::max(1, static_cast<int>(std::lround(metres / metres_per_texel)));
}

cv::Mat smoothField(cv::Size size, double cell_x, double cell_y, Random& rng) {
  const int gw = std::max(2, static_cast<int>(std::ceil(size.width / cell_x)) + 1);
  const int gh = std::max(2, static_cast<int>(std::ceil(size.height / cell_y)) + 1);
  cv::Mat grid(gh, gw, CV_32F);
  for (int y = 0; y < gh; ++y)
    for (int x = 0; x < gw; ++x) grid.at<float>(y, x) = static_cast<float>(rng.uniform(-1, 1));
  cv::Mat out;
  cv::resize(grid, out, size, 0, 0, cv::INTER_CUBIC);
  return out;
}

void shade(cv::Mat& img, const cv::Mat& field, double amplitude) {
  for (int y = 0; y < img.rows; ++y) {
    cv::Vec3b* row = img.ptr<cv::Vec3b>(y);
    const float* f = field.ptr<float>(y);
    for (int x = 0; x < img.cols; ++x) {
      const double g = 1 + amplitude * f[x];
      for (int c = 0; c < 3; ++c) row[x][c] = cv::saturate_cast<uchar>(row[x][c] * g);
    }
  }
}

void grain(cv::Mat& img, int amplitude, Random& rng) {
  const int span = 2 * amplitude + 1;
  for (int y = 0; y < img.rows; ++y) {
    cv::Vec3b* row = img.ptr<cv::Vec3b>(y);
    for (int x = 0; x < img.cols; ++x) {
      const int n = static_cast<int>((rng.bits() >> 16) * static_cast<std::uint32_t>(span) >> 16) - amplitude;
      for (int c = 0; c < 3; ++c) row[x][c] = cv::saturate_cast<uchar>(row[x][c] + n);
    }
  }
}

cv::Scalar scaleColour(const cv::Scalar& c, double k) { return cv::Scalar(c[0] * k, c[1] * k, c[2] * k); }

cv::Scalar jitter(const cv::Scalar& c, double amount, Random& rng) {
  const double k = 1 + rng.uniform(-amount, amount);
  return cv::Scalar(std::clamp(c[0] * k + rng.uniform(-8, 8), 0.0, 255.0),
                    std::clamp(c[1] * k + rng.uniform(-8, 8), 0.0, 255.0),
                    std::clamp(c[2] * k + rng.uniform(-8, 8), 0.0, 255.0));
}

cv::Scalar inkFor(const cv::Scalar& bg, Random& rng) {
  const double lum = 0.114 * bg[0] + 0.587 * bg[1] + 0.299 * bg[2];
  if (lum > 128) return rng.chance(0.7) ? cv::Scalar(25, 25, 30) : randomColour(rng, 0.6, 1.0, 0.25, 0.5);
  return rng.chance(0.7) ? cv::Scalar(240, 240, 240) : randomColour(rng, 0.3, 0.7, 0.85, 1.0);
}

std::string randomWord(Random& rng, int lo, int hi, bool digits) {
  static const char* letters = "ABCDEFGHIJKLMNOPRSTUVWXYZ";
  static const char* numbers = "0123456789";
  std::string w;
  const int n = rng.uniformInt(lo, hi);
  for (int i = 0; i < n; ++i)
    w += digits && rng.chance(0.5) ? numbers[rng.uniformInt(0, 9)] : letters[rng.uniformInt(0, 24)];
  return w;
}

void putTextFit(cv::Mat& img, const std::string& text, const cv::Rect& box, const cv::Scalar& colour, int font,
                int thickness_hint) {
  if (box.height < 3 || box.width < 3 || text.empty()) return;
  int base = 0;
  const cv::Size unit = cv::getTextSize(text, font, 1.0, 1, &base);
  double scale = std::min(box.height / static_cast<double>(unit.height + base),
                          box.width / static_cast<double>(std::max(1, unit.width)));
  if (scale < 0.15) return;
  const int thickness = thickness_hint > 0 ? thickness_hint : std::max(1, static_cast<int>(scale * 1.6));
  const cv::Size sz = cv::getTextSize(text, font, scale, thickness, &base);
  const cv::Point org(box.x + (box.width - sz.width) / 2, box.y + (box.height + sz.height) / 2 - base / 2);
  cv::putText(img, text, org, font, scale, colour, thickness, cv::LINE_AA);
}

void textBlock(cv::Mat& img, const cv::Rect& area, double line_px, const cv::Scalar& colour, Random& rng) {
  if (line_px < 4) return;
  const double scale = line_px / 30.0;
  const int thickness = std::max(1, static_cast<int>(std::lround(scale * 1.5)));
  for (double y = area.y + line_px; y <= area.y + area.height; y += line_px * 1.5) {
    double x = area.x;
    const double end = area.x + area.width * rng.uniform(0.6, 1.0);
    while (true) {
      const std::string w = randomWord(rng, 2, 8, rng.chance(0.2));
      int base = 0;
      const cv::Size sz = cv::getTextSize(w, cv::FONT_HERSHEY_SIMPLEX, scale, thickness, &base);
      if (x + sz.width > end) break;
      cv::putText(img, w, cv::Point(static_cast<int>(x), static_cast<int>(y)), cv::FONT_HERSHEY_SIMPLEX, scale, colour,
                  thickness, cv::LINE_AA);
      x += sz.width + line_px * 0.5;
    }
  }
}

void barcode(cv::Mat& img, const cv::Rect& area, Random& rng) {
  cv::rectangle(img, area, cv::Scalar(245, 245, 245), cv::FILLED);
  int x = area.x + 2;
  while (x < area.x + area.width - 2) {
    const int w = rng.uniformInt(1, 3);
    if (rng.chance(0.55))
      cv::rectangle(img, cv::Rect(x, area.y + 2, w, area.height - 4), cv::Scalar(20, 20, 20), cv::FILLED);
    x += w;
  }
}

void shapes(cv::Mat& img, const cv::Rect& area, int count, Random& rng) {
  for (int i = 0; i < count; ++i) {
    const cv::Scalar c = randomColour(rng, 0.3, 1.0, 0.2, 1.0);
    const int s = std::max(3, static_cast<int>(std::min(area.width, area.height) * rng.uniform(0.08, 0.4)));
    const cv::Point p(area.x + rng.uniformInt(0, std::max(0, area.width - s)),
                      area.y + rng.uniformInt(0, std::max(0, area.height - s)));
    switch (rng.uniformInt(0, 3)) {
      case 0:
        cv::rectangle(img, cv::Rect(p.x, p.y, s, static_cast<int>(s * rng.uniform(0.4, 1.0))), c, cv::FILLED);
        break;
      case 1:
        cv::circle(img, p + cv::Point(s / 2, s / 2), s / 2, c, cv::FILLED, cv::LINE_AA);
        break;
      case 2: {
        std::vector<cv::Point> tri = {p + cv::Point(s / 2, 0), p + cv::Point(s, s), p + cv::Point(0, s)};
        cv::fillConvexPoly(img, tri, c, cv::LINE_AA);
        break;
      }
      default:
        cv::rectangle(img, cv::Rect(p.x, p.y, s, s), c, std::max(1, s / 8));
    }
  }
}

void pastePhoto(cv::Mat& img, const cv::Rect& area, const cv::Mat& photo) {
  if (area.width < 2 || area.height < 2) return;
  // Centre crop to the area's aspect ratio, then resize.
  const double aspect = area.width / static_cast<double>(area.height);
  cv::Rect crop(0, 0, photo.cols, photo.rows);
  if (photo.cols / static_cast<double>(photo.rows) > aspect) {
    crop.width = std::max(1, static_cast<int>(photo.rows * aspect));
    crop.x = (photo.cols - crop.width) / 2;
  } else {
    crop.height = std::max(1, static_cast<int>(photo.cols / aspect));
    crop.y = (photo.rows - crop.height) / 2;
  }
  cv::Mat resized;
  cv::resize(photo(crop), resized, area.size(), 0, 0, cv::INTER_AREA);
  resized.copyTo(img(area));
}

void drawPosterInto(cv::Mat& img, const cv::Rect& area, Random& rng, const cv::Mat& photo) {
  const cv::Scalar bg = randomColour(rng, 0.0, 0.9, 0.3, 1.0);
  cv::rectangle(img, area, bg, cv::FILLED);
  const cv::Scalar ink = inkFor(bg, rng);
  const int m = std::max(2, area.width / 14);
  const cv::Rect title(area.x + m, area.y + m, area.width - 2 * m, std::max(3, area.height / 8));
  putTextFit(img, randomWord(rng, 4, 9), title, ink,
             rng.chance(0.5) ? cv::FONT_HERSHEY_DUPLEX : cv::FONT_HERSHEY_TRIPLEX);
  const cv::Rect middle(area.x + m, title.y + title.height + m, area.width - 2 * m, area.height * 11 / 20);
  if (!photo.empty()) {
    pastePhoto(img, middle, photo);
  } else if (rng.chance(0.3)) {
    // A bar chart with axes and labels.
    cv::rectangle(img, middle, cv::Scalar(250, 250, 250), cv::FILLED);
    const int bars = rng.uniformInt(4, 8);
    const int bw = middle.width / (bars * 2 + 1);
    for (int i = 0; i < bars; ++i) {
      const int h = static_cast<int>(middle.height * rng.uniform(0.2, 0.9));
      cv::rectangle(img, cv::Rect(middle.x + bw * (2 * i + 1), middle.y + middle.height - h, bw, h),
                    randomColour(rng, 0.5, 1.0, 0.4, 0.9), cv::FILLED);
    }
    cv::line(img, middle.tl(), cv::Point(middle.x, middle.y + middle.height), cv::Scalar(0, 0, 0), 2);
    cv::line(img, cv::Point(middle.x, middle.y + middle.height - 1), middle.br() - cv::Point(0, 1), cv::Scalar(0, 0, 0),
             2);
  } else {
    shapes(img, middle, rng.uniformInt(6, 14), rng);
  }
  const int text_top = middle.y + middle.height + m;
  textBlock(img, cv::Rect(area.x + m, text_top, area.width - 2 * m, area.y + area.height - m - text_top),
            std::max(4.0, area.height / 30.0), ink, rng);
}

}  // namespace paint
}  // namespace amos::synth::textures
