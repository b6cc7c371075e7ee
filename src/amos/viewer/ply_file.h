#pragma once
// Reading the PLY files a run leaves for the viewer: map.ply (ASCII, x y z), and the dense products of
// `run --dense` (mesh.ply, cloud.ply, removed_points.ply: binary little-endian, x y z float, red green blue uchar,
// faces as a list of vertex indices). Only what the viewer draws is kept: positions, colours (grey when the file
// has none) and triangles (polygons are split into fans). Any other property is skipped by its size.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace amos::viewer {

struct ColouredGeometry {
  std::vector<float> xyz;                // 3 per vertex
  std::vector<std::uint8_t> rgb;         // 3 per vertex
  std::vector<std::uint32_t> triangles;  // 3 vertex indices per triangle; empty for a point cloud
  std::size_t vertexCount() const { return xyz.size() / 3; }
  std::size_t triangleCount() const { return triangles.size() / 3; }
};

// Reads an ASCII or binary little-endian PLY. Throws core::Error naming the file and what is wrong (not a PLY,
// an unsupported format or property type, no x y z, a truncated body, a face index out of range, a vertex
// coordinate that is not a finite float). Every count is checked against the bytes the file has before it is
// used: an element count or a list's item count claiming more than the rest of the file can hold is an error at
// once (no allocation or loop of the claimed size).
ColouredGeometry readPly(const std::filesystem::path& path);

// The same for the file's bytes in memory; `file` names them in errors.
ColouredGeometry parsePly(const std::string& text, const std::string& file);

}  // namespace amos::viewer
