#include "amos/io/sequence_recorder.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "amos/core/bounded_queue.h"
#include "amos/core/error.h"
#include "amos/io/image_codecs.h"

namespace amos::io {

namespace fs = std::filesystem;

std::string stampText(double timestamp) {
  const std::string fixed = fmt::format("{:.6f}", timestamp);
  if (std::strtod(fixed.c_str(), nullptr) == timestamp) return fixed;
  return fmt::format("{}", timestamp);  // shortest text that reads back to the same double
}

namespace {

// Metres -> raw 16-bit at `factor`; 0 where there is no depth or it does not fit.
cv::Mat rawDepth(const cv::Mat& metres, double factor) {
  core::require(metres.type() == CV_32F, "recorder: depth must be CV_32F metres");
  cv::Mat raw(metres.size(), CV_16U);
  const double max_metres = 65535.5 / factor;
  for (int r = 0; r < metres.rows; ++r) {
    const float* in = metres.ptr<float>(r);
    auto* out = raw.ptr<std::uint16_t>(r);
    for (int c = 0; c < metres.cols; ++c) {
      const double d = in[c];
      out[c] = d > 0 && d < max_metres ? static_cast<std::uint16_t>(cvRound(d * factor)) : 0;  // NaN fails d > 0
    }
  }
  return raw;
}

std::ofstream openList(const fs::path& path, const char* what) {
  std::ofstream out(path);
  core::require(out.good(), fmt::format("cannot write {}", path.string()));
  out << "# " << what << " recorded by amos-slam run --record\n# timestamp filename\n";
  return out;
}

}  // namespace

struct SequenceRecorder::Impl {
  std::string dir;
  double depth_factor;
  core::BoundedQueue<RgbdFrame> queue;
  std::ofstream rgb_list, depth_list;
  std::string last_stamp;  // consumer side: duplicate detection
  std::atomic<std::size_t> written{0};
  std::mutex error_mutex;
  std::exception_ptr error;
  bool finished = false;
  std::thread writer;  // last: started when everything it uses exists

  Impl(const std::string& d, double factor, std::size_t capacity)
      : dir(d), depth_factor(factor), queue(capacity) {
    core::require(factor > 0, fmt::format("recorder: depth factor must be positive, got {}", factor));
    for (const fs::path& p : {fs::path(dir), fs::path(dir) / "rgb", fs::path(dir) / "depth"}) {
      std::error_code ec;
      fs::create_directories(p, ec);
      core::require(!ec && fs::is_directory(p),
                    fmt::format("cannot create recording folder {}{}", p.string(), ec ? ": " + ec.message() : ""));
    }
    rgb_list = openList(fs::path(dir) / "rgb.txt", "color images");
    depth_list = openList(fs::path(dir) / "depth.txt", "depth maps");
    writer = std::thread([this] { run(); });
  }

  std::exception_ptr firstError() {
    std::lock_guard<std::mutex> lock(error_mutex);
    return error;
  }

  void write(const RgbdFrame& frame) {
    const std::string stamp = stampText(frame.timestamp);
    const std::string rgb_name = "rgb/" + stamp + ".png", depth_name = "depth/" + stamp + ".png";
    const fs::path root(dir);
    core::require(!frame.bgr.empty() && frame.bgr.type() == CV_8UC3,
                  fmt::format("recorder: frame {} has no 8-bit colour image", stamp));
    writeImage((root / rgb_name).string(), frame.bgr);
    writeImage((root / depth_name).string(), rawDepth(frame.depth, depth_factor));
    rgb_list << stamp << ' ' << rgb_name << '\n';
    depth_list << stamp << ' ' << depth_name << '\n';
    core::require(rgb_list.good() && depth_list.good(), fmt::format("cannot write the lists in {}", dir));
    written.fetch_add(1, std::memory_order_relaxed);
  }

  void run() {
    while (auto frame = queue.pop()) {
      if (firstError()) continue;  // drain, so add() never blocks on a dead writer
      try {
        write(*frame);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        error = std::current_exception();
      }
    }
  }

  void finish() {
    if (finished) return;
    finished = true;
    queue.close();
    if (writer.joinable()) writer.join();
    rgb_list.close();
    depth_list.close();
    if (auto e = firstError()) std::rethrow_exception(e);
    core::require(!rgb_list.fail() && !depth_list.fail(), fmt::format("cannot write the lists in {}", dir));
  }
};

SequenceRecorder::SequenceRecorder(const std::string& dir, double depth_factor, std::size_t queue_capacity)
    : impl_(std::make_unique<Impl>(dir, depth_factor, queue_capacity)) {}

SequenceRecorder::~SequenceRecorder() {
  try {
    impl_->finish();
  } catch (const std::exception& e) {
    spdlog::error("recording in {} is incomplete: {}", impl_->dir, e.what());
  }
}

void SequenceRecorder::add(const RgbdFrame& frame) {
  core::require(!impl_->finished, "recorder: add() after finish()");
  if (auto e = impl_->firstError()) std::rethrow_exception(e);
  const std::string stamp = stampText(frame.timestamp);
  if (stamp == impl_->last_stamp) {
    spdlog::warn("recorder: frame {} has the same time stamp {} as the one before; not recorded", frame.index,
                 stamp);
    return;
  }
  impl_->last_stamp = stamp;
  impl_->queue.push(frame);
}

void SequenceRecorder::finish() { impl_->finish(); }
std::size_t SequenceRecorder::framesWritten() const { return impl_->written.load(std::memory_order_relaxed); }
const std::string& SequenceRecorder::dir() const { return impl_->dir; }

}  // namespace amos::io
