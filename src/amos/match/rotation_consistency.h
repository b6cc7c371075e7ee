#pragma once
// Rotation consistency check of ORB-style matchers (ORB-SLAM2): between two views, the keypoint angle
// differences of correct matches agree (the in-plane rotation of the camera), so matches are voted into a
// histogram of angle differences and only those in the most populated bins are kept.
#include <vector>

namespace amos::match {

class RotationHistogram {
 public:
  // 30 bins of 12 degrees; bin b is centred on b * 12 degrees, so a small rotation (|d| < 6) falls in bin 0.
  explicit RotationHistogram(int num_bins = 30);

  // Records match `id` between keypoints with orientations angle_a_deg and angle_b_deg (degrees, any range).
  void add(int id, float angle_a_deg, float angle_b_deg);

  // Ids in the three most populated bins, in the order they were added. The second and third bins count only
  // when they hold at least 10% of the first bin's votes (ORB-SLAM2). Ties between bins: the lower bin wins.
  std::vector<int> consistent() const;
  // The other ids, in the order they were added: the matches to discard.
  std::vector<int> inconsistent() const;

  int binOf(float angle_a_deg, float angle_b_deg) const;
  int numBins() const { return num_bins_; }

 private:
  std::vector<bool> keptBins() const;

  int num_bins_;
  std::vector<int> ids_, bins_;
};

// The same check for a list of matches given by their rotation differences (degrees): `rotation_deltas[k]` belongs
// to match k; returns per match whether it is kept.
std::vector<bool> rotationConsistent(const std::vector<float>& rotation_deltas_deg);

}  // namespace amos::match
