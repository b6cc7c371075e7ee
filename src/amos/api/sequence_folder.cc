// amos::SequenceFolder (include/amos/sequence_folder.h): io::indexSequence's association and io::readPng's
// decoding, the ones `amos-slam run` reads a folder with, so a program replaying a folder through amos::Slam gives
// it the same pixels and time stamps.
#include "amos/sequence_folder.h"

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

#include <exception>
#include <optional>
#include <thread>
#include <variant>

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
  f.bgr = readImage(entry.rgb_file, cv::IMREAD_COLOR, "colour image");
  f.depth = readImage(entry.depth_file, cv::IMREAD_UNCHANGED, "depth image");
  f.timestamp = entry.t_rgb;
  f.rgb_file = entry.rgb_file;
  f.depth_file = entry.depth_file;
  return f;
}

// Frames decoded ahead, in order, by one thread; a read error travels in its frame's place and ends the stream.
class Prefetch {
 public:
  static constexpr std::size_t kAhead = 4;
  explicit Prefetch(const io::SequenceIndex& index) : queue_(kAhead), worker_([this, &index] { produce(index); }) {}
  ~Prefetch() {
    queue_.close();
    worker_.join();
  }
  std::optional<RgbdImages> next() {
    std::optional<Item> item = queue_.pop();
    if (!item) return std::nullopt;
    if (auto* error = std::get_if<std::exception_ptr>(&*item)) std::rethrow_exception(*error);
    return std::get<RgbdImages>(std::move(*item));
  }

 private:
  using Item = std::variant<RgbdImages, std::exception_ptr>;
  void produce(const io::SequenceIndex& index) {
    for (const io::AssociatedFrame& entry : index.frames) {
      try {
        if (!queue_.push(readFrame(entry))) return;  // closed: the folder is going away
      } catch (...) {
        queue_.push(std::current_exception());
        break;
      }
    }
    queue_.close();  // the consumer takes what is queued, then nullopt
  }
  core::BoundedQueue<Item> queue_;
  std::thread worker_;  // last: started once the queue exists
};

}  // namespace

struct SequenceFolder::Impl {
  io::SequenceIndex index;
  std::unique_ptr<Prefetch> prefetch;  // started by the first next()
};

SequenceFolder::SequenceFolder(const std::string& dir)
    : impl_(std::make_unique<Impl>(Impl{io::indexSequence(dir), nullptr})) {}
SequenceFolder::~SequenceFolder() = default;
SequenceFolder::SequenceFolder(SequenceFolder&&) noexcept = default;
SequenceFolder& SequenceFolder::operator=(SequenceFolder&&) noexcept = default;

std::size_t SequenceFolder::size() const { return impl_->index.frames.size(); }

RgbdImages SequenceFolder::read(std::size_t i) const {
  core::require(i < size(), fmt::format("SequenceFolder::read({}): {} has {} frames", i, impl_->index.dir, size()));
  return readFrame(impl_->index.frames[i]);
}

std::optional<RgbdImages> SequenceFolder::next() {
  if (!impl_->prefetch) impl_->prefetch = std::make_unique<Prefetch>(impl_->index);
  return impl_->prefetch->next();
}

std::string SequenceFolder::groundTruthFile() const { return impl_->index.groundtruth_file; }

}  // namespace amos
