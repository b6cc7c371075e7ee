#include "amos/io/libdeflate_threads.h"

#if AMOS_WITH_LIBDEFLATE
#include <algorithm>
#include <memory>

namespace amos::io {

libdeflate_decompressor* threadDecompressor() {
  struct Free {
    void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
  };
  thread_local const std::unique_ptr<libdeflate_decompressor, Free> decompressor(libdeflate_alloc_decompressor());
  return decompressor.get();
}

libdeflate_compressor* threadCompressor(int level) {
  struct Free {
    void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
  };
  thread_local std::unique_ptr<libdeflate_compressor, Free> compressors[10];
  auto& compressor = compressors[std::clamp(level, 1, 9)];
  if (!compressor) compressor.reset(libdeflate_alloc_compressor(std::clamp(level, 1, 9)));
  return compressor.get();
}

}  // namespace amos::io
#endif
