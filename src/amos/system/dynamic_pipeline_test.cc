// DynamicPipeline's two stages: stage A of frames pushed ahead runs while stage B processes the current one, and
// the results are those of the plain pipeline whatever the look-ahead.
#include "amos/system/dynamic_pipeline.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <mutex>
#include <opencv2/core/utility.hpp>
#include <set>

#include "amos/segmentation/model_locator.h"
#include "amos/segmentation/segmenter_factory.h"
#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/io/dataset.h"
#include "amos/testing/shared_data.h"
#include "amos/testing/test_camera.h"

namespace amos::system {
namespace {

const std::string kBonn = testing::dataPath("bonn_crowd_dev");

SlamOptions bonnOptions() {
  SlamOptions o;
  o.camera = testing::bonnIntrinsics();
  o.sensor.bf = 40.0;
  o.sensor.th_depth = 40.0;
  o.deterministic = true;
  return o;
}

std::vector<io::RgbdFrame> bonnFrames(std::size_t count, std::size_t first) {
  io::SequenceIndex index = io::indexSequence(kBonn);
  index.frames.erase(index.frames.begin(), index.frames.begin() + static_cast<std::ptrdiff_t>(first));
  index.frames.resize(count);
  io::SequenceReader reader(std::move(index), io::ReaderOptions{});
  std::vector<io::RgbdFrame> frames;
  while (auto f = reader.next()) frames.push_back(std::move(*f));
  return frames;
}

// The segmentation lane around `segmenter`, with the default mask dilation.
std::unique_ptr<segmentation::SegmentationWorker> workerOf(std::unique_ptr<segmentation::Segmenter> segmenter) {
  return std::make_unique<segmentation::SegmentationWorker>(std::move(segmenter), segmentation::MaskDilationOptions{});
}

std::unique_ptr<segmentation::SegmentationWorker> realSegmentation() {
  segmentation::ModelSources sources;
  sources.cli_dir = testing::modelsDir();
  sources.default_dirs.clear();
  return workerOf(
      segmentation::createSegmenter(segmentation::SegmenterOptions{}, sources, segmentation::builtinSegmenterFactory()));
}

// Mode prior with the given person-segmentation schedule.
dynamic::DynamicOptions priorOptions(int interval, int lag, int detect_every = 1) {
  dynamic::DynamicOptions options;
  options.mode = dynamic::DynamicMode::kPrior;
  options.prior.interval = interval;
  options.prior.lag = lag;
  options.prior.detect_every = detect_every;
  return options;
}

struct RunRecord {
  std::vector<cv::Mat> prior_masks, dynamic_masks;
  std::vector<core::SE3> poses;
};

// Pushes frames so that `ahead` of them wait beyond the one being processed (0 = push, process, push, ...).
template <typename OnOutput>
void feedPipeline(DynamicPipeline& pipeline, const std::vector<io::RgbdFrame>& frames, std::size_t ahead,
                  OnOutput&& on_output) {
  std::size_t pushed = 0;
  while (pushed < frames.size() || pipeline.waiting() > 0) {
    while (pushed < frames.size() && pipeline.waiting() <= ahead) pipeline.push(frames[pushed++]);
    on_output(pipeline.processNext());
  }
}

// Mode full, deterministic, over `frames`, with `ahead` frames pushed ahead of stage B.
RunRecord runPipeline(const std::vector<io::RgbdFrame>& frames, std::size_t ahead) {
  SlamSystem slam(bonnOptions());
  dynamic::DynamicOptions options;
  options.mode = dynamic::DynamicMode::kFull;
  DynamicPipeline pipeline(slam, options, realSegmentation());
  RunRecord record;
  feedPipeline(pipeline, frames, ahead, [&](const ProcessedFrame& out) {
    record.prior_masks.push_back(out.prior_mask);
    record.dynamic_masks.push_back(out.dynamic_mask);
    record.poses.push_back(out.slam.track.T_cw);
  });
  pipeline.finish();
  return record;
}

bool sameMask(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && (a.empty() || cv::norm(a, b, cv::NORM_INF) == 0);
}

// Twelve frames of Bonn crowd with people in view: the same prior masks, dynamic masks and poses, bit for bit, with
// no look-ahead, the one frame that `run` uses, and three (the stage-A tasks then wait for the hand-offs of
// frames stage B has not reached).
TEST(DynamicPipeline, LookAheadGivesTheSameMasksAndPoses) {
  AMOS_REQUIRE_DATA("bonn_crowd_dev");
  AMOS_REQUIRE_MODELS("nanodet_m_320.onnx");
  AMOS_REQUIRE_MODELS("selfie_seg_256.onnx");
  const std::vector<io::RgbdFrame> frames = bonnFrames(12, 90);
  ASSERT_EQ(frames.size(), 12u);
  const RunRecord plain = runPipeline(frames, 0);
  int with_people = 0;
  for (const std::size_t ahead : {1, 3}) {
    const RunRecord record = runPipeline(frames, ahead);
    for (std::size_t k = 0; k < frames.size(); ++k) {
      EXPECT_TRUE(sameMask(plain.prior_masks[k], record.prior_masks[k])) << "prior mask of frame " << k << ", ahead " << ahead;
      EXPECT_TRUE(sameMask(plain.dynamic_masks[k], record.dynamic_masks[k])) << "dynamic mask of frame " << k << ", ahead " << ahead;
      EXPECT_TRUE(plain.poses[k].isApprox(record.poses[k], 0.0)) << "pose of frame " << k << ", ahead " << ahead;
    }
  }
  for (const cv::Mat& mask : plain.prior_masks) with_people += cv::countNonZero(mask) > 0;
  EXPECT_GE(with_people, 10);  // the comparison is about real masks, not empty ones
}

// The depth evidence keeps the depth of the last frames as its baseline (Dynamic.Depth.baselineFrames): geometry
// mode with it processes every frame with the baseline off, shorter than the run and engaged, and gives the same
// masks with and without look-ahead.
TEST(DynamicPipeline, BaselineComparisonsAreDeterministicAndMayBeOff) {
  // The depth evidence and the long-baseline tracks (each alone: the history is kept for either) compare with the
  // frame `baseline` back, whatever the look-ahead.
  AMOS_REQUIRE_DATA("bonn_crowd_dev");
  const std::vector<io::RgbdFrame> frames = bonnFrames(8, 90);
  ASSERT_EQ(frames.size(), 8u);
  auto run = [&](int baseline_frames, std::size_t ahead, bool depth, bool tracks) {
    SlamSystem slam(bonnOptions());
    dynamic::DynamicOptions options;
    options.mode = dynamic::DynamicMode::kGeometry;
    options.depth.enabled = depth;
    options.baseline_tracks.enabled = tracks;
    options.depth.baseline_frames = baseline_frames;
    DynamicPipeline pipeline(slam, options, nullptr);
    std::vector<cv::Mat> masks;
    feedPipeline(pipeline, frames, ahead, [&](const ProcessedFrame& out) { masks.push_back(out.dynamic_mask); });
    pipeline.finish();
    return masks;
  };
  for (const int baseline : {0, 1, 3, 20})
    EXPECT_EQ(run(baseline, 0, true, false).size(), frames.size()) << "baseline " << baseline;
  for (const auto& [depth, tracks] : {std::pair{true, false}, {false, true}, {true, true}}) {
    const std::vector<cv::Mat> plain = run(3, 0, depth, tracks), ahead = run(3, 1, depth, tracks);
    int marked = 0;
    for (std::size_t k = 0; k < frames.size(); ++k) {
      EXPECT_TRUE(sameMask(plain[k], ahead[k])) << "frame " << k << " depth " << depth << " tracks " << tracks;
      marked += cv::countNonZero(plain[k]) > 0;
    }
    EXPECT_GE(marked, 1);  // people walk through these frames
  }
  // Without a history the long-baseline tracks cannot be on (DynamicOptions::check).
  SlamSystem slam(bonnOptions());
  dynamic::DynamicOptions no_history;
  no_history.baseline_tracks.enabled = true;
  no_history.depth.baseline_frames = 0;
  EXPECT_THROW(DynamicPipeline(slam, no_history, nullptr), core::InvalidOption);
}

// A segmenter that records which frames (by the code in pixel (0, 0)) it has started, so a test can wait until a
// given frame reaches it. Its masks are empty.
class RecordingSegmenter : public segmentation::Segmenter {
 public:
  struct Log {
    std::mutex mutex;
    std::condition_variable changed;
    std::set<int> started;
    std::set<int> resegmented;  // of which without the detector
  };
  explicit RecordingSegmenter(std::shared_ptr<Log> log) : log_(std::move(log)) {}
  std::vector<segmentation::SegmentedInstance> segment(const cv::Mat& bgr, const cv::Mat&) override {
    {
      std::lock_guard<std::mutex> lock(log_->mutex);
      log_->started.insert(bgr.at<cv::Vec3b>(0, 0)[0]);
    }
    log_->changed.notify_all();
    return {};
  }
  std::vector<segmentation::SegmentedInstance> resegment(const cv::Mat& bgr, const cv::Mat& depth,
                                                         const std::vector<segmentation::SegmentedInstance>&) override {
    {
      std::lock_guard<std::mutex> lock(log_->mutex);
      log_->resegmented.insert(bgr.at<cv::Vec3b>(0, 0)[0]);
    }
    return segment(bgr, depth);
  }
  std::string name() const override { return "recording"; }

 private:
  std::shared_ptr<Log> log_;
};

io::RgbdFrame codedFrame(std::size_t index) {
  io::RgbdFrame f;
  f.index = index;
  f.bgr = cv::Mat(480, 640, CV_8UC3, cv::Scalar::all(0));
  f.bgr.at<cv::Vec3b>(0, 0)[0] = static_cast<uchar>(index);
  f.depth = cv::Mat(480, 640, CV_32F, cv::Scalar(0));
  return f;
}

// push(k+1) before processNext() of frame k hands frame k+1 to the segmentation lane at once; a frame not pushed
// yet does not reach it. More than FrameScheduler::kMaxAhead waiting frames are refused.
TEST(DynamicPipeline, PushSchedulesStageAAtOnce) {
  auto log = std::make_shared<RecordingSegmenter::Log>();
  SlamSystem slam(bonnOptions());
  // The paper's schedule: every frame segmented.
  DynamicPipeline pipeline(slam, priorOptions(1, 0), workerOf(std::make_unique<RecordingSegmenter>(log)));
  EXPECT_EQ(pipeline.push(codedFrame(1)), 0u);
  EXPECT_EQ(pipeline.push(codedFrame(2)), 1u);
  EXPECT_EQ(pipeline.processNext().frame.index, 1u);
  {
    std::unique_lock<std::mutex> lock(log->mutex);
    EXPECT_TRUE(log->changed.wait_for(lock, std::chrono::seconds(5), [&] { return log->started.count(2) > 0; }))
        << "frame 2 was not submitted when it was pushed";
  }
  EXPECT_EQ(pipeline.processNext().frame.index, 2u);  // nothing pushed ahead: frame 3 is unknown
  {
    std::lock_guard<std::mutex> lock(log->mutex);
    EXPECT_EQ(log->started, (std::set<int>{1, 2}));
  }
  EXPECT_THROW(pipeline.processNext(), core::Error);  // nothing waits
  for (std::size_t code = 3; code < 3 + FrameScheduler::kMaxAhead; ++code) pipeline.push(codedFrame(code));
  EXPECT_THROW(pipeline.push(codedFrame(9)), core::Error);
  EXPECT_EQ(pipeline.waiting(), FrameScheduler::kMaxAhead);
  EXPECT_EQ(pipeline.processNext().frame.index, 3u);
  pipeline.finish();
}

// Dynamic.Prior.interval 3: the network sees processed frames 0, 3, 6, ... only (announced ones early, through the
// look-ahead), whatever their sequence index.
TEST(DynamicPipeline, SegmentsEveryIntervalthFrame) {
  auto log = std::make_shared<RecordingSegmenter::Log>();
  SlamSystem slam(bonnOptions());
  DynamicPipeline pipeline(slam, priorOptions(3, 2), workerOf(std::make_unique<RecordingSegmenter>(log)));
  std::vector<io::RgbdFrame> frames;
  for (std::size_t code = 10; code < 18; ++code) frames.push_back(codedFrame(code));
  feedPipeline(pipeline, frames, 1, [&](const ProcessedFrame& out) {
    if (out.frame.index == 12) {  // frame 3 was pushed ahead of frame 2: on its way before frame 3 is processed
      std::unique_lock<std::mutex> lock(log->mutex);
      EXPECT_TRUE(log->changed.wait_for(lock, std::chrono::seconds(5), [&] { return log->started.count(13) > 0; }));
    }
  });
  pipeline.finish();
  std::unique_lock<std::mutex> lock(log->mutex);
  log->changed.wait_for(lock, std::chrono::seconds(5), [&] { return log->started.size() >= 3; });
  EXPECT_EQ(log->started, (std::set<int>{10, 13, 16}));
}

// Dynamic.Prior.detectEvery 2: of the segmented frames 0, 3, 6, 9, 12 the detector runs on 0, 6 and 12; 3 and 9
// mask the people of the detection before them again.
TEST(DynamicPipeline, DetectsOnEveryDetectEverythSegmentation) {
  auto log = std::make_shared<RecordingSegmenter::Log>();
  SlamSystem slam(bonnOptions());
  DynamicPipeline pipeline(slam, priorOptions(3, 2, 2), workerOf(std::make_unique<RecordingSegmenter>(log)));
  std::vector<io::RgbdFrame> frames;
  for (std::size_t code = 10; code < 25; ++code) frames.push_back(codedFrame(code));
  feedPipeline(pipeline, frames, 1, [](const ProcessedFrame&) {});
  pipeline.finish();
  std::unique_lock<std::mutex> lock(log->mutex);
  log->changed.wait_for(lock, std::chrono::seconds(5), [&] { return log->started.size() >= 5; });
  EXPECT_EQ(log->started, (std::set<int>{10, 13, 16, 19, 22}));
  EXPECT_EQ(log->resegmented, (std::set<int>{13, 19}));
}

// A segmenter that reports one "person" covering the left `fraction` of every image.
class LeftBandSegmenter : public segmentation::Segmenter {
 public:
  explicit LeftBandSegmenter(double fraction) : fraction_(fraction) {}
  std::vector<segmentation::SegmentedInstance> segment(const cv::Mat& bgr, const cv::Mat&) override {
    segmentation::SegmentedInstance person;
    person.class_id = 0;
    person.score = 1.f;
    person.box = cv::Rect(0, 0, static_cast<int>(fraction_ * bgr.cols), bgr.rows);
    person.mask = cv::Mat(person.box.size(), CV_8UC1, cv::Scalar(255));
    return {person};
  }
  std::string name() const override { return "left band"; }

 private:
  double fraction_;
};

struct MaskedExtractionRun {
  int kept = 0, removed = 0;  // keypoints of the last frame outside / inside the dynamic mask
  bool map_from_first_frame = false;
};

MaskedExtractionRun runLeftBand(const std::vector<io::RgbdFrame>& frames, double fraction, bool masked) {
  SlamSystem slam(bonnOptions());
  dynamic::DynamicOptions options;
  options.mode = dynamic::DynamicMode::kPrior;
  options.prior_masked_extraction = masked;
  DynamicPipeline pipeline(slam, options, workerOf(std::make_unique<LeftBandSegmenter>(fraction)));
  MaskedExtractionRun run;
  std::size_t k = 0;
  feedPipeline(pipeline, frames, 1, [&](const ProcessedFrame& out) {
    run.kept = out.slam.keypoints;
    run.removed = out.slam.removed_dynamic;
    if (k++ == 0) run.map_from_first_frame = out.slam.track.initialized_map;
  });
  pipeline.finish();
  return run;
}

// With 70 % of the view masked, the last frame's ORB features are detected outside the previous frame's (dilated)
// mask: none is thrown away and the static part gets the whole budget. With 30 % masked (below
// priorMaskedExtractionCoverage) and a map in place, or with the option off, extraction ignores the mask and the
// mask removes them.
TEST(DynamicPipeline, MaskedExtractionPutsTheFeatureBudgetOutsideLargePriorMasks) {
  AMOS_REQUIRE_DATA("bonn_crowd_dev");
  const std::vector<io::RgbdFrame> frames = bonnFrames(4, 0);
  const MaskedExtractionRun masked = runLeftBand(frames, 0.7, true);
  const MaskedExtractionRun unmasked = runLeftBand(frames, 0.7, false);
  EXPECT_EQ(masked.removed, 0);
  EXPECT_GT(unmasked.removed, 300);
  EXPECT_GT(masked.kept, 2 * unmasked.kept) << "the budget did not move to the unmasked part";
  const MaskedExtractionRun small = runLeftBand(frames, 0.3, true);
  ASSERT_TRUE(small.map_from_first_frame);
  EXPECT_GT(small.removed, 100) << "a mask below the coverage threshold must not steer the extraction";
}

// Before the map exists the mask steers the extraction at any coverage: the frame alone must supply the points to
// start the map. Here the first two frames have no depth, so no map exists before the third frame is prepared.
TEST(DynamicPipeline, MaskedExtractionBeforeTheMapIgnoresTheCoverage) {
  AMOS_REQUIRE_DATA("bonn_crowd_dev");
  std::vector<io::RgbdFrame> frames = bonnFrames(3, 0);
  for (std::size_t k = 0; k < 2; ++k) frames[k].depth = cv::Mat(frames[k].depth.size(), CV_32F, cv::Scalar(0));
  const MaskedExtractionRun small = runLeftBand(frames, 0.3, true);
  EXPECT_FALSE(small.map_from_first_frame);
  EXPECT_EQ(small.removed, 0);
  EXPECT_GT(small.kept, 0);
}

// A failure in one of stage A's lanes (the segmentation network, the preparation) reaches stage B through the
// frame's future: processNext() of that frame throws it, the frames before it were processed, and the pipeline
// still finishes and shuts down (runSequence then ends the run with the outputs of those frames).

// A segmenter that throws on the frame coded `bad` (see codedFrame).
class FailingSegmenter : public segmentation::Segmenter {
 public:
  explicit FailingSegmenter(int bad) : bad_(bad) {}
  std::vector<segmentation::SegmentedInstance> segment(const cv::Mat& bgr, const cv::Mat&) override {
    if (bgr.at<cv::Vec3b>(0, 0)[0] == bad_)
      throw core::Error("segmenter: out of memory on frame " + std::to_string(bad_));
    return {};
  }
  std::string name() const override { return "failing"; }

 private:
  int bad_;
};

// Feeds frames 0..count-1 with one frame of look-ahead, as runSequence does; returns the frames processed before
// processNext() threw, and the error.
std::size_t feedUntilFailure(DynamicPipeline& pipeline, std::size_t count, std::string& error) {
  std::size_t pushed = 0, processed = 0;
  try {
    while (pushed < count || pipeline.waiting() > 0) {
      while (pushed < count && pipeline.waiting() < 2) pipeline.push(codedFrame(pushed++));
      pipeline.processNext();
      ++processed;
    }
  } catch (const core::Error& e) {
    error = e.what();
  }
  return processed;
}

TEST(DynamicPipelineFailure, SegmentationLaneFailureReachesItsFrame) {
  SlamSystem slam(bonnOptions());
  {
    DynamicPipeline pipeline(slam, priorOptions(1, 0), workerOf(std::make_unique<FailingSegmenter>(2)));
    std::string error;
    EXPECT_EQ(feedUntilFailure(pipeline, 6, error), 2u);
    EXPECT_NE(error.find("segmenter: out of memory on frame 2"), std::string::npos) << error;
    pipeline.finish();
  }  // the lanes stop; frame 3, pushed ahead, is dropped
  EXPECT_EQ(slam.stats().frames, 2u);
}

// A frame the preparation lane cannot handle (a grey image where colour is expected).
TEST(DynamicPipelineFailure, PreparationLaneFailureReachesItsFrame) {
  SlamSystem slam(bonnOptions());
  dynamic::DynamicOptions options;
  options.mode = dynamic::DynamicMode::kGeometry;
  {
    DynamicPipeline pipeline(slam, options, nullptr);
    std::size_t processed = 0;
    std::string error;
    try {
      for (std::size_t k = 0; k < 5; ++k) {
        io::RgbdFrame frame = codedFrame(k);
        if (k == 3) frame.bgr = cv::Mat(480, 640, CV_8UC1, cv::Scalar(0));
        pipeline.push(std::move(frame));
        if (k > 0) {
          pipeline.processNext();
          ++processed;
        }
      }
    } catch (const core::Error& e) {
      error = e.what();
    }
    EXPECT_EQ(processed, 3u);
    EXPECT_NE(error.find("CV_8UC3"), std::string::npos) << error;
    pipeline.finish();
  }
  EXPECT_EQ(slam.stats().frames, 3u);
}

}  // namespace
}  // namespace amos::system
