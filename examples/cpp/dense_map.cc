// dense_map SEQUENCE CONFIG OUT [MODE]
// Tracks a TUM/Bonn-layout folder through the public API with the dense static map on (Options::dense), and writes
// the map fused with the final trajectory: OUT/mesh.ply, OUT/cloud.ply and, when a floor was found, the floor plan
// OUT/occupancy.pgm + OUT/occupancy.yaml: what `amos-slam run --dense --deterministic` writes for the same folder
// and settings (deterministic mode). Needs a library built with Open3D.
#include <amos/dense_map.h>
#include <amos/sequence_folder.h>
#include <amos/slam.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>

int main(int argc, char** argv) {
  if (argc < 4 || argc > 5) {
    std::fprintf(stderr, "usage: %s SEQUENCE CONFIG OUT [none|prior|geometry|full]\n", argv[0]);
    return 2;
  }
  try {
    if (!amos::denseMappingAvailable()) {
      std::fprintf(stderr, "error: this amos-slam library was built without the dense map (Open3D)\n");
      return 1;
    }
    amos::Options options;
    options.settings_file = argv[2];
    options.mode = amos::parseMode(argc == 5 ? argv[4] : "full");
    options.deterministic = true;
    options.dense = true;  // the settings' Dense.* keys apply
    amos::Slam slam(options);
    amos::SequenceFolder folder(argv[1]);
    slam.trackFrames(
        [&]() -> std::optional<amos::InputFrame> {
          std::optional<amos::RgbdImages> f = folder.next();
          if (!f) return std::nullopt;
          return amos::InputFrame{f->bgr, f->depth, f->timestamp, {}};
        },
        [&](const amos::FrameResult& result) {
          // While running, the live surface (tracking poses) is there for a viewer of your own.
          if (result.frame % 20 == 19) {
            if (const std::optional<amos::DenseSnapshot> live = slam.denseSnapshot())
              std::printf("frame %zu: live surface of %zu points\n", result.frame, live->cloud.points.size());
          }
        });
    slam.finish();
    const amos::DenseMap map = slam.denseMap();  // fused anew with the final trajectory
    const std::filesystem::path out(argv[3]);
    std::filesystem::create_directories(out);
    amos::writeMeshPly(map, (out / "mesh.ply").string());
    amos::writeCloudPly(map, (out / "cloud.ply").string());
    if (map.grid) amos::writeFloorPlan(map, (out / "occupancy").string());
    std::printf("dense map of %zu frames: mesh of %zu vertices and %zu triangles, floor plan %s -> %s\n",
                map.frames_fused, map.mesh.vertices.size(), map.mesh.triangles.size(),
                map.grid ? "written" : "none (no floor found)", argv[3]);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
