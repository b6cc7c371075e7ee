// amos::SequenceFolder (include/amos/sequence_folder.h): io::indexSequence's association and io::readPng's
// decoding, the ones `amos-slam run` reads a folder with, so a program replaying a folder through amos::Slam gives
// it the same pixels and time stamps.
#include "amos/sequence_folder.h"

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

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

}  // namespace

struct SequenceFolder::Impl {
  io::SequenceIndex index;
};

SequenceFolder::SequenceFolder(const std::string& dir)
    : impl_(std::make_unique<Impl>(Impl{io::indexSequence(dir)})) {}
SequenceFolder::~SequenceFolder() = default;
SequenceFolder::SequenceFolder(SequenceFolder&&) noexcept = default;
SequenceFolder& SequenceFolder::operator=(SequenceFolder&&) noexcept = default;

std::size_t SequenceFolder::size() const { return impl_->index.frames.size(); }

RgbdImages SequenceFolder::read(std::size_t i) const {
  core::require(i < size(), fmt::format("SequenceFolder::read({}): {} has {} frames", i, impl_->index.dir, size()));
  const io::AssociatedFrame& entry = impl_->index.frames[i];
  RgbdImages f;
  f.bgr = readImage(entry.rgb_file, cv::IMREAD_COLOR, "colour image");
  f.depth = readImage(entry.depth_file, cv::IMREAD_UNCHANGED, "depth image");
  f.timestamp = entry.t_rgb;
  f.rgb_file = entry.rgb_file;
  f.depth_file = entry.depth_file;
  return f;
}

std::string SequenceFolder::groundTruthFile() const { return impl_->index.groundtruth_file; }

}  // namespace amos
