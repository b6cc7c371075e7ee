#include "amos/io/png_reader.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <new>
#include <optional>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

#include "amos/io/image_decoders.h"
#include "amos/io/image_read_flags.h"

#include "amos/io/libdeflate_threads.h"
#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/asan_interface.h>
#endif

namespace amos::io {
namespace {

struct Decoded {
  cv::Mat image;
  PngReadInfo info;
};

// Grow-only memory reused by one thread's calls, so that a frame's buffers (file bytes, joined IDAT data, inflated
// rows: 2.3 MB for a 640x480 RGB frame) are not page-faulted in anew for every frame. A buffer larger than
// kKeptBytes is freed after the call that needed it.
class ScratchBuffer {
 public:
  std::uint8_t* reserve(std::size_t size) {
    if (size > capacity_) {
      data_.reset();
      data_.reset(new std::uint8_t[size]);
      capacity_ = size;
    }
#if defined(__SANITIZE_ADDRESS__)
    // Under AddressSanitizer only the bytes asked for are addressable, as in a fresh allocation of `size`.
    ASAN_UNPOISON_MEMORY_REGION(data_.get(), size);
    ASAN_POISON_MEMORY_REGION(data_.get() + size, capacity_ - size);
#endif
    return data_.get();
  }
  void trim() {
    if (capacity_ > kKeptBytes) {
      data_.reset();
      capacity_ = 0;
    }
  }

 private:
  static constexpr std::size_t kKeptBytes = std::size_t{64} << 20;
  std::unique_ptr<std::uint8_t[]> data_;
  std::size_t capacity_ = 0;
};

struct Scratch {
  ScratchBuffer file, idat, rows;
  void trim() {
    file.trim();
    idat.trim();
    rows.trim();
  }
};

Scratch& threadScratch() {
  thread_local Scratch scratch;
  return scratch;
}

#if AMOS_WITH_LIBDEFLATE

// The flags a PNG is decoded here for.
enum class Mode { colour, unchanged };

std::optional<Mode> modeOf(int imread_flags) {
  if (imread_flags == kReadUnchanged) return Mode::unchanged;
  if ((imread_flags & ~kReadIgnoreOrientation) == kReadColor) return Mode::colour;
  return std::nullopt;
}

// Thrown inside the fast path to leave it: route general or rejected, with the reason.
struct Handoff {
  PngRoute route;
  std::string reason;
};

[[noreturn]] void handOver(std::string reason) { throw Handoff{PngRoute::general, std::move(reason)}; }
[[noreturn]] void reject(std::string reason) { throw Handoff{PngRoute::rejected, std::move(reason)}; }

constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

std::uint32_t be32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

constexpr std::uint32_t chunkType(const char (&name)[5]) {
  return (std::uint32_t(std::uint8_t(name[0])) << 24) | (std::uint32_t(std::uint8_t(name[1])) << 16) |
         (std::uint32_t(std::uint8_t(name[2])) << 8) | std::uint32_t(std::uint8_t(name[3]));
}
constexpr std::uint32_t kIHDR = chunkType("IHDR"), kIDAT = chunkType("IDAT"), kIEND = chunkType("IEND"),
                        ktRNS = chunkType("tRNS"), keXIf = chunkType("eXIf");

// A chunk type for messages: its four letters, or its hexadecimal value when they are not letters.
std::string typeName(std::uint32_t type) {
  std::string name;
  for (int shift = 24; shift >= 0; shift -= 8) {
    const char c = static_cast<char>((type >> shift) & 0xff);
    if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'))) return fmt::format("0x{:08x}", type);
    name += c;
  }
  return name;
}

// libpng's default user limit on width and height (png_set_user_limits); OpenCV's limit on pixels
// (CV_IO_MAX_IMAGE_PIXELS), which the general decoders keep.
constexpr std::uint32_t kMaxSide = 1000000;
constexpr std::uint64_t kMaxPixels = std::uint64_t{1} << 30;
// DEFLATE expands one compressed byte into at most 4 * 258 bytes: an image that needs more than this many bytes
// per IDAT byte is truncated, whatever its header claims (this also bounds the allocation a corrupt header asks for).
constexpr std::uint64_t kMaxInflateRatio = 1032;

struct PngLayout {
  std::uint32_t width = 0, height = 0;
  int bit_depth = 0;
  int channels = 0;  // samples per pixel: grey or palette 1, grey+alpha 2, RGB 3, RGBA 4
  bool interlaced = false;
  std::vector<std::pair<const std::uint8_t*, std::size_t>> idat;  // the IDAT chunks' data, in order
  std::size_t idat_bytes = 0;
  // Why the general decoders decode it, when they do (the first reason found); the chunks are still walked, so that
  // a PNG handed over is checked as much as one decoded here (its CRCs, and its image data against its size).
  std::optional<std::string> handover_reason;
};

void handOverLater(PngLayout& layout, std::string reason) {
  if (!layout.handover_reason) layout.handover_reason = std::move(reason);
}

// Reads IHDR's fields into `layout`; rejects what libpng rejects (png_check_IHDR), hands over what is valid but not
// handled here.
void readHeader(const std::uint8_t* ihdr, PngLayout& layout) {
  layout.width = be32(ihdr);
  layout.height = be32(ihdr + 4);
  const int bit_depth = ihdr[8], colour_type = ihdr[9], compression = ihdr[10], filter = ihdr[11],
            interlace = ihdr[12];
  if (layout.width == 0 || layout.height == 0 || layout.width > 0x7fffffffu || layout.height > 0x7fffffffu)
    reject(fmt::format("IHDR has an invalid size {}x{}", layout.width, layout.height));
  const bool depth_ok = (colour_type == 0 && (bit_depth == 1 || bit_depth == 2 || bit_depth == 4 ||
                                              bit_depth == 8 || bit_depth == 16)) ||
                        (colour_type == 3 && (bit_depth == 1 || bit_depth == 2 || bit_depth == 4 || bit_depth == 8)) ||
                        ((colour_type == 2 || colour_type == 4 || colour_type == 6) &&
                         (bit_depth == 8 || bit_depth == 16));
  if (!depth_ok) reject(fmt::format("IHDR has an invalid colour type {} with bit depth {}", colour_type, bit_depth));
  if (compression != 0 || filter != 0 || interlace > 1)
    reject(fmt::format("IHDR has an invalid compression ({}), filter ({}) or interlace ({}) method", compression,
                       filter, interlace));
  // libpng (png_set_user_limits) or OpenCV (CV_IO_MAX_IMAGE_PIXELS; cv::imread throws) refuse these too.
  if (layout.width > kMaxSide || layout.height > kMaxSide ||
      std::uint64_t{layout.width} * layout.height > kMaxPixels)
    reject(fmt::format("size {}x{} beyond the limits of {} pixels a side and {} pixels", layout.width, layout.height,
                       kMaxSide, kMaxPixels));
  layout.bit_depth = bit_depth;
  layout.channels = colour_type == 0 || colour_type == 3 ? 1 : colour_type == 4 ? 2 : colour_type == 2 ? 3 : 4;
  layout.interlaced = interlace != 0;
  if (interlace != 0) handOverLater(layout, "interlaced");
  if (colour_type == 3) handOverLater(layout, "palette colour type");
  if (bit_depth < 8) handOverLater(layout, fmt::format("bit depth {}", bit_depth));
}

// The fewest bytes the inflated image data of `layout` can have: exact without interlacing (a filter byte and the
// packed samples of each row); with it, at least the packed samples of all the pixels.
std::uint64_t minimumImageDataBytes(const PngLayout& layout) {
  const std::uint64_t bits_per_pixel = std::uint64_t(layout.channels) * layout.bit_depth;
  if (layout.interlaced) return (std::uint64_t{layout.width} * layout.height * bits_per_pixel + 7) / 8;
  return std::uint64_t{layout.height} * (1 + (layout.width * bits_per_pixel + 7) / 8);
}

// Rejects a header that claims more pixels than its image data can inflate to, before anything of the image's
// size is allocated (here or by libpng's decoder, which allocates the image from the header before it reads the data).
void requireImageDataFor(const PngLayout& layout) {
  if (minimumImageDataBytes(layout) > kMaxInflateRatio * layout.idat_bytes)
    reject(fmt::format("the image data ({} bytes) is too short for {}x{}", layout.idat_bytes, layout.width,
                       layout.height));
}

void checkCrc(std::uint32_t type, const std::uint8_t* type_and_data, std::uint32_t length) {
  const std::uint32_t stored = be32(type_and_data + 4 + length);
  if (libdeflate_crc32(0, type_and_data, std::size_t{length} + 4) != stored)
    reject(fmt::format("CRC mismatch in chunk {}", typeName(type)));
}

// Walks the chunks from the signature to IEND.
PngLayout readChunks(const std::uint8_t* data, std::size_t size, bool orientation_applies) {
  if (size < sizeof(kSignature) || std::memcmp(data, kSignature, sizeof(kSignature)) != 0)
    handOver("no PNG signature");
  PngLayout layout;
  std::size_t pos = sizeof(kSignature);
  bool in_idat = false, after_idat = false;
  for (bool first = true;; first = false) {
    if (size - pos < 8) reject("truncated: the file ends before the IEND chunk");
    const std::uint32_t length = be32(data + pos), type = be32(data + pos + 4);
    if (length > 0x7fffffffu) reject(fmt::format("chunk {} has the invalid length {}", typeName(type), length));
    if (size - pos - 8 < std::size_t{length} + 4)
      reject(fmt::format("truncated: the file ends inside chunk {}", typeName(type)));
    const std::uint8_t* type_and_data = data + pos + 4;
    const std::uint8_t* body = type_and_data + 4;
    pos += std::size_t{length} + 12;
    if (first) {
      if (type != kIHDR || length != 13) reject(fmt::format("the first chunk is {} of {} bytes, not a 13-byte IHDR",
                                                            typeName(type), length));
      checkCrc(type, type_and_data, length);
      readHeader(body, layout);
      continue;
    }
    if (type == kIDAT) {
      if (after_idat) handOverLater(layout, "IDAT chunks that are not consecutive");
      checkCrc(type, type_and_data, length);
      in_idat = true;
      layout.idat.emplace_back(body, length);
      layout.idat_bytes += length;
      continue;
    }
    after_idat = after_idat || in_idat;
    if (type == kIEND) {
      checkCrc(type, type_and_data, length);
      break;
    }
    const bool critical = (type & 0x20000000u) == 0;  // bit 5 of the first letter: lower case = ancillary
    if (critical) handOverLater(layout, fmt::format("critical chunk {}", typeName(type)));
    if (type == ktRNS) handOverLater(layout, "tRNS chunk");
    if (type == keXIf && orientation_applies)
      handOverLater(layout, "eXIf chunk (cv::imread applies its orientation)");
  }
  if (layout.idat.empty()) reject("no IDAT chunk");
  requireImageDataFor(layout);
  return layout;
}

// The Paeth predictor (PNG specification section 9.4) of left a, up b and upper-left c; pa, pb, pc are the
// specification's |p - a|, |p - b|, |p - c| for p = a + b - c.
inline std::uint8_t paeth(int a, int b, int c) {
  const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
  return static_cast<std::uint8_t>(pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
}

// Un-filters one row of n bytes (a multiple of kBpp) in place, given the row above (zeros for the first row): PNG
// specification section 9.2. False for an invalid filter type.
template <std::size_t kBpp>
bool unfilterRow(std::uint8_t filter, std::uint8_t* row, const std::uint8_t* up, std::size_t n) {
  switch (filter) {
    case 0:  // None
      return true;
    case 1: {  // Sub: the left neighbours kept in registers
      std::uint8_t left[kBpp];
      std::memcpy(left, row, kBpp);
      for (std::size_t i = kBpp; i < n; i += kBpp) {
        for (std::size_t k = 0; k < kBpp; ++k) row[i + k] = left[k] = static_cast<std::uint8_t>(row[i + k] + left[k]);
      }
      return true;
    }
    case 2:  // Up
      for (std::size_t i = 0; i < n; ++i) row[i] = static_cast<std::uint8_t>(row[i] + up[i]);
      return true;
    case 3:  // Average
      for (std::size_t i = 0; i < kBpp; ++i) row[i] = static_cast<std::uint8_t>(row[i] + (up[i] >> 1));
      for (std::size_t i = kBpp; i < n; ++i)
        row[i] = static_cast<std::uint8_t>(row[i] + ((row[i - kBpp] + up[i]) >> 1));
      return true;
    case 4:  // Paeth
      for (std::size_t i = 0; i < kBpp; ++i) row[i] = static_cast<std::uint8_t>(row[i] + up[i]);
      for (std::size_t i = kBpp; i < n; ++i)
        row[i] = static_cast<std::uint8_t>(row[i] + paeth(row[i - kBpp], up[i], up[i - kBpp]));
      return true;
    default:
      return false;
  }
}

using RowUnfilter = bool (*)(std::uint8_t, std::uint8_t*, const std::uint8_t*, std::size_t);

RowUnfilter unfilterFor(std::size_t bytes_per_pixel) {
  switch (bytes_per_pixel) {
    case 1: return unfilterRow<1>;
    case 2: return unfilterRow<2>;
    case 3: return unfilterRow<3>;
    case 4: return unfilterRow<4>;
    case 6: return unfilterRow<6>;
    default: return unfilterRow<8>;
  }
}

// Which input sample feeds output channel c (output in OpenCV's order: grey, BGR or BGRA): grey and grey+alpha are
// replicated into B, G and R, RGB(A) is swapped, alpha stays last.
constexpr int sourceChannel(int in_channels, int c) {
  return in_channels <= 2 ? (c == 3 ? 1 : 0) : (c == 3 ? 3 : 2 - c);
}

// One un-filtered row of `width` pixels of kIn samples of kSampleBytes (big-endian) into kOut channels of T: a
// 16-bit sample becomes its value (T = 16 bits) or its high byte (T = 8 bits, as png_set_strip_16).
template <int kIn, int kSampleBytes, int kOut, typename T>
void convertRow(const std::uint8_t* in, std::uint8_t* out_bytes, std::size_t width) {
  T* out = reinterpret_cast<T*>(out_bytes);
  for (std::size_t x = 0; x < width; ++x, in += kIn * kSampleBytes, out += kOut) {
    for (int c = 0; c < kOut; ++c) {
      const std::uint8_t* sample = in + sourceChannel(kIn, c) * kSampleBytes;
      if constexpr (sizeof(T) == 2) {
        out[c] = static_cast<T>((sample[0] << 8) | sample[1]);
      } else {
        out[c] = sample[0];
      }
    }
  }
}

using RowConverter = void (*)(const std::uint8_t*, std::uint8_t*, std::size_t);

template <int kSampleBytes>
RowConverter converterFor(int in_channels, Mode mode) {
  using Wide = std::conditional_t<kSampleBytes == 2, std::uint16_t, std::uint8_t>;
  if (mode == Mode::colour) {
    switch (in_channels) {
      case 1: return convertRow<1, kSampleBytes, 3, std::uint8_t>;
      case 2: return convertRow<2, kSampleBytes, 3, std::uint8_t>;
      case 3: return convertRow<3, kSampleBytes, 3, std::uint8_t>;
      default: return convertRow<4, kSampleBytes, 3, std::uint8_t>;
    }
  }
  switch (in_channels) {
    case 1: return convertRow<1, kSampleBytes, 1, Wide>;
    case 2: return convertRow<2, kSampleBytes, 4, Wide>;
    case 3: return convertRow<3, kSampleBytes, 3, Wide>;
    default: return convertRow<4, kSampleBytes, 4, Wide>;
  }
}

// The output type cv::imread gives (see the header).
int outputType(const PngLayout& layout, Mode mode) {
  if (mode == Mode::colour) return CV_8UC3;
  const int channels = layout.channels == 2 ? 4 : layout.channels;
  return CV_MAKETYPE(layout.bit_depth == 16 ? CV_16U : CV_8U, channels);
}

// Inflates the IDAT stream into exactly `expected` bytes (in the thread's scratch memory).
std::uint8_t* inflateImageData(const PngLayout& layout, std::size_t expected) {
  libdeflate_decompressor* decompressor = threadDecompressor();
  if (decompressor == nullptr) handOver("libdeflate could not allocate a decompressor");
  const std::uint8_t* stream = layout.idat.front().first;
  if (layout.idat.size() > 1) {
    std::uint8_t* joined = threadScratch().idat.reserve(layout.idat_bytes);
    std::size_t at = 0;
    for (const auto& [chunk, length] : layout.idat) {
      if (length > 0) std::memcpy(joined + at, chunk, length);
      at += length;
    }
    stream = joined;
  }
  std::uint8_t* raw = threadScratch().rows.reserve(expected);
  switch (libdeflate_zlib_decompress(decompressor, stream, layout.idat_bytes, raw, expected, nullptr)) {
    case LIBDEFLATE_SUCCESS:
      return raw;
    case LIBDEFLATE_SHORT_OUTPUT:
      reject(fmt::format("the image data is too short for {}x{}", layout.width, layout.height));
    case LIBDEFLATE_INSUFFICIENT_SPACE:  // libpng warns about data beyond the image and decodes it
      handOver(fmt::format("more image data than {}x{} needs", layout.width, layout.height));
    default:  // corrupt for libdeflate although the CRCs are right: zlib has the last word
      handOver("a zlib stream libdeflate rejects");
  }
}

cv::Mat decodeLayout(const PngLayout& layout, Mode mode) {
  const std::size_t sample_bytes = static_cast<std::size_t>(layout.bit_depth / 8);
  const std::size_t bytes_per_pixel = layout.channels * sample_bytes;
  const std::size_t row_bytes = layout.width * bytes_per_pixel;
  const std::uint64_t expected = minimumImageDataBytes(layout);  // exact: not interlaced
  std::uint8_t* raw = inflateImageData(layout, static_cast<std::size_t>(expected));

  cv::Mat image(static_cast<int>(layout.height), static_cast<int>(layout.width), outputType(layout, mode));
  const RowUnfilter unfilter = unfilterFor(bytes_per_pixel);
  const RowConverter convert =
      sample_bytes == 2 ? converterFor<2>(layout.channels, mode) : converterFor<1>(layout.channels, mode);
  const std::vector<std::uint8_t> zeros(row_bytes, 0);
  const std::uint8_t* up = zeros.data();
  for (int y = 0; y < image.rows; ++y) {
    std::uint8_t* line = raw + static_cast<std::size_t>(y) * (row_bytes + 1);
    if (!unfilter(line[0], line + 1, up, row_bytes))
      reject(fmt::format("row {} has the invalid filter type {}", y, line[0]));
    convert(line + 1, image.ptr(y), layout.width);
    up = line + 1;
  }
  return image;
}

// Decodes with `mode`, or only checks the PNG before it goes to libpng (no mode: flags not handled here).
Decoded decodeHere(const std::uint8_t* data, std::size_t size, std::optional<Mode> mode, int imread_flags) {
  const bool orientation_applies =
      mode == Mode::colour && (imread_flags & kReadIgnoreOrientation) == 0;
  try {
    const PngLayout layout = readChunks(data, size, orientation_applies);
    if (!mode) handOver(fmt::format("imread flags {}", imread_flags));
    if (layout.handover_reason) handOver(*layout.handover_reason);
    return {decodeLayout(layout, *mode), {PngRoute::decoded, {}}};
  } catch (const Handoff& handoff) {
    return {cv::Mat(), {handoff.route, handoff.reason}};
  } catch (const std::bad_alloc&) {
    return {cv::Mat(), {PngRoute::rejected, "out of memory for the image"}};
  }
}

#endif  // AMOS_WITH_LIBDEFLATE

// Why no PNG is decoded or checked here; nullopt when they are.
std::optional<std::string> notDecodedHere() {
#if AMOS_WITH_LIBDEFLATE
  return std::nullopt;
#else
  return "built without libdeflate";
#endif
}

// The fast path's answer (notDecodedHere gave nullopt): decoded, rejected, or checked and handed over.
Decoded tryDecode(const std::uint8_t* data, std::size_t size, int imread_flags) {
#if AMOS_WITH_LIBDEFLATE
  return decodeHere(data, size, modeOf(imread_flags), imread_flags);
#else
  return {cv::Mat(), {PngRoute::general, "built without libdeflate"}};
#endif
}

// Reads the whole file into `buffer`; its size, or nullopt with the reason in `problem`.
std::optional<std::size_t> readWholeFile(const std::string& path, ScratchBuffer& buffer, std::string& problem) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) {
    problem = fmt::format("cannot read it: {}", error.message());
    return std::nullopt;
  }
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!file || (size > 0 && std::fread(buffer.reserve(size), 1, size, file.get()) != size)) {
    problem = "cannot read it";
    return std::nullopt;
  }
  return static_cast<std::size_t>(size);
}

// The fast path's answer, or the general decoders' (image_decoders.h) for what it hands over.
Decoded decodeBytes(const std::uint8_t* data, std::size_t size, int imread_flags) {
  Decoded decoded;
  if (const auto why = notDecodedHere()) {
    decoded.info = {PngRoute::general, *why};
  } else {
    decoded = tryDecode(data, size, imread_flags);
  }
  if (decoded.info.route != PngRoute::general) return decoded;
  std::string problem;
  decoded.image = decodeBySignature(data, size, imread_flags, problem);
  if (decoded.image.empty()) decoded.info = {PngRoute::rejected, problem};
  return decoded;
}

}  // namespace

bool pngFastPathAvailable() {
#if AMOS_WITH_LIBDEFLATE
  return true;
#else
  return false;
#endif
}

cv::Mat decodePng(const std::uint8_t* data, std::size_t size, int imread_flags, PngReadInfo* info) {
  PngReadInfo local;
  PngReadInfo& out = info != nullptr ? *info : local;
  if (size == 0 || size > static_cast<std::size_t>(INT_MAX)) {
    out = {PngRoute::rejected, size == 0 ? "no bytes" : "more than 2 GiB"};
    return cv::Mat();
  }
  Decoded decoded = decodeBytes(data, size, imread_flags);
  threadScratch().trim();
  out = std::move(decoded.info);
  return decoded.image;
}

cv::Mat readPng(const std::string& path, int imread_flags, PngReadInfo* info) {
  PngReadInfo local;
  PngReadInfo& out = info != nullptr ? *info : local;
  const bool caller_reports = info != nullptr;
  Decoded decoded;
  std::string problem;
  if (const auto size = readWholeFile(path, threadScratch().file, problem); !size) {
    decoded.info = {PngRoute::rejected, problem};
  } else if (*size == 0) {
    decoded.info = {PngRoute::rejected, "empty file"};
  } else {
    decoded = decodeBytes(threadScratch().file.reserve(*size), *size, imread_flags);
  }
  threadScratch().trim();
  out = std::move(decoded.info);
  if (out.route == PngRoute::rejected && !caller_reports)
    spdlog::warn("cannot decode image '{}': {}", path, out.reason);
  return decoded.image;
}

std::optional<cv::Size> pngHeaderSize(const std::string& path) {
  // Signature (8 bytes), IHDR length (4) and type (4), width and height (4 each, big-endian).
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  unsigned char header[24];
  if (!file || std::fread(header, 1, sizeof header, file.get()) != sizeof header) return std::nullopt;
  if (std::memcmp(header, kSignature, sizeof kSignature) != 0 || std::memcmp(header + 12, "IHDR", 4) != 0)
    return std::nullopt;
  const auto big_endian = [&](int at) {
    return (std::uint32_t{header[at]} << 24) | (std::uint32_t{header[at + 1]} << 16) |
           (std::uint32_t{header[at + 2]} << 8) | std::uint32_t{header[at + 3]};
  };
  const std::uint32_t width = big_endian(16), height = big_endian(20);
  if (width == 0 || height == 0 || width > INT_MAX || height > INT_MAX) return std::nullopt;
  return cv::Size(static_cast<int>(width), static_cast<int>(height));
}

}  // namespace amos::io
