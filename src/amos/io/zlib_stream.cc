#include "amos/io/zlib_stream.h"

#include <fmt/format.h>

#include <algorithm>
#include <memory>

#include "amos/core/error.h"

#ifdef AMOS_WITH_LIBDEFLATE
#include <libdeflate.h>
#else
#include <zlib.h>
#endif

namespace amos::io {

#ifdef AMOS_WITH_LIBDEFLATE
namespace {

// One compressor per level and thread: allocating one costs more than compressing a small image.
libdeflate_compressor* threadCompressor(int level) {
  struct Free {
    void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
  };
  thread_local std::unique_ptr<libdeflate_compressor, Free> compressors[10];
  auto& compressor = compressors[level];
  if (!compressor) compressor.reset(libdeflate_alloc_compressor(level));
  core::require(compressor != nullptr, "libdeflate could not allocate a compressor");
  return compressor.get();
}

libdeflate_decompressor* threadDecompressor() {
  struct Free {
    void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
  };
  thread_local const std::unique_ptr<libdeflate_decompressor, Free> decompressor(libdeflate_alloc_decompressor());
  core::require(decompressor != nullptr, "libdeflate could not allocate a decompressor");
  return decompressor.get();
}

}  // namespace

std::vector<std::uint8_t> deflateBytes(const void* data, std::size_t size, int level) {
  libdeflate_compressor* compressor = threadCompressor(std::clamp(level, 1, 9));
  std::vector<std::uint8_t> out(libdeflate_zlib_compress_bound(compressor, size));
  out.resize(libdeflate_zlib_compress(compressor, data, size, out.data(), out.size()));
  core::require(!out.empty(), "libdeflate could not compress the bytes");
  return out;
}

void inflateBytes(const std::vector<std::uint8_t>& stream, void* out, std::size_t size) {
  std::size_t written = 0;
  const libdeflate_result result =
      libdeflate_zlib_decompress(threadDecompressor(), stream.data(), stream.size(), out, size, &written);
  core::require(result == LIBDEFLATE_SUCCESS && written == size,
                fmt::format("a zlib stream of {} bytes does not inflate to {} bytes", stream.size(), size));
}

#else

std::vector<std::uint8_t> deflateBytes(const void* data, std::size_t size, int level) {
  uLongf bytes = compressBound(static_cast<uLong>(size));
  std::vector<std::uint8_t> out(bytes);
  core::require(compress2(out.data(), &bytes, static_cast<const Bytef*>(data), static_cast<uLong>(size),
                          std::clamp(level, 1, 9)) == Z_OK,
                "zlib could not compress the bytes");
  out.resize(bytes);
  return out;
}

void inflateBytes(const std::vector<std::uint8_t>& stream, void* out, std::size_t size) {
  uLongf written = static_cast<uLongf>(size);
  const int result = uncompress(static_cast<Bytef*>(out), &written, stream.data(), static_cast<uLong>(stream.size()));
  core::require(result == Z_OK && written == size,
                fmt::format("a zlib stream of {} bytes does not inflate to {} bytes", stream.size(), size));
}

#endif

}  // namespace amos::io
