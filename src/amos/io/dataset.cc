#include "amos/io/dataset.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <filesystem>
#include <vector>
#include <sstream>
#include <thread>
#include <variant>

#include "amos/core/bounded_queue.h"
#include "amos/core/error.h"
#include "amos/io/png_reader.h"
#include "amos/io/text_lines.h"

namespace amos::io {

namespace fs = std::filesystem;

namespace {

struct StampedFile {
  double t = 0;
  std::string file;
};

// The rows of rgb.txt or depth.txt. A row with the stamp of the row before it (a list appended twice, a copy
// gone wrong) is a duplicate: left out, warned about once (count and first line) and counted in `duplicates`.
std::vector<StampedFile> readStampedList(const std::vector<TextLine>& lines, const std::string& path,
                                         std::size_t& duplicates) {
  std::vector<StampedFile> out;
  int first_duplicate_line = 0;
  duplicates = 0;
  for (const auto& line : lines) {
    if (line.fields.size() < 2) {
      throw core::Error(fmt::format("{}:{}: expected 'timestamp filename', got {} field(s)", path, line.number,
                                    line.fields.size()));
    }
    const double stamp = parseNumber(line.fields[0], path, line.number, "timestamp");
    if (!out.empty() && stamp == out.back().t) {
      if (duplicates++ == 0) first_duplicate_line = line.number;
      continue;
    }
    out.push_back({stamp, line.fields[1]});
  }
  if (duplicates > 0) {
    spdlog::warn("{}: {} row(s) repeat the time stamp of the row before (first: line {}); left out", path, duplicates,
                 first_duplicate_line);
  }
  return out;
}

// The rows of an association file; each of its two stamp columns must increase from row to row.
std::vector<AssociatedFrame> readAssociationFile(const std::vector<TextLine>& lines, const std::string& path,
                                                 AssociationStats& stats) {
  std::vector<AssociatedFrame> out;
  int previous_line = 0;
  int first_beyond_line = 0;
  double first_beyond_s = 0;
  auto requireIncreasing = [&](double stamp, double previous, int line, const char* what) {
    if (stamp <= previous) {
      throw core::Error(fmt::format("{}:{}: {} timestamp {:.6f} does not increase (line {} has {:.6f}); the rows of an "
                                    "association file must be in time order",
                                    path, line, what, stamp, previous_line, previous));
    }
  };
  for (const auto& line : lines) {
    if (line.fields.size() < 4) {
      throw core::Error(fmt::format("{}:{}: expected 't_rgb rgb_file t_depth depth_file', got {} field(s)", path,
                                    line.number, line.fields.size()));
    }
    AssociatedFrame f;
    f.t_rgb = parseNumber(line.fields[0], path, line.number, "RGB timestamp");
    f.rgb_file = line.fields[1];
    f.t_depth = parseNumber(line.fields[2], path, line.number, "depth timestamp");
    f.depth_file = line.fields[3];
    if (!out.empty()) {
      requireIncreasing(f.t_rgb, out.back().t_rgb, line.number, "RGB");
      requireIncreasing(f.t_depth, out.back().t_depth, line.number, "depth");
    }
    previous_line = line.number;
    const double difference = std::abs(f.t_rgb - f.t_depth);
    if (difference > stats.window_s) {
      if (stats.rows_beyond_window == 0) first_beyond_line = line.number, first_beyond_s = difference;
      ++stats.rows_beyond_window;
    }
    out.push_back(std::move(f));
  }
  stats.file = path;
  stats.rows = out.size();
  if (stats.rows_beyond_window > 0) {
    spdlog::warn("{}: {} of {} rows pair RGB and depth stamps more than {} s apart (first: line {}, {:.3f} s); their "
                 "depth images may not show what their colour images show",
                 path, stats.rows_beyond_window, stats.rows, stats.window_s, first_beyond_line, first_beyond_s);
  }
  return out;
}

// Pairs the frames of rgb.txt and depth.txt by their stamps.
std::vector<AssociatedFrame> associateLists(const std::vector<StampedFile>& rgb, const std::vector<StampedFile>& depth,
                                            double max_dt) {
  std::vector<double> t_rgb, t_depth;
  for (const auto& s : rgb) t_rgb.push_back(s.t);
  for (const auto& s : depth) t_depth.push_back(s.t);
  std::vector<AssociatedFrame> frames;
  for (const auto& [i, j] : associateStamps(t_rgb, t_depth, max_dt)) {
    frames.push_back({rgb[i].t, depth[j].t, rgb[i].file, depth[j].file});
  }
  return frames;
}

std::string firstExisting(const fs::path& dir, std::initializer_list<const char*> names) {
  for (const char* name : names) {
    if (fs::is_regular_file(dir / name)) return (dir / name).string();
  }
  return {};
}

// Drops entries whose files are missing, warning once per missing file (the first few by name, then a count);
// returns the first missing file of each entry dropped.
std::vector<std::string> dropMissingFiles(std::vector<AssociatedFrame>& frames) {
  constexpr std::size_t kNamedWarnings = 10;
  std::size_t missing = 0;
  std::vector<std::string> dropped;
  auto gone = [&](const std::string& file) {
    if (fs::is_regular_file(file)) return false;
    if (++missing <= kNamedWarnings) spdlog::warn("listed file is missing, frame skipped: {}", file);
    return true;
  };
  frames.erase(std::remove_if(frames.begin(), frames.end(),
                              [&](const AssociatedFrame& f) {
                                const bool rgb_gone = gone(f.rgb_file), depth_gone = gone(f.depth_file);
                                if (rgb_gone || depth_gone) dropped.push_back(rgb_gone ? f.rgb_file : f.depth_file);
                                return rgb_gone || depth_gone;
                              }),
               frames.end());
  if (missing > kNamedWarnings) spdlog::warn("{} listed files are missing in all; their frames were skipped", missing);
  return dropped;
}

}  // namespace

SequenceIndex indexSequence(const std::string& dir, double max_dt) {
  const fs::path root(dir);
  core::require(fs::is_directory(root), fmt::format("sequence folder '{}' does not exist", dir));
  SequenceIndex index;
  index.dir = dir;
  index.association.window_s = max_dt;
  const std::string association = firstExisting(root, {"associations.txt", "associate.txt", "association.txt"});
  if (!association.empty()) {
    index.frames = readAssociationFile(readTextLines(association), association, index.association);
  } else {
    const std::string rgb_list = (root / "rgb.txt").string(), depth_list = (root / "depth.txt").string();
    core::require(fs::is_regular_file(rgb_list) && fs::is_regular_file(depth_list),
                  fmt::format("'{}' has neither an association file nor rgb.txt + depth.txt", dir));
    std::size_t rgb_duplicates = 0, depth_duplicates = 0;
    index.frames = associateLists(readStampedList(readTextLines(rgb_list), rgb_list, rgb_duplicates),
                                  readStampedList(readTextLines(depth_list), depth_list, depth_duplicates), max_dt);
    index.association.duplicate_rows = rgb_duplicates + depth_duplicates;
  }
  for (auto& f : index.frames) {
    f.rgb_file = (root / f.rgb_file).string();
    f.depth_file = (root / f.depth_file).string();
  }
  index.missing = dropMissingFiles(index.frames);
  core::require(!index.frames.empty(), fmt::format("sequence '{}' has no RGB-D frame to read", dir));
  index.groundtruth_file = firstExisting(root, {"groundtruth.txt"});
  return index;
}

std::vector<AssociatedFrame> parseAssociationFile(const std::string& text, const std::string& path, double max_dt,
                                                  AssociationStats& stats) {
  std::istringstream in(text);
  stats.window_s = max_dt;
  return readAssociationFile(readTextLines(in), path, stats);
}

std::vector<AssociatedFrame> associateFrameLists(const std::string& rgb_text, const std::string& rgb_path,
                                                 const std::string& depth_text, const std::string& depth_path,
                                                 double max_dt) {
  std::istringstream rgb_in(rgb_text), depth_in(depth_text);
  std::size_t duplicates = 0;
  return associateLists(readStampedList(readTextLines(rgb_in), rgb_path, duplicates),
                        readStampedList(readTextLines(depth_in), depth_path, duplicates), max_dt);
}

namespace {

void requireSize(cv::Size size, const std::string& file, const char* what, const ReaderOptions& options) {
  if (size.width == options.width && size.height == options.height) return;
  throw FrameLoadError(FrameProblem::kWrongSize, file,
                       fmt::format("{} '{}' is {}x{}, the settings say {}x{}", what, file, size.width, size.height,
                                   options.width, options.height));
}

// The image cv::imread would give, decoded by io::readPng (libdeflate), with the reason when there is none; only
// of the settings' size: a PNG whose header declares another size is refused before its pixels are
// decoded (a bound on the memory a frame takes); other formats are checked once decoded.
cv::Mat readImage(const std::string& file, int flags, const char* what, const ReaderOptions& options) {
  if (const auto declared = pngHeaderSize(file)) requireSize(*declared, file, what, options);
  PngReadInfo info;
  cv::Mat image;
  try {
    image = readPng(file, flags, &info);
  } catch (const cv::Exception& e) {
    throw FrameLoadError(FrameProblem::kUnreadable, file, fmt::format("cannot read {} '{}': {}", what, file, e.what()));
  }
  if (!image.empty()) {
    requireSize(image.size(), file, what, options);
    return image;
  }
  if (!fs::is_regular_file(file))
    throw FrameLoadError(FrameProblem::kMissing, file, fmt::format("{} '{}' is missing", what, file));
  throw FrameLoadError(FrameProblem::kUnreadable, file,
                       fmt::format("cannot read {} '{}' ({})", what, file,
                                   info.reason.empty() ? "truncated or not an image" : info.reason));
}


}  // namespace

namespace {

// A colour image to track: 8-bit BGR of the settings' size, not black throughout.
void checkColour(const cv::Mat& bgr, const AssociatedFrame& entry, const ReaderOptions& options) {
  if (bgr.type() != CV_8UC3) {
    throw FrameLoadError(FrameProblem::kWrongFormat, entry.rgb_file,
                         fmt::format("colour image '{}' has {} channel(s) of {} bits; expected 3 channels of 8 bits",
                                     entry.rgb_file, bgr.channels(), bgr.elemSize1() * 8));
  }
  requireSize(bgr.size(), entry.rgb_file, "colour image", options);
  if (cv::countNonZero(bgr.reshape(1)) == 0) {
    throw FrameLoadError(FrameProblem::kBlank, entry.rgb_file,
                         fmt::format("colour image '{}' is black throughout: nothing to track", entry.rgb_file));
  }
}

// The depth in metres (CV_32F, a new buffer), all zero when the sensor gave (next to) none.
void setDepth(RgbdFrame& frame, const cv::Mat& raw, const AssociatedFrame& entry, const ReaderOptions& options) {
  if (raw.channels() != 1 || (raw.depth() != CV_16U && raw.depth() != CV_32F)) {
    throw FrameLoadError(FrameProblem::kWrongFormat, entry.depth_file,
                         fmt::format("depth image '{}' is {}-bit with {} channel(s); expected a 16-bit single-channel "
                                     "PNG",
                                     entry.depth_file, raw.elemSize1() * 8, raw.channels()));
  }
  requireSize(raw.size(), entry.depth_file, "depth image", options);
  raw.convertTo(frame.depth, CV_32F, raw.depth() == CV_16U ? 1.0 / options.depth_factor : 1.0);
  const cv::Mat valid = frame.depth > 0;  // NaN compares false: not valid
  if (cv::countNonZero(valid) < options.min_valid_depth * static_cast<double>(frame.depth.total())) {
    frame.depth.setTo(0);
    frame.depth_dropout = true;
  }
}

RgbdFrame frameHeader(const AssociatedFrame& entry, std::size_t index) {
  RgbdFrame frame;
  frame.index = index;
  frame.timestamp = entry.t_rgb;
  frame.rgb_file = entry.rgb_file;
  return frame;
}

}  // namespace

RgbdFrame loadRgbdFrame(const AssociatedFrame& entry, const ReaderOptions& options, std::size_t index) {
  RgbdFrame frame = frameHeader(entry, index);
  frame.bgr = readImage(entry.rgb_file, kReadColor, "colour image", options);
  checkColour(frame.bgr, entry, options);
  setDepth(frame, readImage(entry.depth_file, kReadUnchanged, "depth image", options), entry, options);
  return frame;
}

RgbdFrame rgbdFrameFromImages(const AssociatedFrame& entry, cv::Mat bgr, const cv::Mat& raw_depth,
                              const ReaderOptions& options, std::size_t index) {
  RgbdFrame frame = frameHeader(entry, index);
  checkColour(bgr, entry, options);
  frame.bgr = std::move(bgr);
  setDepth(frame, raw_depth, entry, options);
  return frame;
}

struct SequenceReader::Impl {
  SequenceIndex index;
  ReaderOptions options;
  FrameLoader loader;
  using Item = std::variant<RgbdFrame, std::exception_ptr>;
  core::BoundedQueue<Item> queue;
  std::atomic<std::size_t> delivered{0};
  mutable std::mutex skipped_mutex;
  SkippedFrames skipped;  // guarded by skipped_mutex
  std::thread worker;

  Impl(SequenceIndex idx, ReaderOptions opts, FrameLoader load)
      : index(std::move(idx)), options(opts), loader(std::move(load)), queue(std::max<std::size_t>(1, opts.prefetch)) {
    skipped.add(FrameProblem::kMissing, index.missing.size());
    worker = std::thread([this] { produce(); });
  }
  ~Impl() {
    queue.close();
    if (worker.joinable()) worker.join();
  }
  // The item for frame i: the frame, an error that ends the stream, or nothing (skipped).
  std::optional<Item> load(std::size_t i) {
    try {
      RgbdFrame frame = loader(index.frames[i], options, i);
      if (frame.depth_dropout) {
        spdlog::warn("frame {}: depth dropout ('{}' has fewer than {:g} % valid pixels): tracked from its colour "
                     "image alone",
                     i, index.frames[i].depth_file, 100 * options.min_valid_depth);
      }
      return Item(std::move(frame));
    } catch (const FrameLoadError& e) {
      if (options.strict) return Item(std::current_exception());
      spdlog::warn("frame {} skipped ({}): {}", i, frameProblemName(e.problem()), e.what());
      std::lock_guard lock(skipped_mutex);
      skipped.add(e.problem());
      return std::nullopt;
    } catch (...) {
      return Item(std::current_exception());
    }
  }
  void produce() {
    if (options.strict && !index.missing.empty()) {
      const std::string& file = index.missing.front();
      queue.push(std::make_exception_ptr(FrameLoadError(
          FrameProblem::kMissing, file,
          fmt::format("listed file '{}' is missing ({} frame(s) with missing files; --strict)", file,
                      index.missing.size()))));
      queue.close();
      return;
    }
    for (std::size_t i = 0; i < index.frames.size(); ++i) {
      std::optional<Item> item = load(i);
      if (!item) continue;
      const bool failed = std::holds_alternative<std::exception_ptr>(*item);
      if (!queue.push(std::move(*item)) || failed) break;
    }
    queue.close();
  }
};

SequenceReader::SequenceReader(SequenceIndex index, ReaderOptions options, FrameLoader loader)
    : impl_(std::make_unique<Impl>(std::move(index), options, std::move(loader))) {}

SequenceReader::~SequenceReader() = default;

std::optional<RgbdFrame> SequenceReader::next() {
  auto item = impl_->queue.pop();
  if (!item) return std::nullopt;
  if (auto* error = std::get_if<std::exception_ptr>(&*item)) std::rethrow_exception(*error);
  RgbdFrame frame = std::get<RgbdFrame>(std::move(*item));
  frame.arrival = std::chrono::steady_clock::now();
  impl_->delivered.fetch_add(1, std::memory_order_relaxed);
  return frame;
}

std::size_t SequenceReader::size() const { return impl_->index.frames.size(); }
SourceStats SequenceReader::stats() const {
  SourceStats stats;
  stats.delivered = impl_->delivered.load(std::memory_order_relaxed);
  std::lock_guard lock(impl_->skipped_mutex);
  stats.skipped = impl_->skipped;
  return stats;
}
const SequenceIndex& SequenceReader::index() const { return impl_->index; }

}  // namespace amos::io
