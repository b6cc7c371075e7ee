#pragma once
// Portable, reproducible randomness for the generator. The std:: distributions are allowed to differ between
// standard libraries, so only the raw std::mt19937 stream is used and the transforms are our own: the same
// preset, seed and frame count then give byte-identical files on every platform.
#include <cstdint>
#include <random>
#include <vector>

namespace amos::synth {

// Independent 32-bit seed for a named stream (a small integer tag) and index, from the user's seed (splitmix64).
std::uint32_t deriveSeed(std::uint64_t seed, std::uint64_t stream, std::uint64_t index = 0);

// Stream tags, so that e.g. removing the movers does not change the room or the camera path.
enum class Stream : std::uint64_t { kRoom = 1, kTextures, kCameraPath, kMovers, kSensor, kAssets };
inline std::uint32_t deriveSeed(std::uint64_t seed, Stream stream, std::uint64_t index = 0) {
  return deriveSeed(seed, static_cast<std::uint64_t>(stream), index);
}

class Random {
 public:
  explicit Random(std::uint32_t seed) : engine_(seed) {}
  std::uint32_t bits() { return engine_(); }
  // Uniform in [0, 1).
  double uniform() { return engine_() * (1.0 / 4294967296.0); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [lo, hi] (inclusive).
  int uniformInt(int lo, int hi);
  bool chance(double p) { return uniform() < p; }
  // Standard normal (Box-Muller); for the few draws of scene construction. Per-pixel noise uses GaussianTable.
  double gaussian();
  // Picks one element index with the given (non-negative) weights.
  std::size_t pickWeighted(const std::vector<double>& weights);

 private:
  std::mt19937 engine_;
};

// Fast standard-normal samples for per-pixel sensor noise: 65536 quantiles of N(0, 1), indexed by 16 random bits
// (so one mt19937 draw gives two samples). Tails are cut at about 4.3 sigma, which no noise model here needs.
class GaussianTable {
 public:
  GaussianTable();
  float operator[](std::uint32_t index16) const { return table_[index16 & 0xffffu]; }

 private:
  std::vector<float> table_;
};

// Inverse of the standard normal CDF, accurate to ~1e-12 (Acklam's rational approximation + one Newton step).
double inverseNormalCdf(double p);

}  // namespace amos::synth
