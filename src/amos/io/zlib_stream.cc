#include "amos/io/zlib_stream.h"

#include <fmt/format.h>

#include <algorithm>

#include "amos/core/error.h"

#if AMOS_WITH_LIBDEFLATE
#include "amos/io/libdeflate_threads.h"
#else
#include <zlib.h>
#endif

namespace amos::io {

#if AMOS_WITH_LIBDEFLATE

std::vector<std::uint8_t> deflateBytes(const void* data, std::size_t size, int level) {
  libdeflate_compressor* compressor = threadCompressor(level);
  core::require(compressor != nullptr, "libdeflate could not allocate a compressor");
  std::vector<std::uint8_t> out(libdeflate_zlib_compress_bound(compressor, size));
  out.resize(libdeflate_zlib_compress(compressor, data, size, out.data(), out.size()));
  core::require(!out.empty(), "libdeflate could not compress the bytes");
  return out;
}

void inflateBytes(const std::vector<std::uint8_t>& stream, void* out, std::size_t size) {
  std::size_t written = 0;
  libdeflate_decompressor* decompressor = threadDecompressor();
  core::require(decompressor != nullptr, "libdeflate could not allocate a decompressor");
  const libdeflate_result result =
      libdeflate_zlib_decompress(decompressor, stream.data(), stream.size(), out, size, &written);
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
