#include "amos/core/binary_stream.h"

#include <fmt/format.h>

#include <array>

namespace amos::core {

namespace {
std::array<std::uint32_t, 256> makeCrcTable() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[i] = c;
  }
  return table;
}
}  // namespace

std::uint32_t crc32(std::string_view bytes) {
  static const std::array<std::uint32_t, 256> table = makeCrcTable();  // immutable after first use
  std::uint32_t c = 0xFFFFFFFFu;
  for (const char ch : bytes) c = table[(c ^ static_cast<std::uint8_t>(ch)) & 0xFFu] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

void ByteReader::getBytes(void* out, std::size_t n, const char* what) {
  if (n > remaining()) {
    fail(fmt::format("malformed: {} needs {} bytes at byte {}, only {} left", what, n, offset_, remaining()));
  }
  std::memcpy(out, bytes_.data() + offset_, n);
  offset_ += n;
}

std::size_t ByteReader::getCount(std::size_t item_bytes, const char* what) {
  const auto n = get<std::uint64_t>(what);
  if (item_bytes > 0 && n > remaining() / item_bytes) {
    fail(fmt::format("malformed: {} is {} at byte {}, more than the {} bytes left can hold", what, n, offset_,
                     remaining()));
  }
  return static_cast<std::size_t>(n);
}

void ByteReader::fail(const std::string& problem) const { throw Error(source_ + ": " + problem); }

}  // namespace amos::core
