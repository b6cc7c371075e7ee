#pragma once
// Thresholds of the descriptor searches against the map (Matching.*), shared by tracking's motion-model and
// local-map searches and by the keyframe searches of relocalisation and loop detection.

namespace amos::match {

struct MatchingOptions {
  int th_high = 100;            // max Hamming distance for projection matches
  int th_low = 50;              // max Hamming distance for brute-force matches
  float local_ratio = 0.8f;     // best / second-best on the same level (local map search)
  float brute_force_ratio = 0.7f;  // Lowe ratio for brute-force matching against a keyframe
  bool check_orientation = true;   // keep matches in the three dominant rotation bins
  void check() const;
};

}  // namespace amos::match
