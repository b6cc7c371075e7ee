#include "amos/viewer/dense_layer.h"

#include <cstdint>
#include <cstring>

#include "amos/core/error.h"

namespace amos::viewer {
namespace {

template <typename T>
void append(std::string& out, const T* data, std::size_t count) {
  // The machines this runs on are little-endian (x86-64, arm64): the bytes are the format's.
  out.append(reinterpret_cast<const char*>(data), count * sizeof(T));
}

}  // namespace

std::string encodeDenseLayer(const ColouredGeometry& g) {
  core::require(g.xyz.size() % 3 == 0 && g.rgb.size() == g.xyz.size() && g.triangles.size() % 3 == 0,
                "viewer: a dense layer needs 3 coordinates and 3 colour bytes per point, 3 indices per triangle");
  const auto vertices = static_cast<std::uint32_t>(g.vertexCount());
  const auto triangles = static_cast<std::uint32_t>(g.triangleCount());
  std::string out;
  out.reserve(8 + 15 * static_cast<std::size_t>(vertices) + 12 * static_cast<std::size_t>(triangles));
  append(out, &vertices, 1);
  append(out, &triangles, 1);
  append(out, g.xyz.data(), 3 * static_cast<std::size_t>(vertices));
  append(out, g.triangles.data(), 3 * static_cast<std::size_t>(triangles));
  append(out, g.rgb.data(), 3 * static_cast<std::size_t>(vertices));
  return out;
}

ColouredGeometry thinPoints(ColouredGeometry cloud, std::size_t max_points) {
  cloud.triangles.clear();
  const std::size_t n = cloud.vertexCount();
  if (max_points == 0 || n <= max_points) return cloud;
  const std::size_t step = (n + max_points - 1) / max_points;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n; i += step, ++kept) {
    std::memmove(&cloud.xyz[3 * kept], &cloud.xyz[3 * i], 3 * sizeof(float));
    std::memmove(&cloud.rgb[3 * kept], &cloud.rgb[3 * i], 3);
  }
  cloud.xyz.resize(3 * kept);
  cloud.rgb.resize(3 * kept);
  return cloud;
}

}  // namespace amos::viewer
