#include "amos/io/image_read_flags.h"

#include <fmt/format.h>

#include <opencv2/core.hpp>

namespace amos::io {

std::optional<int> readType(int flags, int file_type) {
  if (flags == kReadUnchanged) return file_type;
  constexpr int kSupported = kReadColor | kReadAnyDepth | kReadAnyColor | kReadIgnoreOrientation;
  if (flags < 0 || (flags & ~kSupported) != 0) return std::nullopt;
  const int depth = (flags & kReadAnyDepth) != 0 ? CV_MAT_DEPTH(file_type) : CV_8U;
  const bool colour = (flags & kReadColor) != 0 || ((flags & kReadAnyColor) != 0 && CV_MAT_CN(file_type) > 1);
  return CV_MAKETYPE(depth, colour ? 3 : 1);
}

bool appliesOrientation(int flags) { return flags != kReadUnchanged && (flags & kReadIgnoreOrientation) == 0; }

std::optional<std::string> sizeProblem(std::uint64_t width, std::uint64_t height) {
  constexpr std::uint64_t kMaxSide = std::uint64_t{1} << 20, kMaxPixels = std::uint64_t{1} << 30;
  if (width <= kMaxSide && height <= kMaxSide && width * height <= kMaxPixels) return std::nullopt;
  return fmt::format("size {}x{} beyond the limits of {} pixels a side and {} pixels", width, height, kMaxSide,
                     kMaxPixels);
}

}  // namespace amos::io
