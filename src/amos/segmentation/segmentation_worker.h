#pragma once
// Runs a Segmenter on every frame in its own thread (paper Sec. III-A: "instance segmentation using
// multi-threaded parallelism"), overlapped with the tracking thread's feature extraction:
//
//   auto pending = worker.submit(frame_id, bgr, depth);  // returns at once
//   extractOrb(gray, ...);                               // runs while the frame is segmented
//   SegmentationResult masks = pending.get();            // blocks until this frame's masks are ready
//   auto later = worker.resubmit(frame_id + 3, bgr3, depth3, pending_shared);  // the same objects, no detector
//
// Frames are segmented one after the other, in submission order, by a core::SerialExecutor; each result comes
// back through a std::future. A segmenter exception is rethrown by the future's get() in the caller's thread.
//
// Thread safety: submit() and close() may be called from any thread. The worker keeps a reference to the
// submitted images (cv::Mat is shared, not copied): do not write into them until the result has arrived.
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <future>
#include <memory>
#include <vector>

#include "amos/core/serial_executor.h"
#include "amos/core/stage_timer.h"
#include "amos/segmentation/segmenter.h"
#include "amos/segmentation/segmenter_options.h"

namespace amos::segmentation {

struct SegmentationResult {
  std::uint64_t frame_id = 0;
  std::vector<SegmentedInstance> instances;
  cv::Mat mask;          // CV_8UC1 frame, 255 = prior dynamic object, undilated (what `segment` writes)
  cv::Mat dilated_mask;  // mask grown by Segmentation.dilationSize / dilationShape (what removes keypoints)
  double segment_ms = 0;  // time spent in the segmenter and mask operations
  double segment_cpu_ms = 0;  // CPU time of the segmenting thread in them (OpenCV single-threaded: all of it)
  double latency_ms = 0;  // from submit() to the result being ready, queueing included
  bool detected = true;   // false: the objects of an earlier result masked again (Segmenter::resegment)
};

class SegmentationWorker {
 public:
  // queue_capacity: frames that may wait; submit() blocks while that many are queued (no frame is dropped).
  SegmentationWorker(std::unique_ptr<Segmenter> segmenter, MaskDilationOptions dilation,
                     std::size_t queue_capacity = 2);
  // Closes the queue, finishes the frames already queued, joins the thread.
  ~SegmentationWorker();
  SegmentationWorker(const SegmentationWorker&) = delete;
  SegmentationWorker& operator=(const SegmentationWorker&) = delete;

  // bgr: CV_8UC3; depth: CV_32F metres or empty. Throws core::Error after close().
  std::future<SegmentationResult> submit(std::uint64_t frame_id, const cv::Mat& bgr, const cv::Mat& depth = cv::Mat());
  // The same without the detector: the objects of `earlier`, an earlier submission's result, masked again on this
  // frame (Segmenter::resegment). Frames run in submission order, so `earlier` is ready when this one starts; its
  // error, if it failed, becomes this one's.
  std::future<SegmentationResult> resubmit(std::uint64_t frame_id, const cv::Mat& bgr, const cv::Mat& depth,
                                           std::shared_future<SegmentationResult> earlier);

  // Stops accepting frames; queued frames are still segmented. Idempotent.
  void close();

  const Segmenter& segmenter() const { return *segmenter_; }
  const MaskDilationOptions& dilation() const { return dilation_; }

 private:
  // submit() (`earlier` invalid) and resubmit(): queues the frame; `caller` names the public call in errors.
  std::future<SegmentationResult> enqueue(const char* caller, std::uint64_t frame_id, const cv::Mat& bgr,
                                          const cv::Mat& depth, std::shared_future<SegmentationResult> earlier);

  std::unique_ptr<Segmenter> segmenter_;
  MaskDilationOptions dilation_;
  core::SerialExecutor executor_;  // last: its thread stops before the segmenter goes away
};

// Segments one frame synchronously the way the worker does (instances, union mask, dilated mask). For tools and
// tests that do not need the thread.
SegmentationResult segmentFrame(Segmenter& segmenter, const MaskDilationOptions& dilation, std::uint64_t frame_id,
                                const cv::Mat& bgr, const cv::Mat& depth = cv::Mat());
// The same with Segmenter::resegment on the objects of `earlier`.
SegmentationResult resegmentFrame(Segmenter& segmenter, const MaskDilationOptions& dilation, std::uint64_t frame_id,
                                  const cv::Mat& bgr, const cv::Mat& depth,
                                  const std::vector<SegmentedInstance>& earlier);

}  // namespace amos::segmentation
