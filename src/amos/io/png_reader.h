#pragma once
// A PNG reader that gives exactly what cv::imread gives, faster on the PNGs datasets use: the zlib stream is
// inflated by libdeflate (2-3x faster than zlib's inflate, which dominates cv::imread's cost) and the rows are
// un-filtered here. What this fast path does not decode goes to the general decoders (image_decoders.h: libpng with
// cv::imread's transforms for other PNGs, libjpeg for JPEG, PGM/PPM), so that readPng reads any image the project's
// codecs read (io::readImage is readPng).
//
// Decoded here, with kReadColor or kReadUnchanged (image_read_flags.h; the former may carry kReadIgnoreOrientation):
// non-interlaced PNGs of bit depth 8 or 16 in colour type grey, grey+alpha, RGB or RGBA, giving
//   IMREAD_COLOR      CV_8UC3 BGR: RGB swapped, alpha dropped, grey replicated, 16-bit samples cut to their high
//                     byte (as libpng's png_set_strip_16, which cv::imread uses)
//   IMREAD_UNCHANGED  grey: CV_8UC1 / CV_16UC1; RGB: CV_8UC3 / CV_16UC3 BGR; RGBA and grey+alpha: CV_8UC4 /
//                     CV_16UC4 BGRA (grey replicated); 16-bit samples in host byte order (PNG's are big-endian)
//
// Handed to the general decoders, whose result is still cv::imread's: other flags; interlaced, palette and 1/2/4-bit
// PNGs; a tRNS chunk; an eXIf chunk when the orientation would be applied; critical chunks other than
// IHDR/IDAT/IEND; IDAT chunks that are not consecutive; a zlib stream that libdeflate rejects although the CRCs are
// right, or that inflates to more than the image needs (zlib has the last word); bytes that are not a PNG (JPEG,
// PGM and PPM are decoded, anything else gives an empty Mat); every PNG when the build has no libdeflate
// (AMOS_WITH_LIBDEFLATE off). A PNG is handed over only after its chunks were walked and checked as below (with
// libdeflate), since libpng's decoder allocates the image its header declares before it finds the data missing.
//
// Rejected here, because libpng or OpenCV reject them too: a missing or empty file; a truncated file (it ends before
// IEND); a CRC mismatch in IHDR, IDAT or IEND; an invalid IHDR; a size beyond libpng's limit of 1000000 pixels a side
// or OpenCV's of 2^30 pixels; no IDAT; image data too short for the declared size (DEFLATE inflates a byte to at most
// 1032, so a header claiming more than its IDAT chunks can hold is refused before anything of that size is
// allocated) or that un-filters with an invalid filter type. The result is then an empty Mat, as from cv::imread
// (the caller reports it, e.g. loadRgbdFrame's error naming the file); readPng also logs a warning naming the file
// and the problem, unless the caller takes the reason through `info` to report it itself. So is anything the
// general decoders cannot decode, with their reason.
// Every length is checked before it is used. The CRCs of the critical chunks are checked (libdeflate_crc32, about
// 50 us for a 440 kB frame, 2 % of its decoding; libpng checks them too); those of ancillary chunks are not: such
// chunks are skipped, as libpng skips them after a warning.
//
// Thread-safe: each thread has its own libdeflate decompressor and scratch buffers (thread_local; the buffers grow
// to the largest PNG the thread read, 2.3 MB for a 640x480 RGB frame, and are freed beyond 64 MB).
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "amos/io/image_read_flags.h"

namespace amos::io {

// How decodePng / readPng got their result.
enum class PngRoute {
  decoded,   // decoded here with libdeflate
  general,   // handed to the general decoders (see above for when), which decoded it
  rejected,  // not decodable (see above): the result is empty
};

struct PngReadInfo {
  PngRoute route = PngRoute::general;
  std::string reason;  // why it went to the general decoders or was rejected; empty when decoded here
};

// True when this build decodes PNGs here (AMOS_WITH_LIBDEFLATE); false when every PNG goes to libpng.
bool pngFastPathAvailable();

// The image cv::imdecode(bytes, imread_flags) gives, for `size` bytes at `data` (empty when size is 0). `info`, when
// given, receives the route and its reason.
cv::Mat decodePng(const std::uint8_t* data, std::size_t size, int imread_flags, PngReadInfo* info = nullptr);

// The image cv::imread(path, imread_flags) gives (see above); when it is rejected, logs a warning naming `path`
// unless `info` is given (the caller then reports info->reason).
cv::Mat readPng(const std::string& path, int imread_flags, PngReadInfo* info = nullptr);

// The image size a PNG file's header (its IHDR chunk, the first 33 bytes) declares, read without decoding the
// pixels: so that an image of the wrong size is refused before it takes memory (a 20000x20000 frame would need
// 1.2 GB). nullopt when the file cannot be opened or does not start with a PNG signature and an IHDR chunk.
std::optional<cv::Size> pngHeaderSize(const std::string& path);

}  // namespace amos::io
