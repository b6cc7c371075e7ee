#include "amos/place/vocabulary.h"

#include <gtest/gtest.h>

#include <random>

#include "amos/core/error.h"
#include "amos/place/keyframe_database.h"

namespace amos::place {
namespace {

// `places` scenes of 150 random descriptors each; a view of a scene is its descriptors with `flips` random bits
// flipped per descriptor and a third of them replaced by unrelated ones.
struct Scenes {
  std::vector<cv::Mat> base;
  std::mt19937 rng{3};
  explicit Scenes(int places) {
    cv::RNG cv_rng(11);  // not cv::theRNG(): the scenes must not depend on what ran before
    for (int p = 0; p < places; ++p) {
      cv::Mat d(150, 32, CV_8U);
      cv_rng.fill(d, cv::RNG::UNIFORM, 0, 256);
      base.push_back(d);
    }
  }
  cv::Mat view(int place, int flips) {
    cv::Mat d = base[place].clone();
    std::uniform_int_distribution<int> bit(0, 255), row(0, 2);
    for (int r = 0; r < d.rows; ++r) {
      if (row(rng) == 0) {
        for (int b = 0; b < 32; ++b) d.at<std::uint8_t>(r, b) = static_cast<std::uint8_t>(bit(rng));
        continue;
      }
      for (int f = 0; f < flips; ++f) {
        const int b = bit(rng);
        d.at<std::uint8_t>(r, b / 8) ^= static_cast<std::uint8_t>(1u << (b % 8));
      }
    }
    return d;
  }
};

Vocabulary trained(Scenes& scenes) {
  std::vector<cv::Mat> training;
  for (int p = 0; p < static_cast<int>(scenes.base.size()); ++p) {
    for (int k = 0; k < 3; ++k) training.push_back(scenes.view(p, 8));
  }
  VocabularyOptions options;
  options.branching = 6;
  options.depth = 4;
  return Vocabulary::train(training, options);
}

TEST(Vocabulary, ViewsOfTheSamePlaceScoreHighestAndTheDatabaseFindsThem) {
  Scenes scenes(12);
  const auto vocabulary = std::make_shared<const Vocabulary>(trained(scenes));
  EXPECT_GT(vocabulary->numWords(), 200u);
  EXPECT_LE(vocabulary->numWords(), 6u * 6 * 6 * 6);
  KeyFrameDatabase db(vocabulary);
  for (int p = 0; p < 12; ++p) db.add(static_cast<EntryId>(100 + p), vocabulary->transform(scenes.view(p, 10)));
  EXPECT_EQ(db.size(), 12u);
  for (int p = 0; p < 12; ++p) {
    const BowVector q = vocabulary->transform(scenes.view(p, 10));
    double total = 0;
    for (const auto& [w, x] : q.words) total += x;
    EXPECT_NEAR(total, 1.0, 1e-5);
    EXPECT_NEAR(similarity(q, q), 1.0, 1e-5);
    const std::vector<PlaceMatch> found = db.query(q, 0.0);
    ASSERT_FALSE(found.empty());
    EXPECT_EQ(found[0].id, static_cast<EntryId>(100 + p)) << "place " << p;
    if (found.size() > 1) EXPECT_GT(found[0].score, 1.3 * found[1].score);
    // Skipped entries are not returned; erased ones neither.
    for (const PlaceMatch& m : db.query(q, 0.0, [p](EntryId id) { return id == static_cast<EntryId>(100 + p); }))
      EXPECT_NE(m.id, static_cast<EntryId>(100 + p));
  }
  db.erase(105);
  for (const PlaceMatch& m : db.query(vocabulary->transform(scenes.view(5, 10)), 0.0)) EXPECT_NE(m.id, 105u);
}

TEST(Vocabulary, SavedAndLoadedGivesTheSameWordsAndBadFilesAreErrors) {
  Scenes scenes(4);
  const Vocabulary v = trained(scenes);
  const std::string bytes = v.encode();
  const Vocabulary back = Vocabulary::decode(bytes, "v.voc");
  EXPECT_EQ(back.numWords(), v.numWords());
  const cv::Mat d = scenes.view(2, 20);
  for (int r = 0; r < d.rows; ++r) EXPECT_EQ(back.word(d.ptr<std::uint8_t>(r)), v.word(d.ptr<std::uint8_t>(r)));
  EXPECT_TRUE(back.encode() == bytes);
  std::string corrupt = bytes;
  corrupt[bytes.size() / 2] ^= 1;
  EXPECT_THROW(Vocabulary::decode(corrupt, "v.voc"), core::Error);
  EXPECT_THROW(Vocabulary::decode(bytes.substr(0, bytes.size() - 4), "v.voc"), core::Error);
  EXPECT_THROW(Vocabulary::decode("AMOSMAP", "v.voc"), core::Error);
  try {
    Vocabulary::decode(corrupt, "dir/v.voc");
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("dir/v.voc: corrupt"), std::string::npos) << e.what();
  }
}

TEST(Vocabulary, TrainingIsDeterministic) {
  Scenes a(3), b(3);
  EXPECT_TRUE(trained(a).encode() == trained(b).encode());  // (not EXPECT_EQ: it would print the bytes)
}

}  // namespace
}  // namespace amos::place
