#include "amos/synth/procedural_textures.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

namespace amos::synth::textures {
namespace {

int px(double metres, double metres_per_texel) {
  return std::max(1, static_cast<int>(std::lround(metres / metres_per_texel)));
}

// Smooth random field in about [-1, 1] with features of `cell_px` texels (cubic interpolation of a coarse grid).
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

// img *= 1 + amplitude * field.
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

// Per-texel luminance grain, uniform in [-amplitude, amplitude].
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

// Contrasting ink for a background.
cv::Scalar inkFor(const cv::Scalar& bg, Random& rng) {
  const double lum = 0.114 * bg[0] + 0.587 * bg[1] + 0.299 * bg[2];
  if (lum > 128) return rng.chance(0.7) ? cv::Scalar(25, 25, 30) : randomColour(rng, 0.6, 1.0, 0.25, 0.5);
  return rng.chance(0.7) ? cv::Scalar(240, 240, 240) : randomColour(rng, 0.3, 0.7, 0.85, 1.0);
}

std::string randomWord(Random& rng, int lo, int hi, bool digits = false) {
  static const char* letters = "ABCDEFGHIJKLMNOPRSTUVWXYZ";
  static const char* numbers = "0123456789";
  std::string w;
  const int n = rng.uniformInt(lo, hi);
  for (int i = 0; i < n; ++i)
    w += digits && rng.chance(0.5) ? numbers[rng.uniformInt(0, 9)] : letters[rng.uniformInt(0, 24)];
  return w;
}

// Text scaled to fit `box` (height first, then width).
void putTextFit(cv::Mat& img, const std::string& text, const cv::Rect& box, const cv::Scalar& colour, int font,
                int thickness_hint = 0) {
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

// Lines of random words, left aligned, filling `area`.
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

// Random filled shapes (rectangles, circles, triangles) inside `area`.
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

void drawFrame(cv::Mat& img, const cv::Rect& area, int thickness, const cv::Scalar& colour) {
  cv::rectangle(img, area, colour, thickness);
}

void drawWhiteboard(cv::Mat& img, const cv::Rect& area, Random& rng) {
  cv::rectangle(img, area, cv::Scalar(238, 240, 240), cv::FILLED);
  const int m = std::max(3, area.width / 40);
  // Boxes-and-arrows diagram and handwriting-like text in marker colours.
  const cv::Scalar markers[] = {cv::Scalar(160, 40, 20), cv::Scalar(30, 30, 30), cv::Scalar(40, 40, 190),
                                cv::Scalar(40, 140, 40)};
  std::vector<cv::Rect> boxes;
  for (int i = 0; i < rng.uniformInt(4, 7); ++i) {
    const int w = area.width / rng.uniformInt(5, 8), h = area.height / rng.uniformInt(5, 8);
    const cv::Rect b(area.x + m + rng.uniformInt(0, area.width - w - 2 * m),
                     area.y + m + rng.uniformInt(0, area.height / 2 - h), w, h);
    const cv::Scalar c = markers[rng.uniformInt(0, 3)];
    cv::rectangle(img, b, c, std::max(2, m / 2), cv::LINE_AA);
    putTextFit(img, randomWord(rng, 3, 6), cv::Rect(b.x + 3, b.y + 3, b.width - 6, b.height - 6), c,
               cv::FONT_HERSHEY_SCRIPT_SIMPLEX);
    if (!boxes.empty())
      cv::arrowedLine(img, (boxes.back().tl() + boxes.back().br()) / 2, (b.tl() + b.br()) / 2, c, std::max(2, m / 2),
                      cv::LINE_AA, 0, 0.05);
    boxes.push_back(b);
  }
  textBlock(img, cv::Rect(area.x + m, area.y + area.height / 2 + m, area.width - 2 * m, area.height / 2 - 2 * m),
            std::max(6.0, area.height / 14.0), markers[rng.uniformInt(0, 3)], rng);
  cv::rectangle(img, area, cv::Scalar(190, 190, 195), std::max(3, m), cv::LINE_8);
}

void drawNoticeBoard(cv::Mat& img, const cv::Rect& area, Random& rng) {
  cv::rectangle(img, area, cv::Scalar(70, 120, 170), cv::FILLED);  // cork
  cv::Mat roi = img(area);
  grain(roi, 18, rng);
  for (int i = 0; i < rng.uniformInt(5, 10); ++i) {
    const int w = static_cast<int>(area.width * rng.uniform(0.18, 0.35));
    const int h = static_cast<int>(w * rng.uniform(0.7, 1.4));
    const cv::Rect n(area.x + rng.uniformInt(0, std::max(0, area.width - w)),
                     area.y + rng.uniformInt(0, std::max(0, area.height - h)), w, h);
    const cv::Scalar paper = rng.chance(0.5) ? cv::Scalar(245, 245, 245) : randomColour(rng, 0.3, 0.6, 0.9, 1.0);
    cv::rectangle(img, n, paper, cv::FILLED);
    textBlock(img, cv::Rect(n.x + 3, n.y + 3, n.width - 6, n.height - 6), std::max(4.0, h / 9.0),
              cv::Scalar(30, 30, 30), rng);
    cv::circle(img, cv::Point(n.x + n.width / 2, n.y + 4), std::max(2, w / 20), cv::Scalar(30, 30, 200), cv::FILLED);
  }
  cv::rectangle(img, area, cv::Scalar(40, 60, 90), std::max(3, area.width / 50));
}

void drawWindow(cv::Mat& img, const cv::Rect& area, Random& rng) {
  // Sky gradient, a skyline of buildings with lit windows, then the window frame and mullions.
  for (int y = area.y; y < area.y + area.height; ++y) {
    const double f = (y - area.y) / static_cast<double>(area.height);
    cv::line(img, cv::Point(area.x, y), cv::Point(area.x + area.width - 1, y),
             cv::Scalar(235 - 40 * f, 215 - 30 * f, 190 - 20 * f));
  }
  int x = area.x;
  while (x < area.x + area.width) {
    const int w = static_cast<int>(area.width * rng.uniform(0.08, 0.2));
    const int h = static_cast<int>(area.height * rng.uniform(0.3, 0.8));
    const cv::Rect b(x, area.y + area.height - h, w, h);
    const cv::Scalar c = randomColour(rng, 0.0, 0.3, 0.35, 0.7);
    cv::rectangle(img, b & area, c, cv::FILLED);
    const int cell = std::max(4, w / 6);
    for (int wy = b.y + cell / 2; wy < b.y + b.height - cell; wy += cell)
      for (int wx = b.x + cell / 3; wx < b.x + b.width - cell / 2; wx += cell)
        if (rng.chance(0.7))
          cv::rectangle(img, cv::Rect(wx, wy, cell / 2, cell / 2) & area,
                        rng.chance(0.4) ? cv::Scalar(150, 220, 245) : scaleColour(c, 0.6), cv::FILLED);
    x += w + rng.uniformInt(0, w / 3);
  }
  const int t = std::max(4, area.width / 30);
  cv::rectangle(img, area, cv::Scalar(245, 245, 245), t);
  cv::line(img, cv::Point(area.x + area.width / 2, area.y), cv::Point(area.x + area.width / 2, area.y + area.height),
           cv::Scalar(245, 245, 245), t);
  cv::line(img, cv::Point(area.x, area.y + area.height / 3), cv::Point(area.x + area.width, area.y + area.height / 3),
           cv::Scalar(245, 245, 245), t * 2 / 3);
  cv::rectangle(img, cv::Rect(area.x - t, area.y + area.height, area.width + 2 * t, t * 2), cv::Scalar(225, 225, 225),
                cv::FILLED);  // sill
}

void drawDoorway(cv::Mat& img, const cv::Rect& area, Random& rng) {
  // An open doorway onto a dim corridor: darker walls in perspective, a far door and a poster.
  cv::rectangle(img, area, cv::Scalar(60, 66, 70), cv::FILLED);
  const cv::Rect far(area.x + area.width / 4, area.y + area.height / 5, area.width / 2, area.height * 3 / 5);
  cv::rectangle(img, far, cv::Scalar(95, 105, 110), cv::FILLED);
  cv::rectangle(img, cv::Rect(far.x + far.width / 4, far.y + far.height / 4, far.width / 2, far.height * 3 / 4),
                cv::Scalar(40, 70, 110), cv::FILLED);
  cv::line(img, area.tl(), far.tl(), cv::Scalar(35, 35, 40), 2, cv::LINE_AA);
  cv::line(img, cv::Point(area.x + area.width, area.y), cv::Point(far.x + far.width, far.y), cv::Scalar(35, 35, 40), 2,
           cv::LINE_AA);
  cv::line(img, cv::Point(area.x, area.y + area.height), cv::Point(far.x, far.y + far.height), cv::Scalar(35, 35, 40),
           2, cv::LINE_AA);
  cv::line(img, area.br(), far.br(), cv::Scalar(35, 35, 40), 2, cv::LINE_AA);
  drawPosterInto(img, cv::Rect(area.x + 4, area.y + area.height / 3, area.width / 6, area.height / 5), rng, cv::Mat());
  cv::rectangle(img, area, cv::Scalar(230, 230, 230), std::max(4, area.width / 18));  // frame
}

void drawSocket(cv::Mat& img, const cv::Point& centre, int size) {
  const cv::Rect r(centre.x - size / 2, centre.y - size / 2, size, size);
  cv::rectangle(img, r, cv::Scalar(235, 235, 235), cv::FILLED);
  cv::rectangle(img, r, cv::Scalar(150, 150, 150), 1);
  cv::circle(img, centre - cv::Point(size / 6, 0), std::max(1, size / 12), cv::Scalar(40, 40, 40), cv::FILLED);
  cv::circle(img, centre + cv::Point(size / 6, 0), std::max(1, size / 12), cv::Scalar(40, 40, 40), cv::FILLED);
}

void drawClock(cv::Mat& img, const cv::Point& c, int r, Random& rng) {
  cv::circle(img, c, r, cv::Scalar(250, 250, 250), cv::FILLED, cv::LINE_AA);
  cv::circle(img, c, r, cv::Scalar(30, 30, 30), std::max(2, r / 10), cv::LINE_AA);
  for (int i = 0; i < 12; ++i) {
    const double a = i * M_PI / 6;
    cv::line(img, c + cv::Point(static_cast<int>(0.75 * r * std::cos(a)), static_cast<int>(0.75 * r * std::sin(a))),
             c + cv::Point(static_cast<int>(0.9 * r * std::cos(a)), static_cast<int>(0.9 * r * std::sin(a))),
             cv::Scalar(20, 20, 20), std::max(1, r / 15));
  }
  const double h = rng.uniform(0, 2 * M_PI), m = rng.uniform(0, 2 * M_PI);
  cv::line(img, c, c + cv::Point(static_cast<int>(0.5 * r * std::sin(h)), static_cast<int>(-0.5 * r * std::cos(h))),
           cv::Scalar(20, 20, 20), std::max(2, r / 8), cv::LINE_AA);
  cv::line(img, c, c + cv::Point(static_cast<int>(0.8 * r * std::sin(m)), static_cast<int>(-0.8 * r * std::cos(m))),
           cv::Scalar(20, 20, 20), std::max(1, r / 12), cv::LINE_AA);
}

// Wall base patterns.
void wallPattern(cv::Mat& img, int style, double mpt, Random& rng) {
  const cv::Scalar base = randomColour(rng, 0.05, 0.3, 0.72, 0.9);
  img.setTo(base);
  if (style == 1) {  // painted bricks
    const int bw = px(0.215, mpt), bh = px(0.065, mpt), gap = std::max(1, px(0.01, mpt));
    cv::rectangle(img, cv::Rect(0, 0, img.cols, img.rows), scaleColour(base, 0.75), cv::FILLED);
    for (int row = 0, y = 0; y < img.rows; ++row, y += bh + gap) {
      const int offset = (row % 2) ? -(bw + gap) / 2 : 0;
      for (int x = offset; x < img.cols; x += bw + gap)
        cv::rectangle(img, cv::Rect(x, y, bw, bh), jitter(base, 0.12, rng), cv::FILLED);
    }
  } else if (style == 2) {  // concrete blocks
    const int bw = px(0.39, mpt), bh = px(0.19, mpt), gap = std::max(1, px(0.01, mpt));
    cv::rectangle(img, cv::Rect(0, 0, img.cols, img.rows), scaleColour(base, 0.7), cv::FILLED);
    for (int row = 0, y = 0; y < img.rows; ++row, y += bh + gap) {
      const int offset = (row % 2) ? -(bw + gap) / 2 : 0;
      for (int x = offset; x < img.cols; x += bw + gap) {
        cv::rectangle(img, cv::Rect(x, y, bw, bh), jitter(base, 0.08, rng), cv::FILLED);
        for (int k = 0; k < 6; ++k)
          cv::circle(img, cv::Point(x + rng.uniformInt(0, bw), y + rng.uniformInt(0, bh)), rng.uniformInt(1, 3),
                     scaleColour(base, 0.6), cv::FILLED);
      }
    }
  } else if (style == 3) {  // vertical wood panelling
    const int bw = px(0.12, mpt);
    const cv::Scalar wood(70, 120, 170);
    for (int x = 0; x < img.cols; x += bw) {
      cv::rectangle(img, cv::Rect(x, 0, bw, img.rows), jitter(wood, 0.15, rng), cv::FILLED);
      cv::line(img, cv::Point(x, 0), cv::Point(x, img.rows), scaleColour(wood, 0.45), std::max(1, px(0.006, mpt)));
      for (int k = 0; k < 5; ++k) {  // knots
        const cv::Point c(x + rng.uniformInt(bw / 4, 3 * bw / 4), rng.uniformInt(0, img.rows));
        cv::ellipse(img, c, cv::Size(std::max(2, bw / 10), std::max(3, bw / 5)), 0, 0, 360, scaleColour(wood, 0.6),
                    cv::FILLED, cv::LINE_AA);
      }
    }
  } else {  // patterned wallpaper: a jittered lattice of motifs
    const int cell = px(0.11, mpt);
    const cv::Scalar ink = rng.chance(0.5) ? scaleColour(base, 0.62) : randomColour(rng, 0.3, 0.6, 0.45, 0.7);
    const int motif = rng.uniformInt(0, 3);
    for (int row = 0, y = cell / 2; y < img.rows + cell; ++row, y += cell)
      for (int x = (row % 2) * cell / 2; x < img.cols + cell; x += cell) {
        const cv::Point c(x + rng.uniformInt(-cell / 10, cell / 10), y + rng.uniformInt(-cell / 10, cell / 10));
        const int s = static_cast<int>(cell * rng.uniform(0.18, 0.3));
        switch (motif) {
          case 0: {
            std::vector<cv::Point> d = {c + cv::Point(0, -s), c + cv::Point(s, 0), c + cv::Point(0, s),
                                        c + cv::Point(-s, 0)};
            cv::fillConvexPoly(img, d, ink, cv::LINE_AA);
            break;
          }
          case 1:
            cv::rectangle(img, cv::Rect(c.x - s, c.y - s, 2 * s, 2 * s), ink, std::max(1, s / 3));
            break;
          case 2:
            cv::line(img, c - cv::Point(s, 0), c + cv::Point(s, 0), ink, std::max(1, s / 3));
            cv::line(img, c - cv::Point(0, s), c + cv::Point(0, s), ink, std::max(1, s / 3));
            break;
          default: {
            std::vector<cv::Point> t = {c + cv::Point(0, -s), c + cv::Point(s, s), c + cv::Point(-s, s)};
            cv::fillConvexPoly(img, t, ink, cv::LINE_AA);
          }
        }
      }
  }
}

}  // namespace

cv::Scalar randomColour(Random& rng, double sat_lo, double sat_hi, double val_lo, double val_hi) {
  cv::Mat hsv(1, 1, CV_8UC3,
              cv::Scalar(rng.uniformInt(0, 179), rng.uniform(sat_lo, sat_hi) * 255, rng.uniform(val_lo, val_hi) * 255));
  cv::Mat bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
  return cv::Scalar(c[0], c[1], c[2]);
}

cv::Mat wall(const WallSpec& spec, Random& rng, const std::vector<cv::Mat>& photos) {
  const double m = spec.metres_per_texel;
  cv::Mat img(px(spec.height_m, m), px(spec.length_m, m), CV_8UC3, cv::Scalar::all(0));
  wallPattern(img, spec.style, m, rng);
  shade(img, smoothField(img.size(), px(0.8, m), px(0.8, m), rng), 0.05);
  grain(img, 4, rng);

  auto toPixels = [&](const cv::Rect2d& r) {
    return cv::Rect(px(r.x, m), px(r.y, m), px(r.width, m), px(r.height, m)) & cv::Rect(0, 0, img.cols, img.rows);
  };
  std::vector<cv::Rect> occupied;
  for (const WallFeature& f : spec.features) {
    const cv::Rect r = toPixels(f.rect_m);
    occupied.push_back(r);
    if (f.type == WallFeature::Type::kDoorway) drawDoorway(img, r, rng);
    if (f.type == WallFeature::Type::kWindow) drawWindow(img, r, rng);
    if (f.type == WallFeature::Type::kWhiteboard) drawWhiteboard(img, r, rng);
  }
  auto isFree = [&](const cv::Rect& r) {
    for (const cv::Rect& o : occupied) {
      const cv::Rect grown(o.x - px(0.05, m), o.y - px(0.05, m), o.width + px(0.1, m), o.height + px(0.1, m));
      if ((grown & r).area() > 0) return false;
    }
    return true;
  };

  // Skirting board and a picture rail.
  const int skirting = px(0.08, m);
  cv::rectangle(img, cv::Rect(0, img.rows - skirting, img.cols, skirting), cv::Scalar(225, 228, 230), cv::FILLED);
  cv::line(img, cv::Point(0, img.rows - skirting), cv::Point(img.cols, img.rows - skirting), cv::Scalar(120, 120, 120),
           std::max(1, px(0.006, m)));

  // Decorations along the wall, left to right, wherever there is room.
  double x = rng.uniform(0.1, 0.4);
  int photo_index = photos.empty() ? 0 : rng.uniformInt(0, static_cast<int>(photos.size()) - 1);
  while (x < spec.length_m - 0.3) {
    const int kind = static_cast<int>(rng.pickWeighted({4, 2, 1.5, 0.7, 1.0}));
    double w = 0, h = 0, top = 0;
    switch (kind) {
      case 0:
        w = rng.uniform(0.45, 0.8);
        h = w * rng.uniform(1.2, 1.45);
        top = rng.uniform(0.55, 0.85);
        break;  // poster
      case 1:
        w = rng.uniform(0.7, 1.1);
        h = rng.uniform(0.3, 0.45);
        top = rng.uniform(0.7, 0.9);
        break;  // frames
      case 2:
        w = rng.uniform(0.6, 0.9);
        h = w * rng.uniform(0.6, 0.8);
        top = rng.uniform(0.7, 0.9);
        break;  // notices
      case 3:
        w = 0.3;
        h = 0.3;
        top = rng.uniform(0.45, 0.6);
        break;  // clock
      default:
        w = rng.uniform(0.35, 0.6);
        h = w * 1.4;
        top = rng.uniform(0.6, 0.9);
        break;  // poster
    }
    w = std::min(w, spec.length_m - x - 0.1);
    const cv::Rect r = toPixels(cv::Rect2d(x, top, w, h));
    if (w > 0.25 && r.area() > 0 && isFree(r)) {
      occupied.push_back(r);
      const cv::Mat photo = photos.empty() || rng.chance(0.35)
                                ? cv::Mat()
                                : photos[static_cast<std::size_t>(photo_index++) % photos.size()];
      if (kind == 0 || kind == 4) {
        drawPosterInto(img, r, rng, photo);
        if (rng.chance(0.5)) drawFrame(img, r, std::max(2, px(0.015, m)), cv::Scalar(30, 30, 30));
      } else if (kind == 1) {
        const int n = rng.uniformInt(2, 3);
        const int fw = (r.width - (n - 1) * px(0.05, m)) / n;
        for (int i = 0; i < n; ++i) {
          const cv::Rect f(r.x + i * (fw + px(0.05, m)), r.y + rng.uniformInt(0, r.height / 5), fw, r.height * 4 / 5);
          const int t = std::max(3, px(0.025, m));
          cv::rectangle(img, f, rng.chance(0.5) ? cv::Scalar(40, 60, 90) : cv::Scalar(30, 30, 30), cv::FILLED);
          const cv::Rect inner(f.x + t, f.y + t, f.width - 2 * t, f.height - 2 * t);
          if (inner.width > 4 && inner.height > 4) {
            if (!photos.empty() && rng.chance(0.7)) {
              pastePhoto(img, inner, photos[static_cast<std::size_t>(photo_index++) % photos.size()]);
            } else {
              cv::rectangle(img, inner, cv::Scalar(240, 240, 240), cv::FILLED);
              shapes(img, cv::Rect(inner.x + t, inner.y + t, inner.width - 2 * t, inner.height - 2 * t), 6, rng);
            }
          }
        }
      } else if (kind == 2) {
        drawNoticeBoard(img, r, rng);
      } else {
        drawClock(img, (r.tl() + r.br()) / 2, r.width / 2, rng);
      }
    }
    x += w + rng.uniform(0.15, 0.5);
  }
  // Sockets and switches near the floor and by the door height.
  for (double sx = rng.uniform(0.3, 1.0); sx < spec.length_m - 0.2; sx += rng.uniform(0.9, 2.0)) {
    const cv::Point c(px(sx, m), img.rows - px(0.3, m));
    const cv::Rect r(c.x - px(0.05, m), c.y - px(0.05, m), px(0.1, m), px(0.1, m));
    if (isFree(r)) drawSocket(img, c, px(0.08, m));
  }
  return img;
}

cv::Mat floorPlanks(double width_m, double height_m, double mpt, const cv::Point2d& rug_centre_m,
                    const cv::Size2d& rug_size_m, Random& rng) {
  const cv::Scalar wood_base(60, 110, 160);
  cv::Mat img(px(height_m, mpt), px(width_m, mpt), CV_8UC3, wood_base);
  const int plank_w = px(0.14, mpt);
  // Grain: a field stretched along the planks (x).
  const cv::Mat grain_field = smoothField(img.size(), px(0.6, mpt), px(0.012, mpt), rng);
  for (int y0 = 0; y0 < img.rows; y0 += plank_w) {
    double x = -rng.uniform(0, 1.2);
    while (x < width_m) {
      const double len = rng.uniform(0.7, 1.8);
      // Shared, rounded ends: no gaps between planks.
      const int x0 = static_cast<int>(std::lround(std::max(0.0, x) / mpt)),
                x1 = static_cast<int>(std::lround((x + len) / mpt));
      const cv::Rect r(x0, y0, x1 - x0, plank_w);
      cv::rectangle(img, r & cv::Rect(0, 0, img.cols, img.rows), jitter(wood_base, 0.18, rng), cv::FILLED);
      cv::line(img, cv::Point(r.x, y0), cv::Point(r.x, y0 + plank_w), cv::Scalar(25, 40, 60),
               std::max(1, px(0.004, mpt)));
      x += len;
    }
    cv::line(img, cv::Point(0, y0), cv::Point(img.cols, y0), cv::Scalar(25, 40, 60), std::max(1, px(0.004, mpt)));
  }
  shade(img, grain_field, 0.12);
  // Scuffs and stains.
  for (int i = 0; i < static_cast<int>(width_m * height_m * 2); ++i) {
    const cv::Point c(rng.uniformInt(0, img.cols), rng.uniformInt(0, img.rows));
    cv::ellipse(img, c, cv::Size(px(rng.uniform(0.02, 0.08), mpt), px(rng.uniform(0.01, 0.04), mpt)),
                rng.uniform(0, 180), 0, 360, cv::Scalar(45, 80, 120), cv::FILLED, cv::LINE_AA);
  }
  if (rug_size_m.width > 0 && rug_size_m.height > 0) {
    const cv::Rect rug(px(rug_centre_m.x - rug_size_m.width / 2, mpt), px(rug_centre_m.y - rug_size_m.height / 2, mpt),
                       px(rug_size_m.width, mpt), px(rug_size_m.height, mpt));
    const cv::Scalar c1 = randomColour(rng, 0.5, 0.8, 0.35, 0.6), c2 = randomColour(rng, 0.3, 0.6, 0.7, 0.9);
    cv::rectangle(img, rug, c1, cv::FILLED);
    const int band = px(0.08, mpt);
    cv::rectangle(img, cv::Rect(rug.x + band, rug.y + band, rug.width - 2 * band, rug.height - 2 * band), c2,
                  std::max(2, band / 3));
    const int cell = px(0.25, mpt);
    for (int y = rug.y + 2 * band + cell / 2; y < rug.y + rug.height - 2 * band; y += cell)
      for (int x = rug.x + 2 * band + cell / 2; x < rug.x + rug.width - 2 * band; x += cell) {
        const int s = cell * 2 / 5;
        std::vector<cv::Point> d = {{x, y - s}, {x + s, y}, {x, y + s}, {x - s, y}};
        cv::fillConvexPoly(img, d, (x / cell + y / cell) % 2 ? c2 : scaleColour(c1, 0.6), cv::LINE_AA);
        cv::circle(img, cv::Point(x, y), s / 3, scaleColour(c2, 0.5), cv::FILLED, cv::LINE_AA);
      }
  }
  grain(img, 5, rng);
  return img;
}

cv::Mat ceiling(double width_m, double height_m, double mpt, Random& rng) {
  cv::Mat img(px(height_m, mpt), px(width_m, mpt), CV_8UC3, cv::Scalar(222, 226, 228));
  const int tile = px(0.6, mpt);
  for (int y = 0; y < img.rows; y += tile)
    for (int x = 0; x < img.cols; x += tile) {
      const cv::Rect r(x, y, tile, tile);
      cv::rectangle(img, r, jitter(cv::Scalar(215, 220, 222), 0.04, rng), cv::FILLED);
      for (int k = 0; k < tile * tile / 60; ++k)
        cv::circle(img, cv::Point(x + rng.uniformInt(0, tile), y + rng.uniformInt(0, tile)), 1,
                   cv::Scalar(150, 155, 160), cv::FILLED);
    }
  for (int y = 0; y < img.rows; y += tile)
    cv::line(img, cv::Point(0, y), cv::Point(img.cols, y), cv::Scalar(175, 178, 180), std::max(1, px(0.02, mpt)));
  for (int x = 0; x < img.cols; x += tile)
    cv::line(img, cv::Point(x, 0), cv::Point(x, img.rows), cv::Scalar(175, 178, 180), std::max(1, px(0.02, mpt)));
  // Lamps (bright panels with louvres) and vents.
  for (int ty = 1; ty * tile < img.rows - tile; ty += 3)
    for (int tx = 1; tx * tile < img.cols - tile; tx += 3) {
      const cv::Rect r(tx * tile + 3, ty * tile + 3, tile - 6, 2 * tile - 6);
      if (r.y + r.height >= img.rows) continue;
      if (rng.chance(0.8)) {
        cv::rectangle(img, r, cv::Scalar(250, 252, 252), cv::FILLED);
        for (int k = 1; k < 6; ++k)
          cv::line(img, cv::Point(r.x, r.y + k * r.height / 6), cv::Point(r.x + r.width, r.y + k * r.height / 6),
                   cv::Scalar(185, 190, 195), std::max(1, tile / 60));
        cv::line(img, cv::Point(r.x + r.width / 2, r.y), cv::Point(r.x + r.width / 2, r.y + r.height),
                 cv::Scalar(185, 190, 195), std::max(1, tile / 60));
      } else {
        const cv::Rect v(r.x + tile / 6, r.y + tile / 6, tile / 2, tile / 2);
        cv::rectangle(img, v, cv::Scalar(190, 192, 195), cv::FILLED);
        for (int k = 1; k < 8; ++k)
          cv::line(img, cv::Point(v.x, v.y + k * v.height / 8), cv::Point(v.x + v.width, v.y + k * v.height / 8),
                   cv::Scalar(90, 90, 95), std::max(1, tile / 80));
      }
    }
  grain(img, 3, rng);
  return img;
}

cv::Mat books(cv::Size size, Random& rng) {
  cv::Mat img(size, CV_8UC3, cv::Scalar(35, 40, 45));
  int x = 0;
  while (x < size.width) {
    const int w = std::max(4, static_cast<int>(size.height * rng.uniform(0.08, 0.22)));
    if (rng.chance(0.07)) {  // a gap
      x += w;
      continue;
    }
    const int h = static_cast<int>(size.height * rng.uniform(0.68, 0.98));
    const cv::Rect spine(x, size.height - h, std::min(w, size.width - x), h);
    const cv::Scalar c = randomColour(rng, 0.3, 0.9, 0.25, 0.9);
    cv::rectangle(img, spine, c, cv::FILLED);
    const cv::Scalar ink = inkFor(c, rng);
    for (int b = 0; b < rng.uniformInt(0, 3); ++b) {
      const int by = spine.y + static_cast<int>(h * rng.uniform(0.05, 0.9));
      cv::rectangle(img, cv::Rect(spine.x, by, spine.width, std::max(2, h / 30)), ink, cv::FILLED);
    }
    putTextFit(img, randomWord(rng, 2, 4), cv::Rect(spine.x + 1, spine.y + h / 3, spine.width - 2, h / 5), ink,
               cv::FONT_HERSHEY_SIMPLEX);
    cv::line(img, cv::Point(x, spine.y), cv::Point(x, size.height), scaleColour(c, 0.5), 1);
    x += w;
  }
  grain(img, 4, rng);
  return img;
}

cv::Mat cardboard(cv::Size size, Random& rng) {
  cv::Mat img(size, CV_8UC3, jitter(cv::Scalar(95, 150, 190), 0.1, rng));
  shade(img, smoothField(size, size.width / 6.0, size.height / 6.0, rng), 0.06);
  grain(img, 8, rng);
  const int tape_h = size.height / 7;
  cv::rectangle(img, cv::Rect(0, size.height / 2 - tape_h / 2, size.width, tape_h), cv::Scalar(120, 175, 205),
                cv::FILLED);
  cv::line(img, cv::Point(0, size.height / 2 - tape_h / 2), cv::Point(size.width, size.height / 2 - tape_h / 2),
           cv::Scalar(70, 110, 140), 2);
  cv::line(img, cv::Point(0, size.height / 2 + tape_h / 2), cv::Point(size.width, size.height / 2 + tape_h / 2),
           cv::Scalar(70, 110, 140), 2);
  // Printed pictograms and text.
  const cv::Scalar print = rng.chance(0.5) ? cv::Scalar(30, 30, 30) : cv::Scalar(30, 30, 170);
  putTextFit(img, rng.chance(0.5) ? "FRAGILE" : randomWord(rng, 4, 8),
             cv::Rect(size.width / 10, size.height / 14, size.width * 8 / 10, size.height / 6), print,
             cv::FONT_HERSHEY_DUPLEX);
  for (int i = 0; i < 2; ++i) {
    const int ax = size.width / 8 + i * size.width / 8;
    cv::arrowedLine(img, cv::Point(ax, size.height * 9 / 10), cv::Point(ax, size.height * 7 / 10), print,
                    std::max(2, size.width / 80), cv::LINE_AA, 0, 0.3);
  }
  const cv::Rect label(size.width / 2, size.height * 6 / 10, size.width * 2 / 5, size.height / 4);
  cv::rectangle(img, label, cv::Scalar(245, 245, 245), cv::FILLED);
  textBlock(img, cv::Rect(label.x + 4, label.y + 2, label.width - 8, label.height / 2), label.height / 7.0,
            cv::Scalar(20, 20, 20), rng);
  barcode(img, cv::Rect(label.x + 4, label.y + label.height / 2 + 2, label.width - 8, label.height / 2 - 6), rng);
  return img;
}

cv::Mat wood(cv::Size size, double tone, Random& rng) {
  const cv::Scalar pale(160, 195, 220), dark(35, 60, 95);
  const cv::Scalar base = pale * (1 - tone) + dark * tone;
  cv::Mat img(size, CV_8UC3, base);
  shade(img, smoothField(size, size.width / 3.0, std::max(2.0, size.height / 60.0), rng), 0.15);
  for (int i = 0; i < size.height / 6; ++i) {
    const int y = rng.uniformInt(0, size.height);
    cv::line(img, cv::Point(0, y), cv::Point(size.width, y + rng.uniformInt(-4, 4)), scaleColour(base, 0.8), 1,
             cv::LINE_AA);
  }
  grain(img, 5, rng);
  return img;
}

cv::Mat deskTop(cv::Size size, Random& rng) {
  cv::Mat img = wood(size, rng.uniform(0.0, 0.3), rng);
  for (int i = 0; i < rng.uniformInt(4, 7); ++i) {
    const double w = size.width * rng.uniform(0.12, 0.2), h = w * 1.41;
    const cv::Point2f c(static_cast<float>(rng.uniform(0.1, 0.9) * size.width),
                        static_cast<float>(rng.uniform(0.15, 0.85) * size.height));
    const cv::RotatedRect rr(c, cv::Size2f(static_cast<float>(w), static_cast<float>(h)),
                             static_cast<float>(rng.uniform(-30, 30)));
    cv::Point2f pts[4];
    rr.points(pts);
    std::vector<cv::Point> poly(pts, pts + 4);
    cv::fillConvexPoly(img, poly, cv::Scalar(245, 245, 245), cv::LINE_AA);
    // Text lines along the page (axis-aligned inside its bounding box is enough for texture).
    const cv::Rect box = rr.boundingRect() & cv::Rect(0, 0, size.width, size.height);
    cv::Mat page = img(box).clone();
    textBlock(page, cv::Rect(box.width / 5, box.height / 5, box.width * 3 / 5, box.height * 3 / 5), h / 16.0,
              cv::Scalar(40, 40, 40), rng);
    cv::Mat mask = cv::Mat::zeros(box.size(), CV_8U);
    std::vector<cv::Point> local;
    for (const cv::Point& p : poly) local.push_back(p - box.tl());
    cv::fillConvexPoly(mask, local, cv::Scalar(255));
    page.copyTo(img(box), mask);
  }
  for (int i = 0; i < rng.uniformInt(2, 4); ++i) {  // sticky notes
    const int s = size.width / 14;
    const cv::Rect n(rng.uniformInt(0, size.width - s), rng.uniformInt(0, size.height - s), s, s);
    cv::rectangle(img, n, cv::Scalar(90, 235, 250), cv::FILLED);
    textBlock(img, cv::Rect(n.x + 2, n.y + 2, n.width - 4, n.height - 4), s / 5.0, cv::Scalar(120, 40, 20), rng);
  }
  return img;
}

cv::Mat fabric(cv::Size size, const cv::Scalar& base, Random& rng) {
  cv::Mat img(size, CV_8UC3, base);
  for (int y = 0; y < size.height; ++y) {
    cv::Vec3b* row = img.ptr<cv::Vec3b>(y);
    for (int x = 0; x < size.width; ++x) {
      const int weave = ((x / 2 + y / 2) % 2) ? 10 : -10;
      for (int c = 0; c < 3; ++c) row[x][c] = cv::saturate_cast<uchar>(row[x][c] + weave);
    }
  }
  shade(img, smoothField(size, size.width / 5.0, size.height / 5.0, rng), 0.08);
  grain(img, 10, rng);
  return img;
}

cv::Mat metal(cv::Size size, const cv::Scalar& base, Random& rng) {
  cv::Mat img(size, CV_8UC3, base);
  shade(img, smoothField(size, size.width / 2.0, 2.0, rng), 0.08);
  grain(img, 6, rng);
  return img;
}

cv::Mat screen(cv::Size size, Random& rng, const cv::Mat& photo) {
  cv::Mat img(size, CV_8UC3, cv::Scalar::all(0));
  const cv::Scalar top = randomColour(rng, 0.5, 0.9, 0.3, 0.6), bottom = scaleColour(top, 0.4);
  for (int y = 0; y < size.height; ++y) {
    const double f = y / static_cast<double>(size.height);
    cv::line(img, cv::Point(0, y), cv::Point(size.width, y), top * (1 - f) + bottom * f);
  }
  const int bezel = std::max(3, size.width / 40);
  if (!photo.empty()) pastePhoto(img, cv::Rect(0, 0, size.width, size.height), photo);
  for (int i = 0; i < rng.uniformInt(2, 3); ++i) {
    const int w = static_cast<int>(size.width * rng.uniform(0.35, 0.6)),
              h = static_cast<int>(size.height * rng.uniform(0.35, 0.6));
    const cv::Rect r(rng.uniformInt(bezel, size.width - w - bezel), rng.uniformInt(bezel, size.height - h - bezel), w,
                     h);
    cv::rectangle(img, r, cv::Scalar(245, 245, 245), cv::FILLED);
    cv::rectangle(img, cv::Rect(r.x, r.y, r.width, std::max(3, h / 10)), randomColour(rng, 0.4, 0.8, 0.4, 0.8),
                  cv::FILLED);
    textBlock(img, cv::Rect(r.x + 4, r.y + h / 8, r.width - 8, r.height - h / 8 - 4), std::max(4.0, h / 14.0),
              cv::Scalar(30, 30, 30), rng);
  }
  for (int i = 0; i < 5; ++i)
    cv::rectangle(img, cv::Rect(bezel + 2, bezel + 2 + i * size.height / 7, size.width / 16, size.width / 16),
                  randomColour(rng, 0.6, 1.0, 0.6, 1.0), cv::FILLED);
  cv::rectangle(img, cv::Rect(0, 0, size.width, size.height), cv::Scalar(20, 20, 20), bezel);
  return img;
}

cv::Mat keyboard(cv::Size size, Random& rng) {
  cv::Mat img(size, CV_8UC3, cv::Scalar(40, 40, 42));
  const int rows = 5, cols = 15;
  const double kw = size.width / static_cast<double>(cols), kh = size.height / static_cast<double>(rows);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const cv::Rect key(static_cast<int>(c * kw + 1), static_cast<int>(r * kh + 1), static_cast<int>(kw - 2),
                         static_cast<int>(kh - 2));
      cv::rectangle(img, key, cv::Scalar(70, 70, 74), cv::FILLED);
      putTextFit(img, randomWord(rng, 1, 1),
                 cv::Rect(key.x + key.width / 4, key.y + key.height / 4, key.width / 2, key.height / 2),
                 cv::Scalar(220, 220, 220), cv::FONT_HERSHEY_SIMPLEX, 1);
    }
  return img;
}

cv::Mat door(cv::Size size, Random& rng) {
  cv::Mat img = wood(size, rng.uniform(0.2, 0.6), rng);
  const int m = size.width / 8;
  const cv::Scalar line_c(30, 50, 70);
  cv::rectangle(img, cv::Rect(m, m, size.width - 2 * m, size.height * 2 / 5 - m), line_c, std::max(2, m / 6));
  cv::rectangle(img, cv::Rect(m, size.height * 2 / 5 + m, size.width - 2 * m, size.height * 3 / 5 - 2 * m), line_c,
                std::max(2, m / 6));
  // Handle on the free side (texture right), sign and a notice at eye level.
  const cv::Point handle(size.width - m, size.height / 2);
  cv::circle(img, handle, m / 3, cv::Scalar(180, 185, 190), cv::FILLED, cv::LINE_AA);
  cv::rectangle(img, cv::Rect(handle.x - m, handle.y - m / 8, m, m / 4), cv::Scalar(190, 195, 200), cv::FILLED);
  const cv::Rect sign(size.width / 4, size.height / 5, size.width / 2, size.height / 16);
  cv::rectangle(img, sign, cv::Scalar(240, 240, 240), cv::FILLED);
  putTextFit(img, "ROOM " + std::to_string(rng.uniformInt(1, 4)) + "." + std::to_string(rng.uniformInt(10, 99)), sign,
             cv::Scalar(20, 20, 20), cv::FONT_HERSHEY_SIMPLEX);
  drawPosterInto(img, cv::Rect(size.width / 4, size.height / 4 + size.height / 20, size.width / 2, size.height / 5),
                 rng, cv::Mat());
  return img;
}

cv::Mat leaves(cv::Size size, Random& rng) {
  cv::Mat img(size, CV_8UC3, cv::Scalar(30, 70, 35));
  for (int i = 0; i < size.area() / 60; ++i) {
    const cv::Point c(rng.uniformInt(0, size.width), rng.uniformInt(0, size.height));
    const int l = rng.uniformInt(size.width / 40 + 2, size.width / 15 + 3);
    cv::ellipse(img, c, cv::Size(l, l / 3 + 1), rng.uniform(0, 180), 0, 360,
                cv::Scalar(rng.uniform(20, 70), rng.uniform(90, 190), rng.uniform(30, 90)), cv::FILLED, cv::LINE_AA);
  }
  return img;
}

cv::Mat poster(cv::Size size, Random& rng, const cv::Mat& photo) {
  cv::Mat img(size, CV_8UC3, cv::Scalar::all(0));
  drawPosterInto(img, cv::Rect(0, 0, size.width, size.height), rng, photo);
  return img;
}

cv::Mat shirt(cv::Size size, Random& rng) {
  const cv::Scalar base = randomColour(rng, 0.3, 0.9, 0.3, 0.9);
  cv::Mat img(size, CV_8UC3, base);
  const int style = rng.uniformInt(0, 2);
  if (style == 0) {  // plaid
    const cv::Scalar a = randomColour(rng, 0.4, 0.9, 0.2, 0.6), b = cv::Scalar(235, 235, 235);
    const int p = std::max(6, size.width / 12);
    for (int x = 0; x < size.width; x += p) cv::rectangle(img, cv::Rect(x, 0, p / 3, size.height), a, cv::FILLED);
    for (int y = 0; y < size.height; y += p) cv::rectangle(img, cv::Rect(0, y, size.width, p / 3), a, cv::FILLED);
    for (int x = p / 2; x < size.width; x += p) cv::line(img, cv::Point(x, 0), cv::Point(x, size.height), b, 1);
    for (int y = p / 2; y < size.height; y += p) cv::line(img, cv::Point(0, y), cv::Point(size.width, y), b, 1);
  } else if (style == 1) {  // stripes
    const cv::Scalar a = inkFor(base, rng);
    const int p = std::max(6, size.height / 14);
    for (int y = 0; y < size.height; y += p) cv::rectangle(img, cv::Rect(0, y, size.width, p / 2), a, cv::FILLED);
  } else {  // a print on the front (s = 0.5 faces forward)
    const cv::Rect print(size.width * 3 / 8, size.height / 4, size.width / 4, size.height / 3);
    shapes(img, print, 4, rng);
    putTextFit(img, randomWord(rng, 3, 6), cv::Rect(print.x, print.y + print.height, print.width, print.height / 3),
               inkFor(base, rng), cv::FONT_HERSHEY_DUPLEX);
  }
  shade(img, smoothField(size, size.width / 4.0, size.height / 6.0, rng), 0.12);  // folds
  grain(img, 6, rng);
  return img;
}

cv::Mat trousers(cv::Size size, Random& rng) {
  const int kind = rng.uniformInt(0, 2);
  const cv::Scalar base = kind == 0   ? cv::Scalar(120, 75, 40)
                          : kind == 1 ? cv::Scalar(90, 140, 160)
                                      : cv::Scalar(40, 40, 45);
  cv::Mat img(size, CV_8UC3, base);
  for (int i = -size.height; i < size.width; i += 3)
    cv::line(img, cv::Point(i, 0), cv::Point(i + size.height, size.height), scaleColour(base, 1.15), 1);
  shade(img, smoothField(size, size.width / 3.0, size.height / 8.0, rng), 0.15);
  grain(img, 8, rng);
  return img;
}

cv::Mat skin(cv::Size size, Random& rng, bool with_face) {
  const cv::Scalar tones[] = {cv::Scalar(150, 175, 225), cv::Scalar(120, 150, 200), cv::Scalar(80, 110, 160),
                              cv::Scalar(50, 75, 115)};
  const cv::Scalar base = jitter(tones[rng.uniformInt(0, 3)], 0.05, rng);
  cv::Mat img(size, CV_8UC3, base);
  grain(img, 3, rng);
  if (with_face) {
    // Equirectangular head: s = 0.5 faces forward, t = 0 at the top.
    const int W = size.width, H = size.height;
    const cv::Scalar hair_c = randomColour(rng, 0.3, 0.7, 0.05, 0.35);
    cv::rectangle(img, cv::Rect(0, 0, W, H * 3 / 10), hair_c, cv::FILLED);
    cv::rectangle(img, cv::Rect(0, 0, W / 4, H * 7 / 10), hair_c, cv::FILLED);
    cv::rectangle(img, cv::Rect(W * 3 / 4, 0, W / 4, H * 7 / 10), hair_c, cv::FILLED);
    cv::Mat hair_roi = img(cv::Rect(0, 0, W, H * 3 / 10));
    grain(hair_roi, 12, rng);
    const int ey = H * 45 / 100, ex = W / 28;
    for (int s : {-1, 1}) {
      cv::ellipse(img, cv::Point(W / 2 + s * ex, ey), cv::Size(W / 70 + 1, H / 70 + 1), 0, 0, 360,
                  cv::Scalar(245, 245, 245), cv::FILLED);
      cv::circle(img, cv::Point(W / 2 + s * ex, ey), H / 110 + 1, cv::Scalar(40, 30, 20), cv::FILLED);
      cv::line(img, cv::Point(W / 2 + s * ex - W / 60, ey - H / 30), cv::Point(W / 2 + s * ex + W / 60, ey - H / 30),
               scaleColour(hair_c, 0.8), std::max(1, H / 120));
    }
    cv::line(img, cv::Point(W / 2, ey + H / 40), cv::Point(W / 2 + W / 120, ey + H / 12), scaleColour(base, 0.75),
             std::max(1, H / 150));
    cv::ellipse(img, cv::Point(W / 2, H * 62 / 100), cv::Size(W / 40, H / 80 + 1), 0, 0, 180, cv::Scalar(60, 60, 150),
                std::max(1, H / 120), cv::LINE_AA);
  }
  return img;
}

cv::Mat hair(cv::Size size, Random& rng) {
  cv::Mat img(size, CV_8UC3, randomColour(rng, 0.3, 0.7, 0.05, 0.35));
  shade(img, smoothField(size, 3, size.height / 4.0, rng), 0.3);
  return img;
}

}  // namespace amos::synth::textures
