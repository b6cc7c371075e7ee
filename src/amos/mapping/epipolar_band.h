#pragma once
// The epipolar search of new points (new_points.cc) compares each free keypoint of a keyframe with the free
// keypoints of a neighbour that lie near its epipolar line a u + b v + c = 0 in the neighbour's image: within the
// chi-square bound of the keypoint's octave, (a u + b v + c)^2 / (a^2 + b^2) < bound. Testing every keypoint costs
// ~10^6 pairs per neighbour. Here the keypoints are filed in strips, rows sorted by u and columns sorted by v: a
// line steeper than 45 degrees crosses each row strip within an interval of u found by binary search (a flatter
// one each column strip within an interval of v), and only the keypoints there get the same exact test, so the
// result is the brute force's.
#include <vector>

namespace amos::mapping {

struct BandPoint {
  double u = 0, v = 0;
  double max_distance2 = 0;  // the exact test: (a u + b v + c)^2 / (a^2 + b^2) < max_distance2
};

class EpipolarBand {
 public:
  static constexpr double kStripPixels = 32;

  explicit EpipolarBand(std::vector<BandPoint> points);

  // Slots (indices into the constructor's points) with (a u + b v + c)^2 / (a^2 + b^2) < max_distance2, in
  // ascending order; `out` is cleared first. Nothing when a = b = 0 (den <= 0).
  void near(double a, double b, double c, std::vector<int>& out) const;

  const std::vector<BandPoint>& points() const { return points_; }

 private:
  // Points grouped by strip across one axis and sorted along the other ("along").
  struct Strip {
    double across_min, across_max;  // the span of its points across the strip
    int begin, end;                 // its entries in along_ / slots_
  };
  struct Strips {
    std::vector<Strip> strips;
    std::vector<double> along;  // per entry: the coordinate along the strip, ascending within a strip
    std::vector<int> slots;     // per entry: the point
  };
  static Strips makeStrips(const std::vector<BandPoint>& points, bool rows);
  // Points of `strips` whose line value |along_coef x + across_coef y + c| may be within the band, exact-tested.
  void search(const Strips& strips, double along_coef, double across_coef, double a, double b, double c,
              std::vector<int>& out) const;

  std::vector<BandPoint> points_;
  Strips rows_, cols_;  // rows: across = v, along = u; columns: across = u, along = v
  double max_distance2_ = 0;
};

}  // namespace amos::mapping
