// track_folder SEQUENCE CONFIG TRAJECTORY_OUT [MODE]
// Tracks a TUM/Bonn-layout folder through the public API and writes its trajectory in the TUM format
// (deterministic mode, so it is the trajectory `amos-slam run --deterministic` writes for the same folder). Prints
// the frames per second of the tracking loop (reading the images included).
#include <amos/sequence_folder.h>
#include <amos/slam.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>

int main(int argc, char** argv) {
  if (argc < 4 || argc > 5) {
    std::fprintf(stderr, "usage: %s SEQUENCE CONFIG TRAJECTORY_OUT [none|prior|geometry|full]\n", argv[0]);
    return 2;
  }
  try {
    amos::Options options;
    options.settings_file = argv[2];
    options.mode = amos::parseMode(argc == 5 ? argv[4] : "full");
    options.deterministic = true;
    amos::Slam slam(options);
    // The folder decodes frames ahead in a thread of its own (a frame that cannot be read is skipped and counted).
    amos::SequenceFolder folder(argv[1]);
    std::size_t tracked = 0;
    const auto start = std::chrono::steady_clock::now();
    // trackFrames pulls the frames from this function one ahead of the results, so that the next frame's features
    // are extracted while the current one is tracked. slam.track(bgr, depth, t) in a loop of your own would do too,
    // a little slower.
    slam.trackFrames(
        [&]() -> std::optional<amos::InputFrame> {
          std::optional<amos::RgbdImages> f = folder.next();
          if (!f) return std::nullopt;
          return amos::InputFrame{f->bgr, f->depth, f->timestamp, {}};
        },
        [&](const amos::FrameResult& result) { tracked += result.T_wc.has_value(); });
    slam.finish();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    slam.writeTrajectory(argv[3]);
    const amos::MapSummary map = slam.summary();
    std::printf("amos-slam %s: %zu frames (%zu skipped), %zu tracked, %zu keyframes, %zu map points, %.1f fps -> %s\n",
                amos::kVersion, folder.size(), folder.skipped(), tracked, map.keyframes, map.map_points,
                static_cast<double>(folder.size() - folder.skipped()) / seconds, argv[3]);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
