#include "amos/core/stage_timer.h"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace amos::core {

double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

void StageTimes::add(const std::string& stage, double ms) {
  std::lock_guard<std::mutex> lock(mutex_);
  samples_[stage].push_back(ms);
}

std::vector<double> StageTimes::samples(const std::string& stage) const {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = samples_.find(stage);
  return it == samples_.end() ? std::vector<double>{} : it->second;
}

std::map<std::string, StageSummary> StageTimes::summary() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::map<std::string, StageSummary> out;
  for (const auto& [stage, values] : samples_) {
    StageSummary s;
    s.count = values.size();
    if (!values.empty()) {
      s.median_ms = percentile(values, 0.5);
      s.p95_ms = percentile(values, 0.95);
      s.mean_ms = std::accumulate(values.begin(), values.end(), 0.0) / values.size();
      s.max_ms = *std::max_element(values.begin(), values.end());
    }
    out[stage] = s;
  }
  return out;
}

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double pos = std::clamp(q, 0.0, 1.0) * (values.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const auto hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (pos - lo) * (values[hi] - values[lo]);
}

}  // namespace amos::core
