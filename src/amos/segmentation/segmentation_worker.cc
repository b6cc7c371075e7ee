#include "amos/segmentation/segmentation_worker.h"

#include <exception>
#include <string>

#include "amos/core/error.h"
#include "amos/core/thread_priority.h"
#include "amos/segmentation/segment_masks.h"

namespace amos::segmentation {

namespace {

SegmentationResult segmentOrResegment(Segmenter& segmenter, const MaskDilationOptions& dilation,
                                      std::uint64_t frame_id, const cv::Mat& bgr, const cv::Mat& depth,
                                      const std::vector<SegmentedInstance>* earlier) {
  core::Stopwatch watch;
  const double cpu_start = core::threadCpuMs();
  SegmentationResult result;
  result.frame_id = frame_id;
  result.detected = earlier == nullptr;
  result.instances = earlier ? segmenter.resegment(bgr, depth, *earlier) : segmenter.segment(bgr, depth);
  result.mask = paintInstances(result.instances, bgr.size());
  result.dilated_mask = dilateMask(result.mask, dilation);
  result.segment_ms = watch.elapsedMs();
  result.segment_cpu_ms = core::threadCpuMs() - cpu_start;
  return result;
}

}  // namespace

SegmentationResult segmentFrame(Segmenter& segmenter, const MaskDilationOptions& dilation, std::uint64_t frame_id,
                                const cv::Mat& bgr, const cv::Mat& depth) {
  return segmentOrResegment(segmenter, dilation, frame_id, bgr, depth, nullptr);
}

SegmentationResult resegmentFrame(Segmenter& segmenter, const MaskDilationOptions& dilation, std::uint64_t frame_id,
                                  const cv::Mat& bgr, const cv::Mat& depth,
                                  const std::vector<SegmentedInstance>& earlier) {
  return segmentOrResegment(segmenter, dilation, frame_id, bgr, depth, &earlier);
}

SegmentationWorker::SegmentationWorker(std::unique_ptr<Segmenter> segmenter, MaskDilationOptions dilation,
                                       std::size_t queue_capacity)
    : segmenter_(std::move(segmenter)), dilation_(std::move(dilation)), executor_(queue_capacity) {
  // Background work: its masks are used frames later (core/thread_priority.h). The first task runs in the thread.
  executor_.submit([] { core::lowerThisThreadPriority(core::kBackgroundNice); });
  core::require(segmenter_ != nullptr, "SegmentationWorker needs a segmenter");
  dilation_.check();
}

SegmentationWorker::~SegmentationWorker() { close(); }

void SegmentationWorker::close() { executor_.close(); }

std::future<SegmentationResult> SegmentationWorker::submit(std::uint64_t frame_id, const cv::Mat& bgr,
                                                           const cv::Mat& depth) {
  return enqueue("submit", frame_id, bgr, depth, {});
}

std::future<SegmentationResult> SegmentationWorker::resubmit(std::uint64_t frame_id, const cv::Mat& bgr,
                                                             const cv::Mat& depth,
                                                             std::shared_future<SegmentationResult> earlier) {
  core::require(earlier.valid(), "SegmentationWorker::resubmit needs an earlier result");
  return enqueue("resubmit", frame_id, bgr, depth, std::move(earlier));
}

std::future<SegmentationResult> SegmentationWorker::enqueue(const char* caller, std::uint64_t frame_id,
                                                            const cv::Mat& bgr, const cv::Mat& depth,
                                                            std::shared_future<SegmentationResult> earlier) {
  core::require(!bgr.empty() && bgr.type() == CV_8UC3,
                std::string("SegmentationWorker::") + caller + ": image must be CV_8UC3");
  core::Stopwatch since_submit;
  try {
    return executor_.submit([this, frame_id, bgr, depth, earlier = std::move(earlier), since_submit] {
      SegmentationResult result =
          earlier.valid() ? resegmentFrame(*segmenter_, dilation_, frame_id, bgr, depth, earlier.get().instances)
                          : segmentFrame(*segmenter_, dilation_, frame_id, bgr, depth);
      result.latency_ms = since_submit.elapsedMs();
      return result;
    });
  } catch (const core::Error&) {
    throw core::Error(std::string("SegmentationWorker::") + caller + " after close()");
  }
}

}  // namespace amos::segmentation
