#pragma once
// Person masks between segmentations (issue 12): the segmentation network runs on every Nth frame only, and the
// instances it found are carried to the frames in between by the motion of the LK tracks that lie inside each of
// them, as NGD-SLAM's mask prediction does. The paper (Sec. III-A) segments every frame; with
// PriorScheduleOptions::interval = 1 and lag = 0 this class is never asked to move a mask and the pipeline is the
// paper's.
//
// Why a per-instance translation: between two frames 33 ms apart a walking person's silhouette moves a few to
// ~20 px and changes its shape by much less than the 15 px that the mask dilation (Segmentation.dilationSize 31)
// adds on every side; a median of the tracks inside the instance follows the body and ignores the few tracks that
// slip onto the background at its outline.
#include <opencv2/core.hpp>

#include <cstddef>
#include <vector>

#include "amos/dynamic/corner_tracking.h"
#include "amos/segmentation/segmenter.h"
#include "amos/segmentation/segmenter_options.h"

namespace amos::dynamic {

// When the network runs and when its masks are used (Dynamic.Prior.*).
struct PriorScheduleOptions {
  // Dynamic.Prior.interval: the network segments every interval-th processed frame; 1 = every frame (the paper).
  // 3: NanoDet + the person-mask net cost ~50 ms CPU per run on this CPU, a third of that per frame fits a 30 Hz
  // budget on 2 cores; the masks are then carried over at most interval + lag - 1 = 4 frames (133 ms).
  int interval = 3;
  // Dynamic.Prior.lag: a segmentation of frame j is used from frame j + lag on, so that the network has lag
  // frame periods to finish while tracking goes on (0 = wait for this frame's segmentation, the paper's way).
  // 2 frames = 67 ms: a run takes ~50 ms CPU on a core it shares with the other workers.
  int lag = 2;
  // Dynamic.Prior.detectEvery: the person detector runs on every detectEvery-th segmentation; the ones between
  // mask the people of the last detection again (their boxes widened by Segmentation.carriedBoxWiden*), so only
  // the mask network runs. 1 = every segmentation detects (default). 2 saves about a third of the segmentation CPU
  // and the masks on carried boxes match the detector's, but a person who enters the view is found only by the next
  // detection, up to interval * detectEvery + lag = 8 frames later instead of 5, which costs accuracy in a crowd
  // (docs/experiments/front-end-defaults.md). For CPUs too slow for 1.
  int detect_every = 1;
  // Dynamic.Prior.minTracks: tracks inside an instance needed to measure its motion; with fewer, the instance
  // keeps its last motion (people do not stop within a frame). 3: a median of three is robust to one bad track.
  int min_tracks = 3;
  // Dynamic.Prior.holdMissed: segmentations an instance is kept (and carried on) for when the network no longer
  // finds it: detectors flicker on people who are small, cut by the border or partly hidden, and a person missed
  // by one segmentation would otherwise leave the mask for interval frames. 1 = one period (3 frames at the
  // default interval); a person who really left the view then masks a little static background for 100 ms.
  int hold_missed = 1;
  // Dynamic.Prior.liveWait: whether a paced or live source (--realtime, a camera) waits for a segmentation that is
  // late, as a folder run does (which keeps --deterministic runs exact). 0 (default): it does not while the masks
  // can be carried on, at most one interval longer (system::PersonMaskCarrier::carryOn): a live pose should not wait
  // for the network, and the tracks carry the masks with an IoU of ~0.8 over the schedule's 4 frames.
  bool live_wait = false;
  // Dynamic.Prior.auditPredictions: also segment every frame and record how well the carried masks match what
  // the network finds on that frame (IoU; costs the literal every-frame segmentation). For measurement only.
  bool audit_predictions = false;
  void check() const;

  // The processed frame whose segmentation serves frame `frame` (counted from 0 over the processed frames): the
  // newest scheduled one that is at least `lag` frames old; frame 0's for the first frames.
  std::size_t baseFor(std::size_t frame) const;
  bool isScheduled(std::size_t frame) const { return frame % static_cast<std::size_t>(interval) == 0; }
  // Whether the segmentation of a scheduled frame runs the detector (otherwise it masks the last one's people).
  bool detects(std::size_t frame) const {
    return isScheduled(frame) && (frame / static_cast<std::size_t>(interval)) % static_cast<std::size_t>(detect_every) == 0;
  }
};

// One frame's motion from the previous frame: LK tracks (last = previous frame, current = this frame).
struct FrameFlow {
  std::vector<PointTrack> tracks;
};

class PriorMaskPropagator {
 public:
  PriorMaskPropagator(cv::Size image_size, segmentation::MaskDilationOptions dilation, PriorScheduleOptions options);

  // Starts again from a fresh segmentation of an earlier (or this) frame; instances carried so far that overlap
  // none of the new ones are kept for PriorScheduleOptions::hold_missed segmentations.
  void reset(const std::vector<segmentation::SegmentedInstance>& instances);
  // Moves every instance by the motion of the tracks that start inside it.
  void step(const FrameFlow& flow);

  // Union of the moved instances (CV_8UC1, 255 = prior object, undilated) and the same grown by the dilation.
  cv::Mat mask() const;
  cv::Mat dilatedMask() const;
  std::size_t instanceCount() const { return instances_.size(); }
  // Frames moved since the last reset.
  int age() const { return age_; }

 private:
  struct Moving {
    segmentation::SegmentedInstance instance;  // as segmented
    cv::Mat dilated;                           // instance.mask grown by the dilation, in `dilated_box`
    cv::Rect dilated_box;                      // instance.box grown by the kernel's half size on each side
    cv::Point2f offset{0, 0};                  // accumulated motion since segmentation [px]
    cv::Point2f velocity{0, 0};                // last measured motion per frame [px]
    int missed = 0;                            // segmentations since the network last found it
  };
  bool inside(const Moving& m, const cv::Point2f& p) const;
  cv::Mat paint(bool dilated) const;

  cv::Size size_;
  segmentation::MaskDilationOptions dilation_;
  PriorScheduleOptions options_;
  std::vector<Moving> instances_;
  int age_ = 0;
};

}  // namespace amos::dynamic
