#pragma once
// For the viewer's tests: small run folders with known contents, written as `amos-slam run` (--dense) writes
// them: a trajectory on a circle, keyframes, map.ply (with far outliers), stats.json, a report.html data block,
// and the dense products in their agreed formats (binary little-endian PLY: vertex x y z float, red green blue
// uchar, face list uchar int; occupancy.pgm P5 + occupancy.yaml as ROS map_server writes them).
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "amos/viewer/ply_file.h"
#include "amos/viewer/report_html.h"

namespace amos::viewer::test {

namespace fs = std::filesystem;

inline void writeText(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

// Binary little-endian PLY; faces only when the geometry has triangles (or `faces` is set).
inline void writeBinaryPly(const fs::path& path, const ColouredGeometry& g, bool faces) {
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by a viewer test\n";
  out += "element vertex " + std::to_string(g.vertexCount()) + "\n";
  out += "property float x\nproperty float y\nproperty float z\n";
  out += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (faces) out += "element face " + std::to_string(g.triangleCount()) + "\nproperty list uchar int vertex_indices\n";
  out += "end_header\n";
  for (std::size_t i = 0; i < g.vertexCount(); ++i) {
    out.append(reinterpret_cast<const char*>(&g.xyz[3 * i]), 3 * sizeof(float));
    out.append(reinterpret_cast<const char*>(&g.rgb[3 * i]), 3);
  }
  if (faces)
    for (std::size_t t = 0; t < g.triangleCount(); ++t) {
      out.push_back(3);
      for (int k = 0; k < 3; ++k) {
        const auto index = static_cast<std::int32_t>(g.triangles[3 * t + k]);
        out.append(reinterpret_cast<const char*>(&index), sizeof(index));
      }
    }
  writeText(path, out);
}

// A floor and a wall (2 triangles each) spanning [x0, x1] x [z0, z1] at height y (SLAM frame: y down), coloured.
inline ColouredGeometry floorAndWall(float x0, float x1, float z0, float z1, float y) {
  ColouredGeometry g;
  g.xyz = {x0, y, z0, x1, y, z0, x1, y, z1, x0, y, z1,                         // floor
           x0, y, z1, x1, y, z1, x1, y - 2, z1, x0, y - 2, z1};                // wall at the far end
  g.rgb = {160, 120, 80, 160, 120, 80, 160, 120, 80, 160, 120, 80, 80, 120, 160, 80, 120, 160, 80, 120, 160, 80, 120, 160};
  g.triangles = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
  return g;
}

// `n` points on a grid over the same floor, coloured; for cloud.ply / removed_points.ply.
inline ColouredGeometry gridCloud(float x0, float x1, float z0, float z1, float y, int n, std::uint8_t r,
                                  std::uint8_t gr, std::uint8_t b) {
  ColouredGeometry g;
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  for (int i = 0; i < n; ++i) {
    const float u = (i % side + 0.5f) / side, v = (i / side + 0.5f) / side;
    g.xyz.insert(g.xyz.end(), {x0 + u * (x1 - x0), y, z0 + v * (z1 - z0)});
    g.rgb.insert(g.rgb.end(), {r, gr, b});
  }
  return g;
}

// occupancy.pgm (width x height cells: unknown left quarter, occupied border, free inside) and occupancy.yaml.
inline void writeOccupancy(const fs::path& dir, int width, int height, double resolution) {
  std::string pgm = "P5\n" + std::to_string(width) + " " + std::to_string(height) + "\n255\n";
  for (int r = 0; r < height; ++r)
    for (int c = 0; c < width; ++c) {
      const bool border = r == 0 || c == 0 || r == height - 1 || c == width - 1;
      pgm.push_back(static_cast<char>(c < width / 4 ? 205 : border ? 0 : 254));
    }
  writeText(dir / "occupancy.pgm", pgm);
  writeText(dir / "occupancy.yaml", "image: occupancy.pgm\nmode: trinary\nresolution: " + std::to_string(resolution) +
                                        "\norigin: [-1.5, -2.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
}

// A finished run in `dir`: 60 poses on a circle of radius 1 m about (0, 0, 2) in the x-z plane (SLAM frame),
// 3 keyframes, a map of 400 points around it plus 4 outliers 100 m away, stats.json and a report.html whose data
// holds the ground truth in the map's frame (the trajectory shifted by 5 cm). With `dense`: mesh.ply, cloud.ply,
// removed_points.ply and the occupancy grid.
inline void writeRunFolder(const fs::path& dir, bool dense) {
  fs::create_directories(dir);
  std::string trajectory, keyframes;
  nlohmann::json ground_truth = nlohmann::json::array();
  for (int i = 0; i < 60; ++i) {
    const double a = 2 * M_PI * i / 60, t = 1.0 + i / 30.0, x = std::cos(a), z = 2 + std::sin(a);
    const std::string line = std::to_string(t) + " " + std::to_string(x) + " 0 " + std::to_string(z) + " 0 0 0 1\n";
    trajectory += line;
    if (i % 20 == 0) keyframes += line;
    ground_truth.push_back({t, x + 0.05, 0.0, z});
  }
  writeText(dir / "trajectory.txt", trajectory);
  writeText(dir / "keyframes.txt", keyframes);
  std::string map = "ply\nformat ascii 1.0\nelement vertex 404\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  for (int i = 0; i < 400; ++i)
    map += std::to_string(-1.2 + 2.4 * (i % 20) / 19.0) + " " + std::to_string(-0.5 + (i % 7) * 0.15) + " " +
           std::to_string(0.8 + 2.4 * (i / 20) / 19.0) + "\n";
  for (int i = 0; i < 4; ++i) map += std::to_string(100.0 * (i % 2 ? 1 : -1)) + " 50 " + std::to_string(100.0 * i) + "\n";
  writeText(dir / "map.ply", map);
  const nlohmann::json stage = {{"count", 60}, {"median_ms", 12.5}, {"p95_ms", 20.0}};
  const nlohmann::json stats = {
      {"frames", 60}, {"tracked", 60}, {"lost", 0}, {"mode", "full"}, {"sequence", "synthetic circle"}, {"fps", 30.0},
      {"stages", {{"frame.extract", stage}, {"frame.build", stage}, {"frame.track", stage}, {"frame.total", stage}}},
      {"end", {{"status", "complete"}}}};
  writeText(dir / "stats.json", stats.dump());
  nlohmann::json data = {{"stats", stats}, {"overlays", nlohmann::json::array()}, {"view", {{"ground_truth", ground_truth}}}};
  writeText(dir / "report.html", reportHtml(data));
  if (!dense) return;
  writeBinaryPly(dir / "mesh.ply", floorAndWall(-1.2f, 1.2f, 0.8f, 3.2f, 0.4f), true);
  writeBinaryPly(dir / "cloud.ply", gridCloud(-1.2f, 1.2f, 0.8f, 3.2f, 0.39f, 900, 180, 140, 100), false);
  writeBinaryPly(dir / "removed_points.ply", gridCloud(-0.3f, 0.3f, 1.7f, 2.3f, -0.5f, 400, 0, 0, 0), false);
  writeOccupancy(dir, 48, 40, 0.05);
}

}  // namespace amos::viewer::test
