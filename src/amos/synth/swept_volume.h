#pragma once
// The volume the movers swept (issue 43): the cells of a regular voxel grid that some mover occupied at some
// instant of a sequence, for scoring a dense map's ghosts (amos-slam eval-mesh: what of the reconstruction lies
// where people and objects were, and off the static surface).
//
// A cell is marked when its centre lies within half a cell of what a mover occupies, so nothing at least as thin as
// a cell slips between the centres:
//   - solids by their inside: spheres, capped cylinders, and boxes (SceneGeometry::addBox: six consecutive
//     back-culled quads, taken as the intersection of their faces' back half-spaces);
//   - open surfaces (quads that are not faces of a box, e.g. a cut-out person's billboard, whose transparent
//     margins are marked too; uncapped cylinders) by the surface thickened by `open_margin` on each side.
// Instants: every rendered frame's time (and the depth image's time when the sensor shifts it), and between two of
// them as many evenly spaced instants as it takes that no defining point of the geometry (quad corners, cylinder
// ends, sphere centres) moves farther than `max_step` between two: a walker (1 m/s, 3-4 cm per frame, feet and
// hands twice that) leaves a gap-free trail.
// renderSequence writes it as swept_volume.ply: binary little-endian PLY of the marked cells' centres (float
// x y z, ground truth frame), the cell size in a `comment swept_volume cell <metres>` line. A sequence without
// movers writes an empty volume.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <unordered_set>
#include <vector>

#include "amos/synth/scene.h"

namespace amos::synth {

class SequenceGenerator;

inline constexpr const char* kSweptVolumeFile = "swept_volume.ply";

struct SweptVolumeOptions {
  // 2 cm: the dense map's voxel (Dense.voxelSize) and the tolerance; finer cells would resolve what the
  // reconstruction cannot, coarser ones would over-mark by up to half a cell around every mover.
  double cell = 0.02;         // m
  double open_margin = 0.01;  // m each side of an open surface, beyond half a cell
  double max_step = 0.02;     // m: no defining point moves farther between two sampled instants (= a cell)
  int max_substeps = 64;      // per frame interval, when the geometry's structure changes (no displacement known)
  void check() const;         // throws core::Error naming the bad field
};

class SweptVolume {
 public:
  explicit SweptVolume(double cell = 0.02);
  double cell() const { return cell_; }
  std::size_t size() const { return cells_.size(); }
  bool empty() const { return cells_.empty(); }
  double volumeM3() const { return static_cast<double>(size()) * cell_ * cell_ * cell_; }

  // Marks the cells the geometry occupies (see the file comment).
  void mark(const SceneGeometry& geometry, double open_margin);
  // Marks the cell holding p.
  void markPoint(const Eigen::Vector3d& p);
  bool containsPoint(const Eigen::Vector3d& p) const;
  // Distance from p to the nearest marked cell (a cube; 0 inside one), or +infinity when none lies within
  // max_distance.
  double distanceTo(const Eigen::Vector3d& p, double max_distance) const;
  // Centres of the marked cells, in a fixed order (by cell index).
  std::vector<Eigen::Vector3f> centres() const;

 private:
  std::uint64_t keyOf(long i, long j, long k) const;
  bool marked(long i, long j, long k) const { return cells_.count(keyOf(i, j, k)) > 0; }
  template <typename Inside>
  void markBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const Inside& inside);

  double cell_;
  std::unordered_set<std::uint64_t> cells_;
};

// The geometry of the movers at time t (seconds since the first frame).
using GeometryAt = std::function<SceneGeometry(double t)>;

// Marks the geometry at every time of `times` (ascending) and at sub-steps between them (see the file comment).
SweptVolume sweep(const GeometryAt& geometry_at, const std::vector<double>& times, const SweptVolumeOptions& options);

// The sequence's movers over every rendered frame. Cut-outs turn towards the camera of the nearest frame.
SweptVolume sweptVolumeOf(const SequenceGenerator& generator, const SweptVolumeOptions& options = {});

// Throws core::Error naming the file.
void writeSweptVolumePly(const std::string& path, const SweptVolume& volume);
SweptVolume readSweptVolumePly(const std::string& path);

}  // namespace amos::synth
