// Place recognition speed: the bag-of-words vector of a frame (1000 ORB descriptors) and a database query
// against maps of 100 to 3000 keyframes. The vocabulary is models/orb_vocabulary.voc (run from the checkout, or
// set AMOS_VOCABULARY); the keyframes' descriptors are random, so every query word hits its share of keyframes
// (a worst case for the inverted index: real scenes share fewer words with most keyframes).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>
#include <random>

#include "amos/place/keyframe_database.h"
#include "amos/place/vocabulary.h"

namespace {

std::shared_ptr<const amos::place::Vocabulary> vocabulary() {
  static const std::shared_ptr<const amos::place::Vocabulary> v = [] {
    const char* env = std::getenv("AMOS_VOCABULARY");
    return std::make_shared<const amos::place::Vocabulary>(
        amos::place::Vocabulary::load(env != nullptr ? env : "models/orb_vocabulary.voc"));
  }();
  return v;
}

cv::Mat randomDescriptors(int n, unsigned seed) {
  cv::Mat d(n, 32, CV_8U);
  cv::theRNG().state = seed;
  cv::randu(d, 0, 256);
  return d;
}

void BM_Transform(benchmark::State& state) {
  const auto v = vocabulary();
  const cv::Mat d = randomDescriptors(1000, 1);
  for (auto _ : state) benchmark::DoNotOptimize(v->transform(d));
}
BENCHMARK(BM_Transform)->Unit(benchmark::kMicrosecond);

void BM_LoadVocabulary(benchmark::State& state) {
  const char* env = std::getenv("AMOS_VOCABULARY");
  for (auto _ : state) benchmark::DoNotOptimize(amos::place::Vocabulary::load(env != nullptr ? env : "models/orb_vocabulary.voc"));
}
BENCHMARK(BM_LoadVocabulary)->Unit(benchmark::kMillisecond);

void BM_Query(benchmark::State& state) {
  const auto v = vocabulary();
  amos::place::KeyFrameDatabase db(v);
  for (int k = 0; k < state.range(0); ++k) db.add(static_cast<amos::place::EntryId>(k), v->transform(randomDescriptors(1000, 10 + k)));
  const amos::place::BowVector q = v->transform(randomDescriptors(1000, 5));
  for (auto _ : state) benchmark::DoNotOptimize(db.query(q));
  state.counters["keyframes"] = static_cast<double>(state.range(0));
}
BENCHMARK(BM_Query)->Arg(100)->Arg(300)->Arg(1000)->Arg(3000)->Unit(benchmark::kMicrosecond);

}  // namespace
