#pragma once
// `run --dense`: the dense static map as a run observer (run/run_observer.h). onStart makes the DenseMapper for the
// run's camera; onFrame hands every tracked frame (its depth, colour, dynamic mask and tracking pose; shared
// pixels, nothing copied) to the fusion thread and returns at once; onStreamEnd lets the fusion thread finish what
// is queued; addToInfo fuses the final map with the final trajectory, writes its files (dense_outputs.h) into the
// output folder and adds the "dense" section to stats.json. In mode none the dynamic mask is empty: everything is
// fused, movers included (the reference the masks are judged against).
#include <memory>
#include <string>
#include <vector>

#include "amos/dense/dense_mapper.h"
#include "amos/run/run_observer.h"

namespace amos::dense {

class DenseObserver : public run::RunObserver {
 public:
  // `on_live_cloud` (may be empty): called in the fusion thread with the live volume's surface, at most every
  // Dense.livePeriod seconds (for the live viewer).
  DenseObserver(const DenseOptions& options, std::string output_dir, LiveCloudCallback on_live_cloud = {});
  ~DenseObserver() override;

  // The files it writes into the output folder (for the run's manifest).
  static std::vector<std::string> outputNames();

  void onStart(const run::RunStart& start) override;
  void onFrame(const run::FrameSnapshot& frame) override;
  void onStreamEnd() override;
  void addToInfo(const std::vector<io::StampedPose>& trajectory, report::RunInfo& info) override;

 private:
  DenseOptions options_;
  std::string output_dir_;
  LiveCloudCallback on_live_cloud_;
  std::unique_ptr<DenseMapper> mapper_;
};

}  // namespace amos::dense
