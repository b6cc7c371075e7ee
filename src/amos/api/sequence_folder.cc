// amos::SequenceFolder (include/amos/sequence_folder.h): io::indexSequence's association and io::readPng's
// decoding, the ones `amos-slam run` reads a folder with, so a program replaying a folder through amos::Slam gives
// it the same pixels and time stamps; and, like the run's reader (io::SequenceReader), a frame that cannot be read
// is skipped with a warning and counted.
#include "amos/sequence_folder.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <mutex>
#include <optional>
#include <thread>

#include "amos/api/logging_default.h"
#include "amos/core/bounded_queue.h"
#include "amos/core/error.h"
#include "amos/io/dataset.h"
#include "amos/io/png_reader.h"

namespace amos {

namespace {

cv::Mat readImage(const std::string& file, int flags, const char* what) {
  io::PngReadInfo info;
  cv::Mat image = io::readPng(file, flags, &info);
  if (image.empty()) {
    throw core::Error(fmt::format("cannot read {} '{}' ({})", what, file,
                                  info.reason.empty() ? "missing, truncated or not an image" : info.reason));
  }
  return image;
}

RgbdImages readFrame(const io::AssociatedFrame& entry) {
  RgbdImages f;
  f.bgr = readImage(entry.rgb_file, io::kReadColor, "colour image");
  f.depth = readImage(entry.depth_file, io::kReadUnchanged, "depth image");
  core::require(f.depth.type() == CV_16UC1,
                fmt::format("depth image '{}' is not 16-bit single-channel", entry.depth_file));
  core::require(f.depth.size() == f.bgr.size(),
                fmt::format("depth image '{}' is {}x{}, its colour image '{}' {}x{}", entry.depth_file,
                            f.depth.cols, f.depth.rows, entry.rgb_file, f.bgr.cols, f.bgr.rows));
  f.timestamp = entry.t_rgb;
  f.rgb_file = entry.rgb_file;
  f.depth_file = entry.depth_file;
  return f;
}

// Frames decoded ahead, in order, by one thread; a frame that cannot be read is warned about, counted and left out.
class Prefetch {
 public:
  static constexpr std::size_t kAhead = 4;
  explicit Prefetch(const io::SequenceIndex& index) : queue_(kAhead), worker_([this, &index] { produce(index); }) {}
  ~Prefetch() {
    queue_.close();
    worker_.join();
  }
  std::optional<RgbdImages> next() { return queue_.pop(); }
  std::size_t skipped() const { return skipped_.load(); }

 private:
  void produce(const io::SequenceIndex& index) {
    for (std::size_t i = 0; i < index.frames.size(); ++i) {
      std::optional<RgbdImages> frame;
      try {
        frame = readFrame(index.frames[i]);
      } catch (const std::exception& e) {
        spdlog::warn("SequenceFolder {}: frame {} skipped: {}", index.dir, i, e.what());
        ++skipped_;
        continue;
      }
      if (!queue_.push(std::move(*frame))) return;  // closed: the folder is going away
    }
    queue_.close();  // the consumer takes what is queued, then nullopt
  }
  core::BoundedQueue<RgbdImages> queue_;
  std::atomic<std::size_t> skipped_{0};
  std::thread worker_;  // last: started once the queue exists
};

}  // namespace

struct SequenceFolder::Impl {
  io::SequenceIndex index;
  mutable std::mutex mutex;            // serialises the calls
  std::unique_ptr<Prefetch> prefetch;  // started by the first next()
};

namespace {

// The folder's state, for the call `method` (a template: SequenceFolder::Impl is private).
template <typename Pointer>
auto& use(const Pointer& impl, const char* method) {
  core::require(impl != nullptr,
                fmt::format("amos::SequenceFolder::{}: this SequenceFolder was moved from", method));
  return *impl;
}

io::SequenceIndex indexFolder(const std::string& dir) {
  api::useDefaultLoggingOnce();
  return io::indexSequence(dir);
}

}  // namespace

SequenceFolder::SequenceFolder(const std::string& dir) : impl_(std::make_unique<Impl>()) {
  impl_->index = indexFolder(dir);
}
SequenceFolder::~SequenceFolder() = default;
SequenceFolder::SequenceFolder(SequenceFolder&&) noexcept = default;
SequenceFolder& SequenceFolder::operator=(SequenceFolder&&) noexcept = default;

std::size_t SequenceFolder::size() const { return use(impl_, "size").index.frames.size(); }

RgbdImages SequenceFolder::read(std::size_t i) const {
  const auto& impl = use(impl_, "read");
  core::require(i < impl.index.frames.size(), fmt::format("amos::SequenceFolder::read: argument 'i' = {}: {} has {} "
                                                          "frames", i, impl.index.dir, impl.index.frames.size()));
  return readFrame(impl.index.frames[i]);
}

std::optional<RgbdImages> SequenceFolder::next() {
  auto& impl = use(impl_, "next");
  std::lock_guard lock(impl.mutex);
  if (!impl.prefetch) impl.prefetch = std::make_unique<Prefetch>(impl.index);
  return impl.prefetch->next();
}

std::size_t SequenceFolder::skipped() const {
  const auto& impl = use(impl_, "skipped");
  std::lock_guard lock(impl.mutex);
  return impl.prefetch ? impl.prefetch->skipped() : 0;
}

std::string SequenceFolder::groundTruthFile() const { return use(impl_, "groundTruthFile").index.groundtruth_file; }

std::string SequenceFolder::dir() const { return use(impl_, "dir").index.dir; }

}  // namespace amos
