#pragma once
// Stage B's person masks (Dynamic.Prior.*, dynamic/prior_propagation.h): frame k is served by the network's
// segmentation of frame baseFor(k), as segmented when that is frame k itself (the paper's way), else carried to
// frame k by the motion of the LK tracks inside each person over the frames in between (NGD-SLAM's mask
// prediction). The carrier keeps those frames' tracks, so that a segmentation that arrives `lag` frames late is
// carried over them first.
//
//   PersonMaskCarrier carrier(dilation, schedule);
//   for each frame k, in order:
//     const FrameNumber base = schedule.baseFor(k);
//     if (carrier.startsFrom(base)) ... wait for the segmentation of `base` ...
//     auto [mask, dilated] = carrier.masksFor(k, segmentation_of_base, dynamic::FrameFlow{tracks_of_k});
//
// A live source must not stall on the network: when the segmentation of `base` is not ready yet, carryOn() carries
// the current masks one frame further instead (at most one interval beyond the schedule's oldest, canCarry()), and
// the late segmentation is taken, carried over the frames since, by the first frame that finds it ready.
#include <opencv2/core.hpp>

#include <cstddef>
#include <deque>
#include <optional>
#include <utility>

#include "amos/dynamic/prior_propagation.h"
#include "amos/segmentation/segmentation_worker.h"
#include "amos/system/frame_slot.h"

namespace amos::system {

class PersonMaskCarrier {
 public:
  PersonMaskCarrier(segmentation::MaskDilationOptions dilation, dynamic::PriorScheduleOptions schedule);

  // Whether masksFor() of a frame served by `base` starts from that segmentation afresh (it has not been taken
  // yet), i.e. whether the caller must wait for it.
  bool startsFrom(FrameNumber base) const { return !propagator_ || base_ != base; }

  struct Masks {
    cv::Mat mask;     // CV_8UC1, 255 = person, undilated
    cv::Mat dilated;  // what removes keypoints
  };
  // Frame `number`'s masks. `base_result`: the segmentation of schedule.baseFor(number); `flow`: the tracks from
  // the previous frame into this one (empty when there are none). Frames come in order.
  Masks masksFor(FrameNumber number, const segmentation::SegmentationResult& base_result, dynamic::FrameFlow flow);

  // Whether frame `number` may still be served by the segmentation the masks were last started from: the masks
  // would be at most interval + lag - 1 + interval frames old (one period later than the schedule ever carries).
  bool canCarry(FrameNumber number) const { return propagator_ && number <= base_ + maxAge(); }
  // Frame `number`'s masks carried on from the last segmentation taken, while a newer one is late (canCarry()).
  Masks carryOn(FrameNumber number, dynamic::FrameFlow flow);

 private:
  FrameNumber maxAge() const { return static_cast<FrameNumber>(2 * schedule_.interval + schedule_.lag - 1); }
  void remember(FrameNumber number, dynamic::FrameFlow flow);

  segmentation::MaskDilationOptions dilation_;
  dynamic::PriorScheduleOptions schedule_;
  std::optional<dynamic::PriorMaskPropagator> propagator_;  // created on the first segmentation (its image size)
  FrameNumber base_ = 0;                                    // the segmentation the propagator started from
  std::deque<std::pair<FrameNumber, dynamic::FrameFlow>> flows_;  // the recent frames' tracks, oldest first
};

}  // namespace amos::system
