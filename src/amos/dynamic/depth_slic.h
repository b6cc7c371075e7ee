#pragma once
// Depth-SLIC superpixels (paper Section III-B, Eq. 1-4): SLIC (Achanta et al.) on Lab colour and image position,
// with an added depth term so that superpixel borders follow geometric (depth) edges even where colour does not
// change. Runs on a downscaled copy of the frame for speed; the label map is returned at full resolution.
#include <opencv2/core.hpp>
#include <vector>

namespace amos::dynamic {

// Distance of pixel i to cluster centre c (Eq. 1), each term divided by its normaliser R():
//   D = D_C / colour_scale + D_E / S + D_Z / depth_scale_m
// D_C = Lab distance (Eq. 2), D_E = image distance in working-resolution pixels (Eq. 3), S = grid step, and
// D_Z = |d_i - d_c| (see depth_slic.cc for why not Eq. 4 as printed). When the pixel or the centre has no valid
// depth (0), D_Z is left out: that pixel joins by colour and position only.
struct DepthSlicOptions {
  // Dynamic.Superpixel.count: superpixels over the whole image. ~300 gives S ~ 26 px at 640x480 (a person at
  // 3 m is ~200 px tall, so ~8 superpixels along it) while keeping k-means over superpixels trivial.
  int num_superpixels = 300;
  // Dynamic.Superpixel.scale: working resolution relative to the input (0.5 = 320x240). SLIC cost is linear in
  // the pixel count; at S ~ 13 working pixels a 2x downscale still leaves several pixels per superpixel edge.
  double scale = 0.5;
  // Dynamic.Superpixel.colourScale: Lab distance that weighs as much as one grid step of displacement (SLIC's
  // compactness m; Achanta et al. recommend 10 for CIELAB, where ~2.3 is a just-noticeable difference).
  double colour_scale = 10.0;
  // Dynamic.Superpixel.depthScale: depth difference [m] that weighs as much as one grid step. Object borders in
  // indoor scenes are >= 0.3 m deep (3 units, dominating colour and position), while sensor noise
  // sigma(z) = 0.0012 + 0.0019 (z - 0.4)^2 m stays below 0.026 m (0.26 units) out to z = 4 m.
  double depth_scale_m = 0.10;
  // Dynamic.Superpixel.iterations: SLIC assignment/update rounds; the centres move < 1 px after ~5 rounds.
  int iterations = 5;
  // Throws core::InvalidOption naming the member at fault.
  void check() const;
};

// One superpixel S_i = [x, y, L, A, B, d, C] (paper III-B): means over its pixels.
struct Superpixel {
  float x = 0, y = 0;              // centroid in full-resolution pixel coordinates
  float L = 0, A = 0, B = 0;       // mean CIELAB colour (L in [0, 100])
  float depth = 0;                 // mean of the valid depths [m]; 0 when none of its pixels has depth
  float valid_depth_fraction = 0;  // share of its pixels with valid depth
  int pixel_count = 0;             // at working resolution
  int cluster = -1;                // geometric cluster label C_i, set by k-means (geometric_clustering.h)
};

struct SuperpixelSegmentation {
  cv::Mat labels;  // CV_32S, full input resolution, values 0..superpixels.size()-1, every pixel labelled
  // The same at the working resolution (DepthSlicOptions::scale), of which `labels` is the nearest-neighbour
  // upsampling: the same superpixels touch each other in both, at a quarter of the pixels for scale 0.5.
  cv::Mat working_labels;
  std::vector<Superpixel> superpixels;
};

// bgr: CV_8UC3; depth: CV_32F metres, same size, 0 (or non-finite) = invalid. Deterministic.
SuperpixelSegmentation computeDepthSlic(const cv::Mat& bgr, const cv::Mat& depth, const DepthSlicOptions& options);

// Builds, once per process, what OpenCV computes on its first 8-bit BGR -> Lab conversion: lookup tables made with
// software floating point (~0.15 s on one core), which would otherwise fall on the first frame's superpixels and
// make that frame several frame periods late (a live run drops the frames that arrive meanwhile). Call it before
// the first frame; computeDepthSlic works, with the same results, without it.
void prepareDepthSlic();

// The integer factor f with big = f x small in both directions, or 0 when there is none: for a segmentation,
// integerFactor(labels.size(), working_labels.size()) > 0 says that `labels` is `working_labels` in f x f blocks.
int integerFactor(cv::Size big, cv::Size small);

namespace detail {
// computeDepthSlic with the 8-lane AVX2 assignment loop on or off (on is used when the CPU has AVX2; both give the
// same result). For tests and benchmarks.
SuperpixelSegmentation computeDepthSlic(const cv::Mat& bgr, const cv::Mat& depth, const DepthSlicOptions& options,
                                        bool avx2);
}  // namespace detail

}  // namespace amos::dynamic
