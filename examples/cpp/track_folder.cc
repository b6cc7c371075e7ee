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
    std::fprintf(stderr, "usage: %s SEQUENCE CONFIG TRAJECTORY_OUT [MODE: none|prior|geometry|full]\n", argv[0]);
    return 2;
  }
  try {
    amos::Options options;
    options.settings_file = argv[2];
    options.mode = argc == 5 ? argv[4] : "full";
    options.deterministic = true;
    amos::Slam slam(options);
    // The folder decodes frames ahead in a thread of its own (next()), and one frame of look-ahead goes into the
    // system: frame k+1 is submitted (its features are extracted in the library's threads) before frame k's result
    // is taken. slam.track(bgr, depth, t) alone would do too, a little slower.
    amos::SequenceFolder folder(argv[1]);
    std::size_t tracked = 0;
    bool more = true;
    const auto submitNext = [&] {
      const std::optional<amos::RgbdImages> frame = folder.next();
      if (frame) slam.submit(frame->bgr, frame->depth, frame->timestamp);
      more = frame.has_value();
    };
    const auto start = std::chrono::steady_clock::now();
    submitNext();
    while (slam.pending() > 0) {
      if (more) submitNext();
      const amos::FrameResult result = slam.next();
      tracked += result.state == amos::TrackingState::kOk;
    }
    slam.finish();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    slam.writeTrajectory(argv[3]);
    const amos::MapSummary map = slam.summary();
    std::printf("amos-slam %s: %zu frames, %zu tracked, %zu keyframes, %zu map points, %.1f fps -> %s\n",
                amos::kVersion, folder.size(), tracked, map.keyframes, map.map_points,
                static_cast<double>(folder.size()) / seconds, argv[3]);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
