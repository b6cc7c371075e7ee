#pragma once
// node_stats.json: what the node received, dropped, tracked and published, its latency (pair complete -> pose
// published: median, p95, max) and the map's counts.
#include <string>

#include "amos/slam.h"
#include "slam_node.h"

namespace amos::node {

void writeNodeStats(const std::string& path, const NodeStats& stats, const MapSummary& map);

}  // namespace amos::node
