#pragma once
// A live RGB-D camera through OpenNI2 (ASUS Xtion, PrimeSense Carmine, Kinect with an OpenNI2 driver, ...) as an
// io::FrameSource: `amos-slam run --camera openni2[:URI]`.
//   - opens the device by URI, or the first device OpenNI2 finds;
//   - starts colour (RGB888) and depth (1 mm) streams at width x height @ fps (640 x 480 @ 30 by default), depth
//     registered to colour (IMAGE_REGISTRATION_DEPTH_TO_COLOR), colour-depth frame sync on, mirroring off;
//   - pairs each colour frame with the depth frame whose device time stamp is within max_pair_dt and hands the
//     pair out as one RgbdFrame: BGR CV_8UC3, CV_32F metres (0 = no depth), timestamp = the colour frame's device
//     time stamp (microseconds) in seconds, index = number of frames paired before it;
//   - like the replay, keeps only the newest pair waiting (io::NewestFrameSlot): pairs the consumer was too busy
//     for are counted as dropped.
// Threading: OpenNI2 calls this source from its own thread on every new frame; next() / poll() are called from
// the consumer's thread. A device that disconnects ends the stream with a core::Error from next().
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "amos/io/frame_source.h"

namespace amos::camera {

struct OpenNI2Options {
  std::string uri;  // "" = any device
  int width = 640, height = 480, fps = 30;
  double max_pair_dt = 0.02;  // s: colour and depth frames further apart are not paired
};

class OpenNI2Source : public io::FrameSource {
 public:
  // Throws core::Error saying what OpenNI2 reported (its extended error) and which devices it found, when the
  // device cannot be opened or does not support the streams above.
  explicit OpenNI2Source(const OpenNI2Options& options);
  // Stops the streams and closes the device; frames not taken are discarded.
  ~OpenNI2Source() override;
  OpenNI2Source(const OpenNI2Source&) = delete;
  OpenNI2Source& operator=(const OpenNI2Source&) = delete;

  std::optional<io::RgbdFrame> next() override;
  // A next() that waits for the device returns nullopt at once.
  void cancel() override;
  std::optional<io::RgbdFrame> poll() override;
  std::size_t size() const override { return 0; }
  io::SourceStats stats() const override;
  // "<device name> (<uri>)"
  const std::string& description() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace amos::camera
