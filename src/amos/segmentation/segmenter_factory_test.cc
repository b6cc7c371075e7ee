#include "amos/segmentation/segmenter_factory.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "amos/core/error.h"
#include "amos/testing/scratch_dir.h"

namespace amos::segmentation {
namespace {

// What a user-supplied backend looks like: it declares its model files and loads them in create().
class BoxOnlySegmenter : public Segmenter {
 public:
  explicit BoxOnlySegmenter(std::string model) : model_(std::move(model)) {}
  std::vector<SegmentedInstance> segment(const cv::Mat& bgr, const cv::Mat&) override {
    return {{0, 1.f, cv::Rect(0, 0, bgr.cols / 2, bgr.rows), cv::Mat(bgr.rows, bgr.cols / 2, CV_8UC1, cv::Scalar(255))}};
  }
  std::string name() const override { return "box_only:" + model_; }

 private:
  std::string model_;
};

SegmenterBackend boxOnlyBackend() {
  return {"test backend", [](const SegmenterOptions& o) { return std::vector<std::string>{"box_only.onnx"}; },
          [](const SegmenterOptions& o) -> std::unique_ptr<Segmenter> {
            return std::make_unique<BoxOnlySegmenter>(joinPath(o.models_dir, "box_only.onnx"));
          }};
}

TEST(SegmenterFactory, AnotherBackendFitsWithoutTouchingCallers) {
  namespace fs = std::filesystem;
  const fs::path dir = testing::scratchDirForThisTest("amos_factory_");
  std::ofstream(dir / "box_only.onnx") << "weights";

  SegmenterFactory factory = builtinSegmenterFactory();
  factory.add("box_only", boxOnlyBackend());
  SegmenterOptions options;
  options.backend = "box_only";
  ModelSources sources;
  sources.cli_dir = dir.string();
  auto segmenter = createSegmenter(options, sources, factory);
  EXPECT_EQ(segmenter->name(), "box_only:" + (dir / "box_only.onnx").string());
  EXPECT_EQ(segmenter->segment(cv::Mat(10, 20, CV_8UC3), cv::Mat()).size(), 1u);

  // The settings file's Segmentation.modelsDir is used when there is no --models.
  options.models_dir = dir.string();
  EXPECT_NO_THROW(createSegmenter(options, ModelSources{}, factory));
}

TEST(SegmenterFactory, ErrorsNameTheBackend) {
  SegmenterFactory factory;
  SegmenterOptions options;
  options.backend = "yolact";
  options.models_dir = "/nowhere";
  try {
    factory.create(options);
    FAIL() << "no error for a factory without backends";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("AMOS_WITH_DNN"), std::string::npos) << e.what();
  }
  factory.add("box_only", boxOnlyBackend());
  try {
    factory.create(options);
    FAIL() << "no error for an unknown backend";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("Segmentation.backend 'yolact' is unknown; available: box_only"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(factory.add("box_only", boxOnlyBackend()), core::Error);
  EXPECT_THROW(factory.add("incomplete", SegmenterBackend{}), core::Error);
}

TEST(SegmenterFactory, BuiltinBackendsFollowTheBuildOption) {
#ifdef AMOS_WITH_DNN
  EXPECT_TRUE(builtinSegmenterFactory().has("nanodet_selfie"));
#else
  EXPECT_TRUE(builtinSegmenterFactory().names().empty());
#endif
}

}  // namespace
}  // namespace amos::segmentation
