#pragma once
// The prior-dynamic-object segmenter interface (paper Sec. III-A: instance segmentation of people and other
// movable objects on every frame). Image in, instances out. Backends (NanoDet + person-mask network, or any
// ONNX instance segmenter a user brings) sit behind this interface and are chosen by name through
// segmenter_factory.h, so the SLAM code never names a backend.
#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace amos::segmentation {

// One detected object. `mask` covers `box` only (same size as box, CV_8UC1, 255 = object, 0 = not), so a
// frame with a few small objects does not carry several full-frame masks; segment_masks.h paints them into a
// frame.
struct SegmentedInstance {
  int class_id = -1;   // COCO class index (0 = person), see segmenter_classes.h
  float score = 0.f;   // detector confidence in [0, 1]
  cv::Rect box;        // in image pixels, clipped to the image
  cv::Mat mask;        // CV_8UC1, box.size(), undilated
};

class Segmenter {
 public:
  virtual ~Segmenter() = default;

  // bgr: CV_8UC3 image. depth: CV_32F metres (0 = no depth) of the same size, or empty; backends may use it for
  // classes without a learned mask. Not thread-safe: one call at a time (SegmentationWorker guarantees that).
  // Throws core::Error for an input it cannot handle.
  virtual std::vector<SegmentedInstance> segment(const cv::Mat& bgr, const cv::Mat& depth) = 0;

  // The objects of `earlier` (what this segmenter found on a frame a few frames before) on this frame, without
  // looking for new ones: backends with a separate detector skip it and mask each earlier box again, widened by
  // the motion a few frames allow, dropping an object whose mask comes out empty (Dynamic.Prior.detectEvery). The
  // default, for backends without that split, segments the frame anew.
  virtual std::vector<SegmentedInstance> resegment(const cv::Mat& bgr, const cv::Mat& depth,
                                                   const std::vector<SegmentedInstance>& earlier) {
    (void)earlier;
    return segment(bgr, depth);
  }

  // Backend name as used in Segmentation.backend, for logs and reports.
  virtual std::string name() const = 0;
};

}  // namespace amos::segmentation
