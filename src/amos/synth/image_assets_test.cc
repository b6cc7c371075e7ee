#include "amos/synth/image_assets.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "amos/core/error.h"
#include "amos/testing/shared_data.h"

namespace amos::synth {
namespace {

TEST(ImageAssets, CutoutsFromTheSharedPersonMasks) {
  // Two TUM fr3/walking_xyz frames: a seated man (feet at the bottom border), a standing man cut by the bottom
  // border at the thighs, and a man cut by the right border (not usable).
  AMOS_REQUIRE_DATA("person_masks");
  const std::vector<PersonCutout> cutouts = loadPersonCutouts(testing::dataPath("person_masks"));
  int sitting = 0, upper = 0;
  for (const PersonCutout& c : cutouts) {
    EXPECT_EQ(c.bgr.size(), c.alpha.size());
    EXPECT_GT(cv::countNonZero(c.alpha), 0.3 * c.alpha.total());
    sitting += c.kind == PersonCutout::Kind::kSitting;
    upper += c.kind == PersonCutout::Kind::kUpperBody;
    if (c.kind == PersonCutout::Kind::kUpperBody) {
      EXPECT_GT(c.visible_fraction, 0.4);
      EXPECT_LT(c.visible_fraction, 0.95);
    }
  }
  EXPECT_EQ(sitting, 1);
  EXPECT_EQ(upper, 1);
  EXPECT_EQ(cutouts.size(), 2u);
}

TEST(ImageAssets, BorderCutRegionsAreSkipped) {
  cv::Mat bgr(200, 300, CV_8UC3, cv::Scalar(50, 60, 70)), mask(200, 300, CV_8UC1, cv::Scalar(0));
  cv::rectangle(mask, cv::Rect(20, 30, 40, 120), cv::Scalar(255), cv::FILLED);   // whole, tall: standing
  cv::rectangle(mask, cv::Rect(100, 60, 60, 90), cv::Scalar(255), cv::FILLED);   // whole, squat: sitting
  cv::rectangle(mask, cv::Rect(200, 80, 40, 120), cv::Scalar(255), cv::FILLED);  // tall, touches the bottom
  cv::rectangle(mask, cv::Rect(270, 20, 30, 100), cv::Scalar(255), cv::FILLED);  // touches the right border
  const std::vector<PersonCutout> c = extractCutouts(bgr, mask, "synthetic");
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].kind, PersonCutout::Kind::kStanding);
  EXPECT_EQ(c[1].kind, PersonCutout::Kind::kSitting);
  EXPECT_EQ(c[2].kind, PersonCutout::Kind::kUpperBody);
}

TEST(ImageAssets, PhotosSkipDepthAndMaskFolders) {
  AMOS_REQUIRE_DATA("tum_fr1_desk_first9");
  AMOS_REQUIRE_DATA("trajectories");
  const std::vector<cv::Mat> photos = loadPhotos(testing::dataPath("tum_fr1_desk_first9"), 4);
  EXPECT_EQ(photos.size(), 4u);
  for (const cv::Mat& p : photos) EXPECT_EQ(p.type(), CV_8UC3);
  EXPECT_THROW(loadPhotos(testing::dataPath("no_such_folder")), core::Error);
  EXPECT_THROW(loadPersonCutouts(testing::dataPath("trajectories")), core::Error);
}

}  // namespace
}  // namespace amos::synth
