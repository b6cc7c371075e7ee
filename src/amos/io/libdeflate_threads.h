#pragma once
// One libdeflate compressor per level and one decompressor per thread, made on first use and kept for the thread's
// life: allocating one costs more than (de)compressing a small image. For the io module's own files built with
// libdeflate (AMOS_WITH_LIBDEFLATE): png_reader.cc, zlib_stream.cc.
#if AMOS_WITH_LIBDEFLATE
#include <libdeflate.h>

namespace amos::io {

// nullptr when libdeflate cannot allocate one.
libdeflate_decompressor* threadDecompressor();
// level: 1 to 9 (clamped). nullptr when libdeflate cannot allocate one.
libdeflate_compressor* threadCompressor(int level);

}  // namespace amos::io
#endif
