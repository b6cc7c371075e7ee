#pragma once
// `run --dense`: the dense static map (dense/dense_mapper.h) as a run observer (run_observer.h). onStart makes the
// DenseMapper for the run's camera; onFrame hands every tracked frame (its depth, colour, dynamic mask and tracking
// pose; shared pixels, nothing copied) to the fusion thread and returns at once; onStreamEnd lets the fusion thread
// finish what is queued. The final map is an optional stage that the program runs once the run's main outputs are
// on disk (finishMap): it fuses the map with the final trajectory, writes each of its files on its own
// (dense/dense_map_files.h; one that fails leaves the others) and adds the "dense" section to stats.json. In mode
// none the dynamic mask is empty: everything is fused, movers included (the reference the masks are judged
// against).
// Built with the dense module (Open3D): an optional source of the run module.
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "amos/dense/dense_mapper.h"
#include "amos/report/run_report.h"
#include "amos/run/run_observer.h"

namespace amos::run {

class DenseObserver : public RunObserver {
 public:
  // `on_live_cloud` (may be empty): called in the fusion thread with the live volume's surface, at most every
  // Dense.livePeriod seconds (for the live viewer).
  DenseObserver(const dense::DenseOptions& options, std::string output_dir,
                dense::LiveCloudCallback on_live_cloud = {});
  ~DenseObserver() override;

  // The files it writes into the output folder (for the run's manifest):
  //   mesh.ply            coloured triangle mesh (marching cubes of the TSDF), binary PLY, with vertex normals
  //   cloud.ply           the surface's points (the TSDF's zero crossings), coloured, binary PLY
  //   removed_points.ply  the dynamic readings left out of fusion, back-projected with their frames' final poses
  //                       and downsampled to one per voxel, coloured, binary PLY
  //   occupancy.pgm/.yaml the floor plan (ROS map_server format), when a floor was found
  static std::vector<std::string> outputNames();

  void onStart(const RunStart& start) override;
  void onFrame(const FrameSnapshot& frame) override;
  void onStreamEnd() override;

  // The final map from the frames kept, with `trajectory` (T_wc), and its files; the "dense" section of `info`
  // (with "files": name -> "written", "failed: why" or "none: why"). Abandoned, with status interrupted and no
  // file written, when *stop becomes true. Never throws: a failure is the stage's status and reason.
  report::OptionalStage finishMap(const std::vector<io::StampedPose>& trajectory, report::RunInfo& info,
                                  const std::atomic<bool>* stop = nullptr);

 private:
  // Each file on its own; name -> what became of it. `failures`: "name: why" of each that failed.
  nlohmann::json writeFiles(const dense::DenseMap& map, std::vector<std::string>& failures) const;

  dense::DenseOptions options_;
  std::string output_dir_;
  dense::LiveCloudCallback on_live_cloud_;
  std::unique_ptr<dense::DenseMapper> mapper_;
};

}  // namespace amos::run
