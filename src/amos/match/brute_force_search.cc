#include "amos/match/brute_force_search.h"

#include "amos/feature/descriptor_distance.h"
#include "amos/match/rotation_consistency.h"

namespace amos::match {

std::vector<map::MapPointPtr> matchFrameToKeyFrame(const map::Frame& frame, const map::KeyFrame& kf, float ratio,
                                                   const MatchingOptions& options, int* num_matches) {
  std::vector<map::MapPointPtr> out(frame.size());
  std::vector<int> kf_index;
  for (int i = 0; i < kf.size(); ++i) {
    const map::MapPointPtr& p = kf.mapPoint(i);
    if (p && !p->isBad()) kf_index.push_back(i);
  }
  int n = 0;
  if (!kf_index.empty() && frame.size() > 0) {
    cv::Mat train(static_cast<int>(kf_index.size()), 32, CV_8U);
    for (std::size_t k = 0; k < kf_index.size(); ++k) {
      kf.features().descriptors.row(kf_index[k]).copyTo(train.row(static_cast<int>(k)));
    }
    const auto matches = feature::matchBruteForce(frame.features->descriptors, train, options.th_low, ratio);
    std::vector<int> q;
    std::vector<float> rot;
    for (const auto& m : matches) {
      const int ki = kf_index[m.train];
      q.push_back(m.query);
      rot.push_back(kf.features().keys[ki].angle - frame.features->keys[m.query].angle);
    }
    const std::vector<bool> keep =
        options.check_orientation ? rotationConsistent(rot) : std::vector<bool>(q.size(), true);
    for (std::size_t k = 0; k < matches.size(); ++k) {
      if (!keep[k]) continue;
      out[q[k]] = kf.mapPoint(kf_index[matches[k].train]);
      ++n;
    }
  }
  if (num_matches) *num_matches = n;
  return out;
}

}  // namespace amos::match
