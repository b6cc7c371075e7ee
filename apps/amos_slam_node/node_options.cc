#include "node_options.h"

#include <fmt/format.h>

#include "amos/core/error.h"

namespace amos::node {

void NodeOptions::check() const {
  core::require(!settings_file.empty(), "~settings_file: required (a settings file, configs/*.yaml)");
  core::require(mode == "none" || mode == "prior" || mode == "geometry" || mode == "full",
                fmt::format("~mode '{}': expected none, prior, geometry or full", mode));
  core::require(!map_frame.empty() && !camera_frame.empty(), "~map_frame and ~camera_frame must not be empty");
  core::require(sync_queue >= 1 && sync_queue <= 1000, fmt::format("~sync_queue {}: expected 1 to 1000", sync_queue));
  core::require(max_pair_dt > 0 && max_pair_dt < 1, fmt::format("~max_pair_dt {}: expected (0, 1) s", max_pair_dt));
  core::require(cloud_rate >= 0 && cloud_rate <= 30, fmt::format("~cloud_rate {}: expected 0 (never) to 30 Hz",
                                                                 cloud_rate));
  core::require(dense_rate >= 0 && dense_rate <= 30, fmt::format("~dense_rate {}: expected 0 (never) to 30 Hz",
                                                                 dense_rate));
}

NodeOptions readNodeOptions(const ros::NodeHandle& p) {
  NodeOptions o;
  p.param("settings_file", o.settings_file, o.settings_file);
  p.param("mode", o.mode, o.mode);
  p.param("models_dir", o.models_dir, o.models_dir);
  p.param("deterministic", o.deterministic, o.deterministic);
  p.param("dense", o.dense, o.dense);
  p.param("map_frame", o.map_frame, o.map_frame);
  p.param("camera_frame", o.camera_frame, o.camera_frame);
  p.param("odom_frame", o.odom_frame, o.odom_frame);
  p.param("rgb_topic", o.rgb_topic, o.rgb_topic);
  p.param("depth_topic", o.depth_topic, o.depth_topic);
  p.param("camera_info_topic", o.camera_info_topic, o.camera_info_topic);
  p.param("sync_queue", o.sync_queue, o.sync_queue);
  p.param("max_pair_dt", o.max_pair_dt, o.max_pair_dt);
  p.param("cloud_rate", o.cloud_rate, o.cloud_rate);
  p.param("dense_rate", o.dense_rate, o.dense_rate);
  p.param("output_dir", o.output_dir, o.output_dir);
  o.check();
  return o;
}

}  // namespace amos::node
