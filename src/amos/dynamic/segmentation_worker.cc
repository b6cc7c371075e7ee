#include "amos/dynamic/segmentation_worker.h"

#include <exception>

#include "amos/core/error.h"
#include "amos/dynamic/segment_masks.h"

namespace amos::dynamic {

SegmentationResult segmentFrame(Segmenter& segmenter, const MaskDilationOptions& dilation, std::uint64_t frame_id,
                                const cv::Mat& bgr, const cv::Mat& depth) {
  core::Stopwatch watch;
  const double cpu_start = core::threadCpuMs();
  SegmentationResult result;
  result.frame_id = frame_id;
  result.instances = segmenter.segment(bgr, depth);
  result.mask = paintInstances(result.instances, bgr.size());
  result.dilated_mask = dilateMask(result.mask, dilation);
  result.segment_ms = watch.elapsedMs();
  result.segment_cpu_ms = core::threadCpuMs() - cpu_start;
  return result;
}

SegmentationWorker::SegmentationWorker(std::unique_ptr<Segmenter> segmenter, MaskDilationOptions dilation,
                                       std::size_t queue_capacity)
    : segmenter_(std::move(segmenter)), dilation_(std::move(dilation)), queue_(queue_capacity) {
  core::require(segmenter_ != nullptr, "SegmentationWorker needs a segmenter");
  dilation_.check();
  thread_ = std::thread([this] { run(); });
}

SegmentationWorker::~SegmentationWorker() {
  close();
  if (thread_.joinable()) thread_.join();
}

void SegmentationWorker::close() { queue_.close(); }

std::future<SegmentationResult> SegmentationWorker::submit(std::uint64_t frame_id, const cv::Mat& bgr,
                                                           const cv::Mat& depth) {
  core::require(!bgr.empty() && bgr.type() == CV_8UC3, "SegmentationWorker::submit: image must be CV_8UC3");
  Job job;
  job.frame_id = frame_id;
  job.bgr = bgr;
  job.depth = depth;
  std::future<SegmentationResult> future = job.promise.get_future();
  core::require(queue_.push(std::move(job)), "SegmentationWorker::submit after close()");
  return future;
}

void SegmentationWorker::run() {
  while (std::optional<Job> job = queue_.pop()) {
    try {
      SegmentationResult result = segmentFrame(*segmenter_, dilation_, job->frame_id, job->bgr, job->depth);
      result.latency_ms = job->since_submit.elapsedMs();
      job->promise.set_value(std::move(result));
    } catch (...) {
      job->promise.set_exception(std::current_exception());
    }
  }
}

}  // namespace amos::dynamic
