#include "node_stats.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <stdexcept>

namespace amos::node {

namespace {

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const auto i = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1) + 0.5);
  return values[std::min(i, values.size() - 1)];
}

}  // namespace

void writeNodeStats(const std::string& path, const NodeStats& s, const MapSummary& map) {
  const nlohmann::json j = {
      {"received", s.received},
      {"dropped", s.dropped},
      {"dropped_share", s.received > 0 ? static_cast<double>(s.dropped) / static_cast<double>(s.received) : 0.0},
      {"processed", s.processed},
      {"published", s.published},
      {"latency_ms",
       {{"median", percentile(s.latency_ms, 0.5)},
        {"p95", percentile(s.latency_ms, 0.95)},
        {"max", percentile(s.latency_ms, 1.0)}}},
      {"map", {{"keyframes", map.keyframes}, {"map_points", map.map_points}, {"loops_closed", map.loops_closed}}},
  };
  std::ofstream out(path);
  out << j.dump(2) << "\n";
  if (!out) throw std::runtime_error(fmt::format("cannot write '{}'", path));
}

}  // namespace amos::node
