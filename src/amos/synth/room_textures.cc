// Room surfaces: walls (base pattern plus doorways, windows, whiteboards, posters, frames, notice boards, clocks and
// sockets), the plank floor with its rug, and the tiled ceiling.
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "amos/synth/procedural_textures.h"
#include "amos/synth/texture_painting.h"

namespace amos::synth::textures {

using paint::drawPosterInto;
using paint::grain;
using paint::jitter;
using paint::pastePhoto;
using paint::putTextFit;
using paint::px;
using paint::randomWord;
using paint::scaleColour;
using paint::shade;
using paint::shapes;
using paint::smoothField;
using paint::textBlock;

namespace {

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

}  // namespace amos::synth::textures
