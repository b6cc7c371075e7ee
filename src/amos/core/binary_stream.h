#pragma once
// Little helpers for binary files: a growing byte buffer to write plain values into, a bounds-checked reader over
// bytes, and the CRC-32 (IEEE 802.3, the checksum of zlib and PNG) of a byte range.
//
// Values are stored in the machine's byte order; the formats that use these helpers say little-endian and check
// it (this project builds for x86-64 and arm64 only, both little-endian).
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>

#include "amos/core/error.h"

namespace amos::core {

// CRC-32 of `bytes` (polynomial 0xEDB88320 reflected, initial and final xor 0xFFFFFFFF).
std::uint32_t crc32(std::string_view bytes);

class ByteWriter {
 public:
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>, "plain values only");
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void putBytes(const void* data, std::size_t n) { bytes_.append(static_cast<const char*>(data), n); }
  const std::string& bytes() const { return bytes_; }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

// Reads plain values in order; reading past the end throws Error naming `source` and what was being read.
class ByteReader {
 public:
  ByteReader(std::string_view bytes, std::string source) : bytes_(bytes), source_(std::move(source)) {}

  template <typename T>
  T get(const char* what) {
    static_assert(std::is_trivially_copyable_v<T>, "plain values only");
    T value;
    getBytes(&value, sizeof(T), what);
    return value;
  }
  void getBytes(void* out, std::size_t n, const char* what);
  // A count of items of `item_bytes` each that must still fit in the rest of the bytes (so a corrupt count
  // cannot make the caller allocate gigabytes).
  std::size_t getCount(std::size_t item_bytes, const char* what);
  std::size_t offset() const { return offset_; }
  std::size_t remaining() const { return bytes_.size() - offset_; }
  [[noreturn]] void fail(const std::string& problem) const;

 private:
  std::string_view bytes_;
  std::string source_;
  std::size_t offset_ = 0;
};

}  // namespace amos::core
