#include "amos/segmentation/segmenter_options.h"

#include <gtest/gtest.h>

#include <functional>

#include "amos/core/error.h"
#include "amos/segmentation/segmenter_classes.h"

namespace amos::segmentation {
namespace {

// The message of the error check() throws after `change`, or "" when it does not throw.
std::string checkError(const std::function<void(SegmenterOptions&)>& change) {
  SegmenterOptions options;
  change(options);
  try {
    options.check();
  } catch (const core::Error& e) {
    return e.what();
  }
  return "";
}

TEST(SegmenterOptions, DefaultsAreValidAndMatchThePaper) {
  SegmenterOptions options;
  EXPECT_NO_THROW(options.check());
  EXPECT_EQ(options.classes, std::vector<std::string>{"person"});
  EXPECT_EQ(options.dilation.size, 31);
  EXPECT_EQ(options.dilation.shape, "ellipse");
  EXPECT_EQ(options.input_shape, "square");
  EXPECT_EQ(options.mask_input_size, 160);
}

TEST(SegmenterOptions, ErrorsNameTheMember) {
  const std::pair<std::string, std::function<void(SegmenterOptions&)>> cases[] = {
      {"backend", [](SegmenterOptions& o) { o.backend.clear(); }},
      {"input_size", [](SegmenterOptions& o) { o.input_size = 300; }},
      {"input_shape", [](SegmenterOptions& o) { o.input_shape = "round"; }},
      {"mask_input_size", [](SegmenterOptions& o) { o.mask_input_size = 100; }},
      {"mask_input_size", [](SegmenterOptions& o) { o.mask_input_size = 288; }},
      {"score_threshold", [](SegmenterOptions& o) { o.score_threshold = 1.5f; }},
      {"nms_iou", [](SegmenterOptions& o) { o.nms_iou = 0.f; }},
      {"classes", [](SegmenterOptions& o) { o.classes = {"person", "unicorn"}; }},
      {"classes", [](SegmenterOptions& o) { o.classes.clear(); }},
      {"box_widen_x", [](SegmenterOptions& o) { o.box_widen_x = -0.1f; }},
      {"box_widen_y", [](SegmenterOptions& o) { o.box_widen_y = 2.f; }},
      {"carried_box_widen_x", [](SegmenterOptions& o) { o.carried_box_widen_x = -0.5f; }},
      {"carried_box_widen_y", [](SegmenterOptions& o) { o.carried_box_widen_y = 3.f; }},
      {"mask_threshold", [](SegmenterOptions& o) { o.mask_threshold = 1.f; }},
      {"border_crop_aspect", [](SegmenterOptions& o) { o.border_crop_aspect = -1.f; }},
      {"min_mask_fill", [](SegmenterOptions& o) { o.min_mask_fill = 1.f; }},
      {"depth_tolerance", [](SegmenterOptions& o) { o.depth_tolerance = 0.f; }},
      {"max_instances", [](SegmenterOptions& o) { o.max_instances = 0; }},
      {"threads", [](SegmenterOptions& o) { o.threads = -1; }},
      {"size", [](SegmenterOptions& o) { o.dilation.size = 30; }},
      {"shape", [](SegmenterOptions& o) { o.dilation.shape = "disc"; }},
  };
  for (const auto& [member, change] : cases) {
    const std::string message = checkError(change);
    EXPECT_EQ(message.rfind(member + " ", 0), 0u) << "expected an error naming " << member << ", got: " << message;
  }
  EXPECT_EQ(checkError([](SegmenterOptions& o) { o.dilation.size = 0; }), "");
  EXPECT_EQ(checkError([](SegmenterOptions& o) { o.classes = movableCocoClasses(); }), "");
}

TEST(SegmenterClasses, CocoTable) {
  ASSERT_EQ(cocoClassNames().size(), 80u);
  EXPECT_EQ(cocoClassId("person"), 0);
  EXPECT_EQ(cocoClassId("chair"), 56);
  EXPECT_EQ(cocoClassId("toothbrush"), 79);
  EXPECT_EQ(cocoClassName(16), "dog");
  EXPECT_EQ(cocoClassName(80), "class80");
  EXPECT_THROW(cocoClassId("Person"), core::Error);
}

}  // namespace
}  // namespace amos::segmentation
