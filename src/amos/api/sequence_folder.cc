// amos::SequenceFolder (include/amos/sequence_folder.h): io::indexSequence's association and io::readPng's
// decoding, the ones `amos-slam run` reads a folder with, so a program replaying a folder through amos::Slam gives
// it the same pixels and time stamps; and, like the run's reader (io::SequenceReader), a frame that cannot be read
// is skipped with a warning and counted. A bag's index and frames come from sequence_bag.h.
#include "amos/sequence_folder.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>
#include <tuple>

#include "amos/api/logging_default.h"
#include "amos/api/sequence_bag.h"
#include "amos/core/bounded_queue.h"
#include "amos/core/error.h"
#include "amos/io/dataset.h"
#include "amos/io/png_reader.h"
#include "amos/io/trajectory.h"

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
  Prefetch(const io::SequenceIndex& index, api::FrameReader read)
      : queue_(kAhead), worker_([this, &index, read = std::move(read)] { produce(index, read); }) {}
  ~Prefetch() {
    queue_.close();
    worker_.join();
  }
  std::optional<RgbdImages> next() { return queue_.pop(); }
  std::size_t skipped() const { return skipped_.load(); }

 private:
  void produce(const io::SequenceIndex& index, const api::FrameReader& read) {
    for (std::size_t i = 0; i < index.frames.size(); ++i) {
      std::optional<RgbdImages> frame;
      try {
        frame = read(i);
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
  bool bag = false;
  std::function<api::FrameReader()> make_reader;
  std::optional<std::vector<io::StampedPose>> topic_ground_truth;  // a bag's SequenceOptions::groundtruth_topic
  mutable std::mutex mutex;            // serialises the calls
  std::unique_ptr<Prefetch> prefetch;  // started by the first next()
  mutable std::mutex read_mutex;       // serialises read(i)
  mutable api::FrameReader reader;     // read(i)'s, made by the first
};

namespace {

// The folder's state, for the call `method` (a template: SequenceFolder::Impl is private).
template <typename Pointer>
auto& use(const Pointer& impl, const char* method) {
  core::require(impl != nullptr,
                fmt::format("amos::SequenceFolder::{}: this SequenceFolder was moved from", method));
  return *impl;
}

bool isBagPath(const std::string& path) { return std::filesystem::path(path).extension() == ".bag"; }

void requireNoBagOptions(const std::string& dir, const SequenceOptions& o) {
  const SequenceOptions defaults;
  for (const auto& [name, value, fallback] :
       {std::tuple{"rgb_topic", &o.rgb_topic, &defaults.rgb_topic},
        std::tuple{"depth_topic", &o.depth_topic, &defaults.depth_topic},
        std::tuple{"camera_info_topic", &o.camera_info_topic, &defaults.camera_info_topic},
        std::tuple{"groundtruth_topic", &o.groundtruth_topic, &defaults.groundtruth_topic},
        std::tuple{"groundtruth_parent_frame", &o.groundtruth_parent_frame, &defaults.groundtruth_parent_frame},
        std::tuple{"groundtruth_child_frame", &o.groundtruth_child_frame, &defaults.groundtruth_child_frame}}) {
    core::require(*value == *fallback, fmt::format("amos::SequenceOptions::{} '{}': only for a bag, and '{}' is a "
                                                   "folder",
                                                   name, *value, dir));
  }
}

}  // namespace

bool bagReadingAvailable() { return api::bagsAvailable(); }

SequenceFolder::SequenceFolder(const std::string& path, const SequenceOptions& options)
    : impl_(std::make_unique<Impl>()) {
  api::useDefaultLoggingOnce();
  Impl& impl = *impl_;
  if (isBagPath(path)) {
    api::BagSequence bag = api::openBagSequence(path, options);
    impl.index = std::move(bag.index);
    impl.make_reader = std::move(bag.make_reader);
    impl.topic_ground_truth = std::move(bag.ground_truth);
    impl.bag = true;
    return;
  }
  requireNoBagOptions(path, options);
  impl.index = io::indexSequence(path);
  const io::SequenceIndex* index = &impl.index;  // the Impl stays where it is when the SequenceFolder moves
  impl.make_reader = [index]() -> api::FrameReader {
    return [index](std::size_t i) { return readFrame(index->frames[i]); };
  };
}
SequenceFolder::~SequenceFolder() = default;
SequenceFolder::SequenceFolder(SequenceFolder&&) noexcept = default;
SequenceFolder& SequenceFolder::operator=(SequenceFolder&&) noexcept = default;

std::size_t SequenceFolder::size() const { return use(impl_, "size").index.frames.size(); }

RgbdImages SequenceFolder::read(std::size_t i) const {
  const auto& impl = use(impl_, "read");
  core::require(i < impl.index.frames.size(), fmt::format("amos::SequenceFolder::read: argument 'i' = {}: {} has {} "
                                                          "frames", i, impl.index.dir, impl.index.frames.size()));
  std::lock_guard lock(impl.read_mutex);
  if (!impl.reader) impl.reader = impl.make_reader();
  return impl.reader(i);
}

std::optional<RgbdImages> SequenceFolder::next() {
  auto& impl = use(impl_, "next");
  std::lock_guard lock(impl.mutex);
  if (!impl.prefetch) impl.prefetch = std::make_unique<Prefetch>(impl.index, impl.make_reader());
  return impl.prefetch->next();
}

std::size_t SequenceFolder::skipped() const {
  const auto& impl = use(impl_, "skipped");
  std::lock_guard lock(impl.mutex);
  return impl.prefetch ? impl.prefetch->skipped() : 0;
}

std::string SequenceFolder::groundTruthFile() const { return use(impl_, "groundTruthFile").index.groundtruth_file; }

std::vector<StampedPose> SequenceFolder::groundTruth() const {
  const auto& impl = use(impl_, "groundTruth");
  std::vector<io::StampedPose> poses;
  if (impl.topic_ground_truth) {
    poses = *impl.topic_ground_truth;
  } else if (!impl.index.groundtruth_file.empty()) {
    poses = io::readTumTrajectoryWithPoses(impl.index.groundtruth_file, "ground-truth file");
  }
  std::vector<StampedPose> out;
  out.reserve(poses.size());
  for (const io::StampedPose& p : poses) out.push_back({p.timestamp, p.T_wc.matrix()});
  return out;
}

bool SequenceFolder::isBag() const { return use(impl_, "isBag").bag; }

std::string SequenceFolder::dir() const { return use(impl_, "dir").index.dir; }

}  // namespace amos
