#pragma once
// Drawing helpers shared by the procedural textures (room_textures.cc, object_textures.cc, person_textures.cc).
// Private to the synth module: callers use procedural_textures.h. Every helper that takes a Random draws from it in
// a fixed order, so the textures stay reproducible texel for texel from a seed.
#include <opencv2/core.hpp>
#include <string>

#include "amos/synth/random.h"

namespace amos::synth::textures::paint {

// Metres to texels, rounded, at least 1.
int px(double metres, double metres_per_texel);

// Smooth random field in about [-1, 1] with features of about cell_x by cell_y texels (cubic interpolation of a
// coarse grid); CV_32F of `size`.
cv::Mat smoothField(cv::Size size, double cell_x, double cell_y, Random& rng);
// img *= 1 + amplitude * field.
void shade(cv::Mat& img, const cv::Mat& field, double amplitude);
// Per-texel luminance grain, uniform in [-amplitude, amplitude].
void grain(cv::Mat& img, int amplitude, Random& rng);

cv::Scalar scaleColour(const cv::Scalar& c, double k);
// The colour with random brightness (1 +- amount) and a small random offset per channel.
cv::Scalar jitter(const cv::Scalar& c, double amount, Random& rng);
// Contrasting ink for a background.
cv::Scalar inkFor(const cv::Scalar& bg, Random& rng);

// Capital letters (and digits, half of the time each, when `digits`), lo..hi characters.
std::string randomWord(Random& rng, int lo, int hi, bool digits = false);
// Text scaled to fit `box` (height first, then width).
void putTextFit(cv::Mat& img, const std::string& text, const cv::Rect& box, const cv::Scalar& colour, int font,
                int thickness_hint = 0);
// Lines of random words, left aligned, filling `area`.
void textBlock(cv::Mat& img, const cv::Rect& area, double line_px, const cv::Scalar& colour, Random& rng);
void barcode(cv::Mat& img, const cv::Rect& area, Random& rng);
// Random filled shapes (rectangles, circles, triangles) inside `area`.
void shapes(cv::Mat& img, const cv::Rect& area, int count, Random& rng);
// The photo centre-cropped to the area's aspect ratio and resized into it.
void pastePhoto(cv::Mat& img, const cv::Rect& area, const cv::Mat& photo);
// A poster filling `area`: title, then the photo (when given), a bar chart or shapes, then lines of text.
void drawPosterInto(cv::Mat& img, const cv::Rect& area, Random& rng, const cv::Mat& photo);

}  // namespace amos::synth::textures::paint
