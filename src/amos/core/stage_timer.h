#pragma once
// Per-stage wall-clock timing: Stopwatch measures, StageTimes collects samples per named stage and reports
// medians and 95th percentiles (what stats.json and the benchmarks print).
#include <chrono>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace amos::core {

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  void restart() { start_ = std::chrono::steady_clock::now(); }
  double elapsedMs() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

// CPU time consumed by the calling thread [ms]. Unlike wall time it does not grow when other threads or processes
// share the cores (the "cpu.*" stages of the dynamic pipeline).
double threadCpuMs();

struct StageSummary {
  std::size_t count = 0;
  double median_ms = 0, p95_ms = 0, mean_ms = 0, max_ms = 0;
};

// Thread-safe: stages may be recorded from the tracking and mapping threads at once.
class StageTimes {
 public:
  void add(const std::string& stage, double ms);
  std::map<std::string, StageSummary> summary() const;
  std::vector<double> samples(const std::string& stage) const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::vector<double>> samples_;
};

// Percentile q in [0, 1] by linear interpolation between order statistics (q = 0.5 is the median).
double percentile(std::vector<double> values, double q);

}  // namespace amos::core
