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

 private:
  segmentation::MaskDilationOptions dilation_;
  dynamic::PriorScheduleOptions schedule_;
  std::optional<dynamic::PriorMaskPropagator> propagator_;  // created on the first segmentation (its image size)
  FrameNumber base_ = 0;                                    // the segmentation the propagator started from
  std::deque<std::pair<FrameNumber, dynamic::FrameFlow>> flows_;  // the recent frames' tracks, oldest first
};

}  // namespace amos::system
