#pragma once
// The true static surface of a synthetic sequence, for scoring a dense map (amos-slam eval-mesh): points on the
// room and furniture as the camera saw them, without the movers. For every frame_step-th frame the exact depth of
// the static layers alone (no movers, no sensor model) is back-projected from every pixel_step-th pixel with the
// true pose (T_wc, the ground truth's world frame), and one point is kept per cell-sized cube. Each point keeps the
// nearest depth it was seen from, so a scorer can limit the truth to the depth range the map fused.
// renderSequence writes it as static_surface.ply (binary little-endian PLY: float x y z, float depth).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "amos/synth/sequence.h"

namespace amos::synth {

inline constexpr const char* kStaticSurfaceFile = "static_surface.ply";

struct SurfaceSample {
  Eigen::Vector3f position = Eigen::Vector3f::Zero();  // world (ground truth frame), m
  float depth = 0;                                     // the nearest depth it was seen from, m
};

struct SurfaceSampling {
  int frame_step = 5;
  int pixel_step = 2;
  double cell = 0.01;  // m
};

std::vector<SurfaceSample> staticSurfaceSamples(const SequenceGenerator& generator, const SurfaceSampling& sampling = {});

// Throws core::Error naming the file.
void writeSurfacePly(const std::string& path, const std::vector<SurfaceSample>& samples);
std::vector<SurfaceSample> readSurfacePly(const std::string& path);

}  // namespace amos::synth
