#include "amos/segmentation/segmenter_dnn.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <opencv2/core/utility.hpp>
#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>

#include "amos/core/error.h"
#include "amos/segmentation/model_locator.h"
#include "amos/segmentation/nanodet_decoder.h"
#include "amos/segmentation/nanodet_import_dnn.h"
#include "amos/segmentation/segment_depth_mask.h"
#include "amos/segmentation/segment_masks.h"
#include "amos/segmentation/segmenter_classes.h"
#include "amos/segmentation/segmenter_factory.h"

namespace amos::segmentation {
namespace {

constexpr int kSelfieSize = 256;
constexpr int kPersonClass = 0;
constexpr int kRegMax = 7;
// Frame size the detector is prepared and tested for at start-up (TUM and Bonn); other sizes are prepared on their
// first frame.
const cv::Size kWarmUpFrame(640, 480);
// NanoDet's input normalisation (BGR order): (x - mean) / std.
const cv::Scalar kNanoDetMean(103.53, 116.28, 123.675);
const cv::Scalar kNanoDetInvStd(1.0 / 57.375, 1.0 / 57.12, 1.0 / 58.395);

cv::dnn::Net loadOnnx(const std::string& path) {
  cv::dnn::Net net;
  try {
    net = cv::dnn::readNetFromONNX(path);
  } catch (const cv::Exception& e) {
    throw core::Error(fmt::format("cannot load segmentation model {}: not an ONNX network OpenCV {} can read "
                                  "(corrupt or truncated file?): {}",
                                  path, CV_VERSION, e.what()));
  }
  core::require(!net.empty(), fmt::format("cannot load segmentation model {}: empty network", path));
  net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  return net;
}

class NanoDetSelfieSegmenter : public Segmenter {
 public:
  explicit NanoDetSelfieSegmenter(const SegmenterOptions& options) : options_(options) {
    options_.check();
    if (options_.threads > 0) cv::setNumThreads(options_.threads);
    for (const auto& name : options_.classes) class_ids_.push_back(cocoClassId(name));
    const auto files = nanodetSelfieModelFiles(options_);
    detector_path_ = joinPath(options_.models_dir, files[0]);
    selfie_path_ = joinPath(options_.models_dir, files[1]);
    selfie_ = loadOnnx(selfie_path_);
    selfie_outputs_ = selfie_.getUnconnectedOutLayersNames();
    detectorFor(kWarmUpFrame);
    warmUp();
  }

  std::string name() const override { return "nanodet_selfie"; }

  static void requireInputs(const cv::Mat& bgr, const cv::Mat& depth) {
    core::require(!bgr.empty() && bgr.type() == CV_8UC3, "segmenter: image must be a non-empty CV_8UC3 BGR image");
    core::require(depth.empty() || (depth.type() == CV_32F && depth.size() == bgr.size()),
                  "segmenter: depth must be empty or CV_32F of the image size");
  }

  std::vector<SegmentedInstance> segment(const cv::Mat& bgr, const cv::Mat& depth) override {
    requireInputs(bgr, depth);
    std::vector<SegmentedInstance> instances;
    for (const Detection& det : detect(bgr)) {
      const cv::Rect box = toPixelRect(det.box, bgr.size());
      if (box.width < 2 || box.height < 2) continue;
      SegmentedInstance inst;
      inst.class_id = det.class_id;
      inst.score = det.score;
      inst.box = box;
      inst.mask = det.class_id == kPersonClass ? personMask(bgr, depth, box) : boxDepthMask(depth, box, options_.depth_tolerance);
      instances.push_back(std::move(inst));
    }
    return instances;
  }

  // The detector's boxes of a few frames before, grown by the motion those frames allow, masked again; a person
  // whose mask fills less than min_mask_fill of the earlier box has left it (or is hidden) and is dropped, instead
  // of getting the box + depth fallback that a fresh detection gets. The kept box is the mask's bounding box, so
  // boxes carried on over several segmentations do not keep growing.
  std::vector<SegmentedInstance> resegment(const cv::Mat& bgr, const cv::Mat& depth,
                                           const std::vector<SegmentedInstance>& earlier) override {
    requireInputs(bgr, depth);
    std::vector<SegmentedInstance> instances;
    for (const SegmentedInstance& before : earlier) {
      SegmentedInstance inst = before;
      if (before.class_id != kPersonClass) {
        inst.box = before.box & cv::Rect(cv::Point(0, 0), bgr.size());
        if (inst.box.width < 2 || inst.box.height < 2) continue;
        inst.mask = boxDepthMask(depth, inst.box, options_.depth_tolerance);
        instances.push_back(std::move(inst));
        continue;
      }
      const cv::Rect grown = widenBox(before.box, options_.carried_box_widen_x, options_.carried_box_widen_y, bgr.size());
      if (grown.width < 2 || grown.height < 2) continue;
      const cv::Mat mask = learnedPersonMask(bgr, grown);
      if (cv::countNonZero(mask) < std::max(1.0, static_cast<double>(options_.min_mask_fill) * before.box.area())) continue;
      const cv::Rect tight = cv::boundingRect(mask);
      inst.box = tight + grown.tl();
      inst.mask = mask(tight).clone();
      instances.push_back(std::move(inst));
    }
    return instances;
  }

 private:
  // The detector for frames of `image_size` (its input shape depends on the frame's when input_shape is "frame"):
  // imported on the first frame of a new size, kept for the following ones.
  struct Detector {
    cv::Size image_size, input_size;
    cv::dnn::Net net;
    std::vector<std::string> outputs;
  };

  Detector& detectorFor(cv::Size image_size) {
    if (detector_ && detector_->image_size == image_size) return *detector_;
    Detector d;
    d.image_size = image_size;
    d.input_size = detectorInputSize(image_size, options_.input_size, options_.input_shape == "square");
    NanoDetImport import = loadNanoDet(detector_path_, options_.input_size, d.input_size);
    d.net = std::move(import.net);
    d.outputs = d.net.getUnconnectedOutLayersNames();
    spdlog::debug("segmenter: NanoDet {} on {}x{} input for {}x{} frames ({} reshapes adapted, {} block transposes)",
                  detector_path_, d.input_size.width, d.input_size.height, image_size.width, image_size.height,
                  import.reshapes_adapted, import.block_transposes);
    detector_ = std::move(d);
    return *detector_;
  }

  std::vector<Detection> detect(const cv::Mat& bgr) {
    Detector& detector = detectorFor(bgr.size());
    const Letterbox lb = makeLetterbox(bgr.size(), detector.input_size);
    // (x - mean) / std per channel: blobFromImage subtracts the mean while it converts to planar float, the
    // division is one pass per plane of the blob.
    cv::Mat blob = cv::dnn::blobFromImage(applyLetterbox(bgr, lb), 1.0, cv::Size(), kNanoDetMean, /*swapRB=*/false,
                                          /*crop=*/false, CV_32F);
    const int plane = lb.input.width * lb.input.height;
    for (int c = 0; c < 3; ++c) {
      cv::Mat channel(1, plane, CV_32F, blob.ptr<float>(0, c));
      channel *= kNanoDetInvStd[c];
    }
    detector.net.setInput(blob);
    std::vector<cv::Mat> outputs;
    detector.net.forward(outputs, detector.outputs);
    const auto heads = nanodetHeadsFromOutputs(outputs, lb.input, kRegMax);
    auto detections = nmsPerClass(decodeNanoDet(heads, class_ids_, options_.score_threshold, kRegMax), options_.nms_iou);
    if (detections.size() > static_cast<std::size_t>(options_.max_instances))
      detections.resize(static_cast<std::size_t>(options_.max_instances));
    for (auto& d : detections) d.box = unletterboxBox(d.box, lb, bgr.size());
    return detections;
  }

  static cv::Rect toPixelRect(const cv::Rect2f& box, cv::Size size) {
    const int x0 = static_cast<int>(std::floor(box.x)), y0 = static_cast<int>(std::floor(box.y));
    const int x1 = static_cast<int>(std::ceil(box.x + box.width)), y1 = static_cast<int>(std::ceil(box.y + box.height));
    return cv::Rect(cv::Point(x0, y0), cv::Point(x1, y1)) & cv::Rect(cv::Point(0, 0), size);
  }

  // Widened crop squashed to the selfie input (letterboxing was worse, see the models' README), probability
  // pasted back inside the detector's box. Crops of people cut by a side border are first extended beyond it
  // (mirrored) so they are not squashed into a sliver; a mask that stays nearly empty falls back to box + depth.
  cv::Mat personMask(const cv::Mat& bgr, const cv::Mat& depth, const cv::Rect& box) {
    cv::Mat mask = learnedPersonMask(bgr, box);
    if (cv::countNonZero(mask) < options_.min_mask_fill * box.area())
      mask = boxDepthMask(depth, box, options_.depth_tolerance);
    return mask;
  }

  // The mask network's person pixels inside `box` (box-sized CV_8UC1 0/255).
  cv::Mat learnedPersonMask(const cv::Mat& bgr, const cv::Rect& box) {
    const cv::Rect crop = extendBorderCrop(box, widenBox(box, options_.box_widen_x, options_.box_widen_y, bgr.size()),
                                           bgr.size(), options_.border_crop_aspect);
    return pasteProbabilityMask(runSelfie(imagePatch(bgr, crop)), crop, box, options_.mask_threshold);
  }

  cv::Mat runSelfie(const cv::Mat& crop) {
    const int side = options_.mask_input_size;
    selfie_.setInput(cv::dnn::blobFromImage(crop, 1.0 / 255.0, cv::Size(side, side), cv::Scalar(),
                                            /*swapRB=*/true, /*crop=*/false));
    std::vector<cv::Mat> outputs;
    selfie_.forward(outputs, selfie_outputs_);
    core::require(outputs.size() == 1 && outputs[0].total() == static_cast<std::size_t>(side * side),
                  fmt::format("segmentation model {} gives {} outputs of {} values, expected one 1x1x{}x{} map",
                              selfie_path_, outputs.size(), outputs.empty() ? 0 : outputs[0].total(), side, side));
    return cv::Mat(side, side, CV_32F, outputs[0].ptr<float>()).clone();
  }

  // One pass of each network on a blank image: checks the outputs have the expected shapes and pays the first
  // inference's set-up cost before the first real frame.
  void warmUp() {
    try {
      detect(cv::Mat(kWarmUpFrame, CV_8UC3, cv::Scalar::all(0)));
    } catch (const cv::Exception& e) {
      throw core::Error(fmt::format("segmentation model {} fails on a test input: {}", detector_path_, e.what()));
    } catch (const core::Error& e) {
      throw core::Error(fmt::format("segmentation model {} is not a NanoDet-m {}x{} export (or cannot run on the "
                                    "{} input shape; try Segmentation.inputShape: square): {}",
                                    detector_path_, options_.input_size, options_.input_size, options_.input_shape,
                                    e.what()));
    }
    try {
      runSelfie(cv::Mat(kSelfieSize, kSelfieSize, CV_8UC3, cv::Scalar::all(0)));
    } catch (const cv::Exception& e) {
      throw core::Error(fmt::format("segmentation model {} fails on a test input: {}", selfie_path_, e.what()));
    }
  }

  SegmenterOptions options_;
  std::vector<int> class_ids_;
  std::string detector_path_, selfie_path_;
  std::optional<Detector> detector_;
  cv::dnn::Net selfie_;
  std::vector<std::string> selfie_outputs_;
};

}  // namespace

std::vector<std::string> nanodetSelfieModelFiles(const SegmenterOptions& options) {
  return {fmt::format("nanodet_m_{}.onnx", options.input_size), "selfie_seg_256.onnx"};
}

std::unique_ptr<Segmenter> makeNanoDetSelfieSegmenter(const SegmenterOptions& options) {
  return std::make_unique<NanoDetSelfieSegmenter>(options);
}

void addDnnSegmenterBackends(SegmenterFactory& factory) {
  factory.add("nanodet_selfie", {"NanoDet-m boxes + MediaPipe selfie person masks (OpenCV dnn, CPU)",
                                 nanodetSelfieModelFiles, makeNanoDetSelfieSegmenter});
}

}  // namespace amos::segmentation
