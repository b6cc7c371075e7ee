#pragma once
// Map files (`amos-slam run --save-map FILE` / `--load-map FILE`): everything a later session needs to track
// against a map and to extend it, in one binary file:
//   - the camera the map was built with (intrinsics, distortion, image size, virtual baseline bf, ORB pyramid):
//     a map is only loaded by a run with the same calibration, since its keypoints are undistorted pixels of that
//     camera and its descriptors were taken on that pyramid;
//   - the keyframes: id, frame id, time stamp, pose T_cw, keypoints (undistorted), descriptors, depth, virtual
//     right coordinate, thumbnail, map point per keypoint, covisibility weights, spanning-tree parent and children;
//   - the map points: id, position, observations, representative descriptor, viewing normal and distance range,
//     reference keyframe, tracking and dynamic-evidence counters;
//   - the records of culled keyframes (so poses referring to them stay valid) and the next free ids.
// Place-recognition vectors are not stored: they are recomputed from the descriptors when the map is loaded.
//
// Layout (little-endian): a 32-byte header, then the payload.
//   header: magic "AMOSMAP\0" (8 bytes), format version u32, endianness probe u32 (0x01020304), payload size
//           u64, CRC-32 of the payload u32, reserved u32 (0)
//   payload: the sections above, in that order (map_file.cc writes them; there is no other description).
// Any change of the payload's layout increments kMapFormatVersion; a file of another version is refused.
#include <cstdint>
#include <memory>
#include <string>

#include "amos/map/map.h"
#include "amos/map/sensor.h"

namespace amos::mapio {

inline constexpr std::uint32_t kMapFormatVersion = 1;
inline constexpr std::size_t kMapHeaderBytes = 32;

struct MapFileSummary {
  std::size_t keyframes = 0, map_points = 0, removed_keyframes = 0;
  std::size_t bytes = 0;            // file size
  map::FrameId max_frame_id = 0;    // largest frame id the map refers to (a session that extends it goes on after)
};

// Serialises `map` (good keyframes and points) with the camera of `sensor`. Takes a shared lock on the map.
std::string encodeMap(const map::Map& map, const map::Sensor& sensor, MapFileSummary* summary = nullptr);
// Writes encodeMap() to `path` atomically (a temporary file renamed). Throws core::Error naming the file.
MapFileSummary saveMap(const std::string& path, const map::Map& map, const map::Sensor& sensor);

// Restores a map into `into`, which must be empty: its keyframes get `sensor`. `source` names the bytes in
// errors (the file). Throws core::Error naming the source and the problem: too short / truncated, not a map file,
// another format version, another byte order, checksum mismatch (corrupt), another camera calibration than
// `sensor`, or an inconsistent payload.
MapFileSummary decodeMap(const std::string& bytes, const std::string& source,
                         const std::shared_ptr<const map::Sensor>& sensor, map::Map& into);
// Reads `path` and decodeMap()s it (a missing or unreadable file is an error naming it).
MapFileSummary loadMap(const std::string& path, const std::shared_ptr<const map::Sensor>& sensor, map::Map& into);

}  // namespace amos::mapio
