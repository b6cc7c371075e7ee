#pragma once
// The epipolar search of new points (new_points.cc) compares each free keypoint of a keyframe with the free
// keypoints of a neighbour that lie near its epipolar line a u + b v + c = 0 in the neighbour's image: within the
// chi-square bound of the keypoint's octave, (a u + b v + c)^2 / (a^2 + b^2) < bound. Testing every keypoint costs
// ~10^6 pairs per neighbour; here the keypoints are filed in coarse cells with the box they span, and only the
// cells the widest band crosses are tested, with the same exact test, so the result is the brute force's.
#include <vector>

namespace amos::mapping {

struct BandPoint {
  double u = 0, v = 0;
  double max_distance2 = 0;  // the exact test: (a u + b v + c)^2 / (a^2 + b^2) < max_distance2
};

class EpipolarBand {
 public:
  static constexpr double kCellPixels = 32;

  explicit EpipolarBand(std::vector<BandPoint> points);

  // Slots (indices into the constructor's points) with (a u + b v + c)^2 / (a^2 + b^2) < max_distance2, in
  // ascending order; `out` is cleared first. Nothing when a = b = 0 (den <= 0).
  void near(double a, double b, double c, std::vector<int>& out) const;

 private:
  struct Cell {
    double centre_u, centre_v, half_u, half_v;  // the box the cell's points span
    int begin, end;                              // its slots in slots_
  };
  std::vector<BandPoint> points_;
  std::vector<Cell> cells_;  // non-empty cells only
  std::vector<int> slots_;   // grouped by cell, ascending within a cell
  double max_distance2_ = 0;
};

}  // namespace amos::mapping
