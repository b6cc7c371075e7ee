// Clothing, skin (with a face on the head) and hair for the procedural people.
#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "amos/synth/procedural_textures.h"
#include "amos/synth/texture_painting.h"

namespace amos::synth::textures {

using paint::grain;
using paint::inkFor;
using paint::jitter;
using paint::putTextFit;
using paint::randomWord;
using paint::scaleColour;
using paint::shade;
using paint::shapes;
using paint::smoothField;

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
