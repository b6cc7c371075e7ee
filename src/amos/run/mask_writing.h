#pragma once
// Mask writing (`amos-slam run --save-masks`) as an observer: every processed frame's final dynamic mask into
// <dir>/masks/ and overlays of a few evenly spaced frames into <dir>/overlays/ (the files of report/mask_outputs.h),
// the true movers outlined when a MaskScoring looks them up.
#include <cstddef>
#include <optional>
#include <string>

#include "amos/report/mask_outputs.h"
#include "amos/run/mask_scoring.h"
#include "amos/run/run_observer.h"

namespace amos::run {

class MaskWriting : public RunObserver {
 public:
  // `truth`: the scoring observer added before this one (its frameTruth() is the frame's), or null. Not owned.
  MaskWriting(std::string dir, std::size_t overlay_count, const MaskScoring* truth);

  // Creates <dir>/masks and <dir>/overlays (throws core::Error when it cannot) for RunStart::total_frames frames.
  void onStart(const RunStart& start) override;
  void onFrame(const FrameSnapshot& frame) override;

  std::size_t masksWritten() const { return writer_ ? writer_->masksWritten() : 0; }
  std::size_t overlaysWritten() const { return writer_ ? writer_->overlaysWritten() : 0; }

 private:
  std::string dir_;
  std::size_t overlay_count_;
  const MaskScoring* truth_;
  std::optional<report::MaskOutputWriter> writer_;
};

}  // namespace amos::run
