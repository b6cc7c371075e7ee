// Textures of furniture and the things on it: shelves of books, boxes, wood, desks, fabric, metal, monitors,
// keyboards, doors, plants and posters.
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "amos/synth/procedural_textures.h"
#include "amos/synth/texture_painting.h"

namespace amos::synth::textures {

using paint::barcode;
using paint::drawPosterInto;
using paint::grain;
using paint::inkFor;
using paint::jitter;
using paint::pastePhoto;
using paint::putTextFit;
using paint::randomWord;
using paint::scaleColour;
using paint::shade;
using paint::smoothField;
using paint::textBlock;

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

}  // namespace amos::synth::textures
