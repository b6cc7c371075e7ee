#include "amos/io/exif_orientation.h"

#include <cstring>

namespace amos::io {
namespace {

constexpr std::uint16_t kOrientationTag = 0x0112;
constexpr std::uint16_t kShortType = 3;
constexpr std::size_t kEntryBytes = 12;

// Reads TIFF's integers in the block's byte order ("II" little-endian, "MM" big-endian).
struct TiffReader {
  const std::uint8_t* data;
  std::size_t size;
  bool little_endian;

  std::uint16_t u16(std::size_t at) const {
    return little_endian ? static_cast<std::uint16_t>(data[at] | (data[at + 1] << 8))
                         : static_cast<std::uint16_t>((data[at] << 8) | data[at + 1]);
  }
  std::uint32_t u32(std::size_t at) const {
    const std::uint32_t low = u16(at + (little_endian ? 0 : 2)), high = u16(at + (little_endian ? 2 : 0));
    return (high << 16) | low;
  }
};

}  // namespace

int exifOrientation(const std::uint8_t* tiff, std::size_t size) {
  if (tiff == nullptr || size < 8) return 1;
  const bool little = std::memcmp(tiff, "II*\0", 4) == 0;
  if (!little && std::memcmp(tiff, "MM\0*", 4) != 0) return 1;
  const TiffReader reader{tiff, size, little};
  const std::uint32_t directory = reader.u32(4);
  if (directory > size - 2) return 1;
  const std::size_t entries = reader.u16(directory);
  for (std::size_t i = 0; i < entries; ++i) {
    const std::size_t entry = directory + 2 + i * kEntryBytes;
    if (entry > size - kEntryBytes) return 1;
    if (reader.u16(entry) != kOrientationTag) continue;
    if (reader.u16(entry + 2) != kShortType) return 1;
    const int orientation = reader.u16(entry + 8);
    return orientation >= 1 && orientation <= 8 ? orientation : 1;
  }
  return 1;
}

void applyExifOrientation(int orientation, cv::Mat& image) {
  // EXIF's values: where row 0 and column 0 of the stored image are seen (1 top-left, 2 top-right, 3 bottom-right,
  // 4 bottom-left, 5 left-top, 6 right-top, 7 right-bottom, 8 left-bottom).
  constexpr int kVertical = 0, kHorizontal = 1, kBoth = -1;
  if (orientation < 2 || orientation > 8) return;
  if (orientation >= 5) cv::transpose(image, image);
  switch (orientation) {
    case 2:
    case 6:
      cv::flip(image, image, kHorizontal);
      break;
    case 3:
    case 7:
      cv::flip(image, image, kBoth);
      break;
    case 4:
    case 8:
      cv::flip(image, image, kVertical);
      break;
    default:
      break;  // 5: the transpose alone
  }
}

}  // namespace amos::io
