#pragma once
// Textures for the renderer: an 8-bit BGR mip pyramid sampled with trilinear filtering (bilinear within a level,
// linear between levels), so that far or slanted surfaces do not alias into flickering fake corners. An optional
// alpha channel turns a texture into a cut-out (billboards of people).
#include <opencv2/core.hpp>
#include <vector>

namespace amos::synth {

class Texture {
 public:
  // bgr: CV_8UC3 (at least 1x1). alpha: empty or CV_8UC1 of the same size (255 = opaque). With `repeat` the
  // coordinates wrap around (tiling); otherwise they clamp to the border. Without `mipmaps` every lookup is
  // bilinear at full resolution (aliasing where a pixel covers several texels), for test scenes that must look
  // as a plain ray caster's.
  Texture(const cv::Mat& bgr, const cv::Mat& alpha = cv::Mat(), bool repeat = false, bool mipmaps = true);

  int width() const { return levels_.front().cols; }
  int height() const { return levels_.front().rows; }
  bool hasAlpha() const { return !alpha_.empty(); }
  bool repeats() const { return repeat_; }
  int levelCount() const { return static_cast<int>(levels_.size()); }
  const cv::Mat& image() const { return levels_.front(); }

  // Colour (B, G, R in 0..255) at texture coordinates (s, t): s = 0..1 spans the width once, t = 0..1 the
  // height (row 0 at t = 0). lod = log2(texels per pixel); 0 or less samples the full resolution.
  cv::Vec3f sample(double s, double t, double lod) const;
  // Opacity in [0, 1] at (s, t), bilinear at full resolution; 1 when the texture has no alpha.
  float alpha(double s, double t) const;

 private:
  cv::Vec3f sampleLevel(int level, double s, double t) const;

  std::vector<cv::Mat> levels_;  // CV_8UC3, level 0 = full resolution
  cv::Mat alpha_;                // CV_8UC1 or empty
  bool repeat_;
};

// The textures of one scene; primitives refer to them by index.
class TextureBank {
 public:
  int add(Texture texture) {
    textures_.push_back(std::move(texture));
    return static_cast<int>(textures_.size()) - 1;
  }
  const Texture& operator[](int index) const { return textures_[static_cast<std::size_t>(index)]; }
  int size() const { return static_cast<int>(textures_.size()); }

 private:
  std::vector<Texture> textures_;
};

}  // namespace amos::synth
