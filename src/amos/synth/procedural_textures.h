#pragma once
// Procedural textures, built in so that nothing outside the repository is needed. They are made to be rich in
// corners (text, tiles, bricks, book spines, labels) so that an ORB front end finds features wherever the camera
// looks, and each large surface gets its own non-repeating image so that features are distinctive. All images
// are CV_8UC3 BGR; everything is drawn from the Random passed in, so a seed fixes every texel.
#include <opencv2/core.hpp>
#include <vector>

#include "amos/synth/random.h"

namespace amos::synth::textures {

// Something drawn at a fixed place on a wall, in metres from the wall's top-left corner seen from the room
// (x to the right, y down).
struct WallFeature {
  enum class Type { kDoorway, kWindow, kWhiteboard, kKeepClear };
  Type type = Type::kKeepClear;
  cv::Rect2d rect_m;
};

struct WallSpec {
  double length_m = 4, height_m = 2.7;
  double metres_per_texel = 0.004;
  int style = 0;  // 0 patterned wallpaper, 1 painted bricks, 2 concrete blocks, 3 wood panelling
  std::vector<WallFeature> features;
};

// A wall with its pattern, skirting board, posters, framed pictures (the photos when given), notices and sockets.
cv::Mat wall(const WallSpec& spec, Random& rng, const std::vector<cv::Mat>& photos);

// Wooden plank floor of the given size with a patterned rug centred at rug_centre_m (metres from the texture's
// top-left corner; rug_size_m of zero for none).
cv::Mat floorPlanks(double width_m, double height_m, double metres_per_texel, const cv::Point2d& rug_centre_m,
                    const cv::Size2d& rug_size_m, Random& rng);
// Suspended ceiling: 60 cm tiles with speckle, lamps and vents.
cv::Mat ceiling(double width_m, double height_m, double metres_per_texel, Random& rng);

// Row of book spines filling the image (a shelf seen from the front).
cv::Mat books(cv::Size size, Random& rng);
// Cardboard with tape, printed labels, arrows and barcodes.
cv::Mat cardboard(cv::Size size, Random& rng);
// Wood or laminate; `tone` in [0, 1] from pale to dark.
cv::Mat wood(cv::Size size, double tone, Random& rng);
// Desk top: laminate with papers, notes and a pen.
cv::Mat deskTop(cv::Size size, Random& rng);
// Woven fabric of the given base colour.
cv::Mat fabric(cv::Size size, const cv::Scalar& base, Random& rng);
// Brushed metal / painted metal.
cv::Mat metal(cv::Size size, const cv::Scalar& base, Random& rng);
// Monitor: a desktop with windows, text and icons, or a photo when given.
cv::Mat screen(cv::Size size, Random& rng, const cv::Mat& photo = cv::Mat());
cv::Mat keyboard(cv::Size size, Random& rng);
// Door leaf with panels, a handle, a room sign and a notice.
cv::Mat door(cv::Size size, Random& rng);
cv::Mat leaves(cv::Size size, Random& rng);
// Poster or framed picture filling the image (a photo inside when given).
cv::Mat poster(cv::Size size, Random& rng, const cv::Mat& photo = cv::Mat());

// Clothing and skin for the procedural people.
cv::Mat shirt(cv::Size size, Random& rng);
cv::Mat trousers(cv::Size size, Random& rng);
cv::Mat skin(cv::Size size, Random& rng, bool with_face);
cv::Mat hair(cv::Size size, Random& rng);

// A random saturated-or-not colour: hue anywhere, saturation and value in the given ranges (0..1).
cv::Scalar randomColour(Random& rng, double sat_lo, double sat_hi, double val_lo, double val_hi);

}  // namespace amos::synth::textures
