#pragma once
// The keyframes' bag-of-words vectors with an inverted index (word -> keyframes that contain it), so a query
// scores only the keyframes that share a word with it. Thread-safe: tracking adds keyframes and queries for
// relocalisation, the mapping thread erases culled ones and queries for loops (its own reader-writer lock, never
// held while calling out).
#include <cstdint>
#include <functional>
#include <memory>
#include <shared_mutex>
#include <unordered_map>
#include <utility>
#include <vector>

#include "amos/place/vocabulary.h"

namespace amos::place {

using EntryId = std::uint64_t;  // a keyframe id

struct PlaceMatch {
  EntryId id = 0;
  double score = 0;       // similarity() with the query
  int common_words = 0;
};

class KeyFrameDatabase {
 public:
  explicit KeyFrameDatabase(std::shared_ptr<const Vocabulary> vocabulary);

  const Vocabulary& vocabulary() const { return *vocabulary_; }
  BowVector transform(const cv::Mat& descriptors) const { return vocabulary_->transform(descriptors); }

  // Adds (or replaces) the vector of `id`.
  void add(EntryId id, BowVector v);
  void erase(EntryId id);
  // The vector of `id` (empty when unknown).
  BowVector vector(EntryId id) const;
  std::size_t size() const;

  // Entries sharing words with `query` (except those `skip` rejects), keeping those with at least
  // `min_common_ratio` x the largest number of common words, scored, best first (ties: smaller id).
  std::vector<PlaceMatch> query(const BowVector& query, double min_common_ratio = 0.8,
                                const std::function<bool(EntryId)>& skip = {}) const;

 private:
  std::shared_ptr<const Vocabulary> vocabulary_;
  mutable std::shared_mutex mutex_;
  std::unordered_map<EntryId, BowVector> vectors_;
  std::vector<std::vector<EntryId>> inverted_;  // per word
};

}  // namespace amos::place
