#include "amos/place/keyframe_database.h"

#include <algorithm>
#include <mutex>

#include "amos/core/error.h"

namespace amos::place {

KeyFrameDatabase::KeyFrameDatabase(std::shared_ptr<const Vocabulary> vocabulary)
    : vocabulary_(std::move(vocabulary)) {
  core::require(vocabulary_ && !vocabulary_->empty(), "KeyFrameDatabase: an empty vocabulary");
  inverted_.resize(vocabulary_->numWords());
}

void KeyFrameDatabase::add(EntryId id, BowVector v) {
  std::unique_lock lock(mutex_);
  const auto it = vectors_.find(id);
  if (it != vectors_.end()) {
    for (const auto& [w, x] : it->second.words) {
      auto& list = inverted_[w];
      list.erase(std::remove(list.begin(), list.end(), id), list.end());
    }
  }
  for (const auto& [w, x] : v.words) inverted_[w].push_back(id);
  vectors_[id] = std::move(v);
}

void KeyFrameDatabase::erase(EntryId id) {
  std::unique_lock lock(mutex_);
  const auto it = vectors_.find(id);
  if (it == vectors_.end()) return;
  for (const auto& [w, x] : it->second.words) {
    auto& list = inverted_[w];
    list.erase(std::remove(list.begin(), list.end(), id), list.end());
  }
  vectors_.erase(it);
}

BowVector KeyFrameDatabase::vector(EntryId id) const {
  std::shared_lock lock(mutex_);
  const auto it = vectors_.find(id);
  return it == vectors_.end() ? BowVector{} : it->second;
}

std::size_t KeyFrameDatabase::size() const {
  std::shared_lock lock(mutex_);
  return vectors_.size();
}

std::vector<PlaceMatch> KeyFrameDatabase::query(const BowVector& q, double min_common_ratio,
                                                const std::function<bool(EntryId)>& skip) const {
  std::shared_lock lock(mutex_);
  std::unordered_map<EntryId, int> common;
  for (const auto& [w, x] : q.words) {
    if (w >= inverted_.size()) continue;
    for (const EntryId id : inverted_[w]) ++common[id];
  }
  int max_common = 0;
  std::vector<std::pair<EntryId, int>> shared;
  for (const auto& [id, n] : common) {
    if (skip && skip(id)) continue;
    shared.emplace_back(id, n);
    max_common = std::max(max_common, n);
  }
  const int min_common = static_cast<int>(min_common_ratio * max_common);
  std::vector<PlaceMatch> out;
  for (const auto& [id, n] : shared) {
    if (n < min_common) continue;
    out.push_back({id, similarity(q, vectors_.at(id)), n});
  }
  std::sort(out.begin(), out.end(), [](const PlaceMatch& a, const PlaceMatch& b) {
    return a.score != b.score ? a.score > b.score : a.id < b.id;
  });
  return out;
}

}  // namespace amos::place
