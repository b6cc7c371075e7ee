#pragma once
// amos::Slam's dense map (Options::dense): the tracked frames handed to a dense::DenseMapper as `amos-slam run
// --dense` hands them (run/dense_observer.h: the same frames, poses and dynamic masks), the final map fused with
// the final trajectory, converted to the public plain data (include/amos/dense_map.h). Built without Open3D, making
// one is an error saying so.
#include <memory>
#include <optional>
#include <vector>

#include "amos/config/settings.h"
#include "amos/dense_map.h"
#include "amos/io/trajectory.h"
#include "amos/system/dynamic_pipeline.h"

namespace amos::api {

class DenseFeed {
 public:
  // The settings' Dense.* section (read with settingsSections()) and camera.
  explicit DenseFeed(const config::Settings& settings);
  ~DenseFeed();
  DenseFeed(const DenseFeed&) = delete;
  DenseFeed& operator=(const DenseFeed&) = delete;

  // A processed frame: kept when it was tracked and has depth (never waits).
  void push(const system::ProcessedFrame& out);
  // Fuses what is queued and stops the fusion thread.
  void finish();
  // The final map from the kept frames with `trajectory` (T_wc). After finish().
  DenseMap fuse(const std::vector<io::StampedPose>& trajectory) const;
  // The live volume's latest surface, or nullopt.
  std::optional<DenseSnapshot> snapshot() const;
  // The floor plan of the live volume's latest surface (dense::findFloor and dense::buildOccupancyGrid over it, as
  // the final fusion makes its own over the final surface), the cameras placed by `trajectory` (T_wc); nullopt
  // before the first live surface or while no floor is found.
  std::optional<OccupancyGrid> liveGrid(const std::vector<io::StampedPose>& trajectory) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace amos::api
