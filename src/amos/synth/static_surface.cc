#include "amos/synth/static_surface.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "amos/core/error.h"

namespace amos::synth {

namespace {

using CellKey = std::tuple<long, long, long>;

CellKey cellOf(const Eigen::Vector3d& p, double cell) {
  return {std::lround(std::floor(p.x() / cell)), std::lround(std::floor(p.y() / cell)),
          std::lround(std::floor(p.z() / cell))};
}

constexpr const char* kHeaderEnd = "end_header\n";

}  // namespace

std::vector<SurfaceSample> staticSurfaceSamples(const SequenceGenerator& generator, const SurfaceSampling& sampling) {
  const core::CameraIntrinsics& k = generator.intrinsics();
  std::map<CellKey, SurfaceSample> cells;
  for (int index = 0; index < generator.frameCount(); index += std::max(1, sampling.frame_step)) {
    const RenderedImage image = generator.renderExact(index, /*with_static=*/true, /*with_movers=*/false,
                                                      /*with_color=*/false);
    const core::SE3 T_wc = generator.poseWc(index);
    for (int v = 0; v < image.depth.rows; v += sampling.pixel_step) {
      for (int u = 0; u < image.depth.cols; u += sampling.pixel_step) {
        const float z = image.depth.at<float>(v, u);
        if (!(z > 0)) continue;
        const Eigen::Vector3d p = T_wc * Eigen::Vector3d((u - k.cx) * z / k.fx, (v - k.cy) * z / k.fy, z);
        auto [it, added] = cells.try_emplace(cellOf(p, sampling.cell), SurfaceSample{p.cast<float>(), z});
        if (!added) it->second.depth = std::min(it->second.depth, z);
      }
    }
  }
  std::vector<SurfaceSample> out;
  out.reserve(cells.size());
  for (const auto& [key, sample] : cells) out.push_back(sample);
  return out;
}

void writeSurfacePly(const std::string& path, const std::vector<SurfaceSample>& samples) {
  std::ofstream out(path, std::ios::binary);
  core::require(out.good(), fmt::format("cannot write {}", path));
  out << "ply\nformat binary_little_endian 1.0\ncomment amos-slam synth: true static surface (ground truth frame)\n"
      << "element vertex " << samples.size() << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "property float depth\n" << kHeaderEnd;
  for (const SurfaceSample& s : samples) {
    const float values[4] = {s.position.x(), s.position.y(), s.position.z(), s.depth};
    out.write(reinterpret_cast<const char*>(values), sizeof(values));
  }
  core::require(out.good(), fmt::format("cannot write {}", path));
}

std::vector<SurfaceSample> readSurfacePly(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  core::require(in.good(), fmt::format("{}: cannot be read", path));
  std::string line, header;
  std::size_t count = 0;
  while (std::getline(in, line)) {
    header += line + "\n";
    if (line.rfind("element vertex ", 0) == 0) count = std::stoul(line.substr(15));
    if (line == "end_header") break;
  }
  const std::string expected = "property float x\nproperty float y\nproperty float z\nproperty float depth\n";
  core::require(header.rfind("ply\nformat binary_little_endian 1.0\n", 0) == 0 && header.find(expected) != std::string::npos,
                fmt::format("{}: not a static surface file (binary PLY of x y z depth floats)", path));
  std::vector<SurfaceSample> out(count);
  for (SurfaceSample& s : out) {
    float values[4];
    in.read(reinterpret_cast<char*>(values), sizeof(values));
    core::require(in.good(), fmt::format("{}: truncated ({} points announced)", path, count));
    s.position = {values[0], values[1], values[2]};
    s.depth = values[3];
  }
  return out;
}

}  // namespace amos::synth
