#include "amos/io/pnm_codec.h"

#include <fmt/format.h>

#include <cctype>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "amos/core/error.h"
#include "amos/io/image_read_flags.h"

namespace amos::io {
namespace {

// The header's numbers after the magic "P5"/"P6": whitespace and '#' comments between them, exactly one whitespace
// character after the last.
class HeaderReader {
 public:
  HeaderReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size), position_(2) {}

  std::optional<std::uint32_t> number() {
    skipSpaceAndComments();
    std::uint64_t value = 0;
    const std::size_t start = position_;
    while (position_ < size_ && std::isdigit(data_[position_]) != 0 && value <= 0xffffffffu)
      value = value * 10 + (data_[position_++] - '0');
    if (position_ == start || value > 0xffffffffu) return std::nullopt;
    return static_cast<std::uint32_t>(value);
  }
  // The offset of the pixels: after the single whitespace that ends the header; nullopt when it is missing.
  std::optional<std::size_t> pixelsStart() const {
    if (position_ >= size_ || std::isspace(data_[position_]) == 0) return std::nullopt;
    return position_ + 1;
  }

 private:
  void skipSpaceAndComments() {
    while (position_ < size_) {
      if (data_[position_] == '#') {
        while (position_ < size_ && data_[position_] != '\n') ++position_;
      } else if (std::isspace(data_[position_]) != 0) {
        ++position_;
      } else {
        return;
      }
    }
  }
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t position_;
};

// The samples as stored, in host order, RGB swapped to BGR.
cv::Mat fileImage(const std::uint8_t* pixels, int width, int height, int channels, bool wide) {
  cv::Mat image(height, width, CV_MAKETYPE(wide ? CV_16U : CV_8U, channels));
  const std::size_t row_samples = static_cast<std::size_t>(width) * channels;
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* in = pixels + y * row_samples * (wide ? 2 : 1);
    if (wide) {
      auto* out = image.ptr<std::uint16_t>(y);
      for (std::size_t i = 0; i < row_samples; ++i)
        out[i] = static_cast<std::uint16_t>((in[2 * i] << 8) | in[2 * i + 1]);
    } else {
      std::copy(in, in + row_samples, image.ptr<std::uint8_t>(y));
    }
  }
  if (channels == 3) cv::cvtColor(image, image, cv::COLOR_RGB2BGR);
  return image;
}

// The samples' high bytes, as cv::imread cuts 16-bit PGM/PPM samples to 8 bits.
cv::Mat highBytes(const cv::Mat& wide) {
  cv::Mat narrow(wide.size(), CV_MAKETYPE(CV_8U, wide.channels()));
  const std::size_t samples = static_cast<std::size_t>(wide.cols) * wide.channels();
  for (int y = 0; y < wide.rows; ++y) {
    const auto* in = wide.ptr<std::uint16_t>(y);
    auto* out = narrow.ptr<std::uint8_t>(y);
    for (std::size_t i = 0; i < samples; ++i) out[i] = static_cast<std::uint8_t>(in[i] >> 8);
  }
  return narrow;
}

// BGR made grey with OpenCV's fixed-point weights (0.299 red, 0.587 green, the rest blue, in 1/16384ths, rounded),
// at the image's depth, as cv::imread does for PPM files.
template <typename T>
cv::Mat greyOf(const cv::Mat& bgr) {
  constexpr int kShift = 14, kRed = 4899, kGreen = 9617, kBlue = (1 << kShift) - kRed - kGreen;
  cv::Mat grey(bgr.size(), CV_MAKETYPE(bgr.depth(), 1));
  for (int y = 0; y < bgr.rows; ++y) {
    const T* in = bgr.ptr<T>(y);
    T* out = grey.ptr<T>(y);
    for (int x = 0; x < bgr.cols; ++x, in += 3)
      out[x] = static_cast<T>((in[0] * kBlue + in[1] * kGreen + in[2] * kRed + (1 << (kShift - 1))) >> kShift);
  }
  return grey;
}

// The file's image converted to `type`: depth cut to 8 bits by the high byte, then channels replicated or made grey.
cv::Mat converted(cv::Mat image, int type) {
  if (image.depth() != CV_MAT_DEPTH(type)) image = highBytes(image);
  if (image.channels() == 1 && CV_MAT_CN(type) == 3) cv::cvtColor(image, image, cv::COLOR_GRAY2BGR);
  if (image.channels() == 3 && CV_MAT_CN(type) == 1)
    image = image.depth() == CV_16U ? greyOf<std::uint16_t>(image) : greyOf<std::uint8_t>(image);
  return image;
}

}  // namespace

bool looksLikePnm(const std::uint8_t* data, std::size_t size) {
  return size >= 3 && data[0] == 'P' && (data[1] == '5' || data[1] == '6') && std::isspace(data[2]) != 0;
}

cv::Mat decodePnm(const std::uint8_t* data, std::size_t size, int flags, std::string& problem) {
  if (!looksLikePnm(data, size)) {
    problem = "not a binary PGM or PPM (P5 or P6)";
    return cv::Mat();
  }
  const int channels = data[1] == '6' ? 3 : 1;
  HeaderReader header(data, size);
  const auto width = header.number(), height = header.number(), maxval = header.number();
  const auto start = header.pixelsStart();
  if (!width || !height || !maxval || !start || *width == 0 || *height == 0 || *maxval == 0 || *maxval > 65535) {
    problem = "invalid header (P5 or P6, width, height, maxval from 1 to 65535)";
    return cv::Mat();
  }
  if (auto too_large = sizeProblem(*width, *height)) {
    problem = std::move(*too_large);
    return cv::Mat();
  }
  const bool wide = *maxval > 255;
  const std::uint64_t needed = std::uint64_t{*width} * *height * channels * (wide ? 2 : 1);
  if (size - *start < needed) {
    problem = fmt::format("truncated: {} bytes of pixels for {}x{}, {} needed", size - *start, *width, *height, needed);
    return cv::Mat();
  }
  const std::optional<int> type = readType(flags, CV_MAKETYPE(wide ? CV_16U : CV_8U, channels));
  if (!type) {
    problem = fmt::format("unsupported read flags {}", flags);
    return cv::Mat();
  }
  return converted(fileImage(data + *start, static_cast<int>(*width), static_cast<int>(*height), channels, wide),
                   *type);
}

std::vector<std::uint8_t> encodePnm(const cv::Mat& image) {
  const bool wide = image.depth() == CV_16U;
  core::require(!image.empty() && (image.depth() == CV_8U || wide) && (image.channels() == 1 || image.channels() == 3),
                "PGM/PPM images must be CV_8U or CV_16U with 1 or 3 channels, not type " +
                    cv::typeToString(image.type()) + (image.empty() ? " (empty)" : ""));
  const std::string header =
      fmt::format("P{}\n{} {}\n{}\n", image.channels() == 3 ? 6 : 5, image.cols, image.rows, wide ? 65535 : 255);
  cv::Mat stored;  // a new buffer: the caller's image is const
  if (image.channels() == 3) {
    cv::cvtColor(image, stored, cv::COLOR_BGR2RGB);
  } else {
    stored = image;
  }
  std::vector<std::uint8_t> bytes(header.begin(), header.end());
  bytes.reserve(header.size() + stored.total() * stored.elemSize());
  for (int y = 0; y < stored.rows; ++y) {
    const std::size_t samples = static_cast<std::size_t>(stored.cols) * stored.channels();
    if (wide) {
      const auto* row = stored.ptr<std::uint16_t>(y);
      for (std::size_t i = 0; i < samples; ++i) {
        bytes.push_back(static_cast<std::uint8_t>(row[i] >> 8));
        bytes.push_back(static_cast<std::uint8_t>(row[i] & 0xff));
      }
    } else {
      const auto* row = stored.ptr<std::uint8_t>(y);
      bytes.insert(bytes.end(), row, row + samples);
    }
  }
  return bytes;
}

}  // namespace amos::io
