#include "amos/io/png_reader.h"

#include <gtest/gtest.h>

#include "amos/testing/same_image.h"
#include "amos/testing/scratch_dir.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "amos/testing/shared_data.h"

namespace amos::io {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

using testing::sameImage;

// The route a PNG this reader handles takes in this build.
PngRoute handledRoute() { return pngFastPathAvailable() ? PngRoute::decoded : PngRoute::general; }

cv::Mat decodeWithOpenCv(const Bytes& bytes, int flags) {
  return cv::imdecode(cv::Mat(1, static_cast<int>(bytes.size()), CV_8U, const_cast<std::uint8_t*>(bytes.data())),
                      flags);
}

Bytes fileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const fs::path& path, const Bytes& bytes) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                              static_cast<std::streamsize>(bytes.size()));
}

// ---- A minimal PNG writer, so that every filter type, colour type and corruption can be written on purpose. ----

std::uint32_t crc32(const std::uint8_t* data, std::size_t size) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xffffffffu;
  for (std::size_t i = 0; i < size; ++i) c = table[(c ^ data[i]) & 0xff] ^ (c >> 8);
  return c ^ 0xffffffffu;
}

void putBe32(Bytes& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(v >> shift));
}

// A zlib stream of stored (uncompressed) DEFLATE blocks.
Bytes zlibStored(const Bytes& data) {
  Bytes out = {0x78, 0x01};
  std::size_t at = 0;
  do {
    const std::size_t n = std::min<std::size_t>(65535, data.size() - at);
    out.push_back(at + n == data.size() ? 1 : 0);
    out.push_back(static_cast<std::uint8_t>(n));
    out.push_back(static_cast<std::uint8_t>(n >> 8));
    out.push_back(static_cast<std::uint8_t>(~n));
    out.push_back(static_cast<std::uint8_t>(~n >> 8));
    out.insert(out.end(), data.begin() + at, data.begin() + at + n);
    at += n;
  } while (at < data.size());
  std::uint32_t a = 1, b = 0;
  for (std::uint8_t byte : data) {
    a = (a + byte) % 65521;
    b = (b + a) % 65521;
  }
  putBe32(out, (b << 16) | a);
  return out;
}

// Raw samples as a PNG stores them (big-endian, R G B A order), before filtering.
struct RawImage {
  std::uint32_t width = 0, height = 0;
  int bit_depth = 8, colour_type = 2;
  Bytes samples;  // height rows of rowBytes()

  int channels() const { return colour_type == 0 ? 1 : colour_type == 4 ? 2 : colour_type == 2 ? 3 : 4; }
  std::size_t bytesPerPixel() const { return static_cast<std::size_t>(channels() * bit_depth / 8); }
  std::size_t rowBytes() const { return width * bytesPerPixel(); }
};

RawImage randomImage(std::uint32_t width, std::uint32_t height, int bit_depth, int colour_type, unsigned seed) {
  RawImage image{width, height, bit_depth, colour_type, {}};
  std::mt19937 rng(seed);
  image.samples.resize(image.rowBytes() * height);
  for (auto& s : image.samples) s = static_cast<std::uint8_t>(rng());
  return image;
}

// The PNG specification's Paeth predictor, as written there.
int paethPredictor(int a, int b, int c) {
  const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  if (pa <= pb && pa <= pc) return a;
  return pb <= pc ? b : c;
}

// The filtered scanlines (filter byte + row) with filter_of(row) for each row; a filter type above 4 is written as
// it is, with the row unfiltered.
Bytes filterRows(const RawImage& image, const std::function<int(std::uint32_t)>& filter_of) {
  const std::size_t n = image.rowBytes(), bpp = image.bytesPerPixel();
  const Bytes zeros(n, 0);
  Bytes out;
  for (std::uint32_t y = 0; y < image.height; ++y) {
    const std::uint8_t* row = image.samples.data() + y * n;
    const std::uint8_t* up = y == 0 ? zeros.data() : row - n;
    const int filter = filter_of(y);
    out.push_back(static_cast<std::uint8_t>(filter));
    for (std::size_t i = 0; i < n; ++i) {
      const int a = i >= bpp ? row[i - bpp] : 0, b = up[i], c = i >= bpp ? up[i - bpp] : 0;
      const int predictor = filter == 1 ? a : filter == 2 ? b : filter == 3 ? (a + b) / 2
                                                                : filter == 4 ? paethPredictor(a, b, c) : 0;
      out.push_back(static_cast<std::uint8_t>(row[i] - predictor));
    }
  }
  return out;
}

class PngBuilder {
 public:
  PngBuilder() : bytes_{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'} {}

  PngBuilder& chunk(const std::string& type, const Bytes& data) {
    putBe32(bytes_, static_cast<std::uint32_t>(data.size()));
    const std::size_t start = bytes_.size();
    bytes_.insert(bytes_.end(), type.begin(), type.end());
    bytes_.insert(bytes_.end(), data.begin(), data.end());
    putBe32(bytes_, crc32(bytes_.data() + start, bytes_.size() - start));
    return *this;
  }
  PngBuilder& header(const RawImage& image, int interlace = 0) {
    Bytes data;
    putBe32(data, image.width);
    putBe32(data, image.height);
    data.insert(data.end(), {static_cast<std::uint8_t>(image.bit_depth), static_cast<std::uint8_t>(image.colour_type),
                             0, 0, static_cast<std::uint8_t>(interlace)});
    return chunk("IHDR", data);
  }
  // The zlib stream split into IDAT chunks of at most chunk_size bytes.
  PngBuilder& imageData(const Bytes& zlib, std::size_t chunk_size) {
    for (std::size_t at = 0; at < zlib.size(); at += chunk_size)
      chunk("IDAT", Bytes(zlib.begin() + at, zlib.begin() + std::min(zlib.size(), at + chunk_size)));
    return *this;
  }
  Bytes end() {
    chunk("IEND", {});
    return bytes_;
  }

 private:
  Bytes bytes_;
};

Bytes encodePng(const RawImage& image, const std::function<int(std::uint32_t)>& filter_of,
                std::size_t chunk_size = 8192) {
  return PngBuilder().header(image).imageData(zlibStored(filterRows(image, filter_of)), chunk_size).end();
}

// Where chunk `type` starts (its length field) in a PNG, or npos.
std::size_t findChunk(const Bytes& png, const std::string& type) {
  for (std::size_t pos = 8; pos + 8 <= png.size();) {
    const std::uint32_t length = (std::uint32_t{png[pos]} << 24) | (std::uint32_t{png[pos + 1]} << 16) |
                                 (std::uint32_t{png[pos + 2]} << 8) | png[pos + 3];
    if (std::string(png.begin() + pos + 4, png.begin() + pos + 8) == type) return pos;
    pos += 12 + std::size_t{length};
  }
  return std::string::npos;
}

void fixCrc(Bytes& png, std::size_t chunk_pos) {
  const std::uint32_t length = (std::uint32_t{png[chunk_pos]} << 24) | (std::uint32_t{png[chunk_pos + 1]} << 16) |
                               (std::uint32_t{png[chunk_pos + 2]} << 8) | png[chunk_pos + 3];
  const std::uint32_t crc = crc32(png.data() + chunk_pos + 4, length + 4);
  for (int k = 0; k < 4; ++k) png[chunk_pos + 8 + length + k] = static_cast<std::uint8_t>(crc >> (24 - 8 * k));
}

constexpr std::array<int, 2> kFlags = {cv::IMREAD_COLOR, cv::IMREAD_UNCHANGED};

// decodePng gives what cv::imdecode gives, by the expected route (what libpng cannot decode either is rejected).
void expectLikeImdecode(const Bytes& png, int flags, PngRoute route, const std::string& what) {
  PngReadInfo info;
  const cv::Mat ours = decodePng(png.data(), png.size(), flags, &info);
  const cv::Mat opencv = decodeWithOpenCv(png, flags);
  EXPECT_TRUE(sameImage(ours, opencv)) << what << " flags " << flags;
  const PngRoute expected = route == PngRoute::general && opencv.empty() ? PngRoute::rejected : route;
  EXPECT_EQ(info.route, expected) << what << " flags " << flags << ": " << info.reason;
}

// ---- Real frames ----

std::vector<fs::path> pngsIn(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".png") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

// Every rgb/ frame with IMREAD_COLOR and depth/ frame with IMREAD_UNCHANGED equals cv::imread's, decoded here.
void expectSequenceLikeImread(const std::string& name) {
  AMOS_REQUIRE_DATA(name + "/rgb");
  AMOS_REQUIRE_DATA(name + "/depth");
  const fs::path dir = testing::dataPath(name);
  std::size_t frames = 0;
  for (const auto& [sub, flags] : {std::pair{"rgb", cv::IMREAD_COLOR}, std::pair{"depth", cv::IMREAD_UNCHANGED}}) {
    for (const fs::path& file : pngsIn(dir / sub)) {
      PngReadInfo info;
      const cv::Mat ours = readPng(file.string(), flags, &info);
      ASSERT_FALSE(ours.empty()) << file << ": " << info.reason;
      ASSERT_TRUE(sameImage(ours, cv::imread(file.string(), flags))) << file;
      ASSERT_EQ(info.route, handledRoute()) << file << ": " << info.reason;
      ++frames;
    }
  }
  EXPECT_GT(frames, 0u);
}

TEST(PngReaderRealData, BonnCrowdFramesEqualImread) { expectSequenceLikeImread("bonn_crowd_dev"); }
TEST(PngReaderRealData, TumFr2DeskFramesEqualImread) { expectSequenceLikeImread("tum_fr2_desk_first50"); }

// ---- Images from cv::imwrite ----

class PngReaderFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = amos::testing::scratchDirForThisTest("amos_png_reader_test_");
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(PngReaderFiles, ImwriteImagesOfEveryTypeSizeAndStrategyEqualImread) {
  const std::vector<cv::Size> sizes = {{1, 1}, {3, 7}, {7, 3}, {17, 5}, {640, 480}};
  const std::vector<int> types = {CV_8UC1, CV_8UC3, CV_8UC4, CV_16UC1, CV_16UC3, CV_16UC4};
  // Each zlib strategy at the default level, and level 0 (stored blocks) and 9.
  const std::vector<std::vector<int>> params = {
      {cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_DEFAULT},
      {cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_FILTERED},
      {cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_HUFFMAN_ONLY},
      {cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_RLE},
      {cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_FIXED},
      {cv::IMWRITE_PNG_COMPRESSION, 0},
      {cv::IMWRITE_PNG_COMPRESSION, 9}};
  cv::RNG rng(7);
  int written = 0;
  for (const cv::Size& size : sizes) {
    for (int type : types) {
      // Noise, and a smooth image (what filters and compression are for) for the larger sizes.
      cv::Mat image(size, type);
      rng.fill(image, cv::RNG::UNIFORM, 0, CV_MAT_DEPTH(type) == CV_16U ? 65536 : 256);
      if (size.area() > 50 && written % 2 == 1) cv::GaussianBlur(image, image, {9, 9}, 3);
      for (const auto& param : params) {
        const fs::path file = dir_ / ("image_" + std::to_string(written++) + ".png");
        ASSERT_TRUE(cv::imwrite(file.string(), image, param));
        for (int flags : kFlags) {
          PngReadInfo info;
          const cv::Mat ours = readPng(file.string(), flags, &info);
          ASSERT_TRUE(sameImage(ours, cv::imread(file.string(), flags)))
              << size << " type " << type << " param " << param[0] << "=" << param[1] << " flags " << flags;
          EXPECT_EQ(info.route, handledRoute()) << info.reason;
        }
      }
    }
  }
}

// ---- Every filter type and colour type, from the writer above ----

TEST(PngReader, EveryFilterColourTypeAndDepthEqualsImdecode) {
  const std::vector<std::pair<std::uint32_t, std::uint32_t>> sizes = {{1, 1}, {3, 7}, {33, 9}};
  const std::vector<std::pair<std::string, std::function<int(std::uint32_t)>>> filters = {
      {"none", [](std::uint32_t) { return 0; }},  {"sub", [](std::uint32_t) { return 1; }},
      {"up", [](std::uint32_t) { return 2; }},    {"average", [](std::uint32_t) { return 3; }},
      {"paeth", [](std::uint32_t) { return 4; }}, {"mixed", [](std::uint32_t y) { return int(y % 5); }}};
  unsigned seed = 1;
  for (int bit_depth : {8, 16}) {
    for (int colour_type : {0, 2, 4, 6}) {
      for (const auto& [width, height] : sizes) {
        for (const auto& [filter_name, filter_of] : filters) {
          const RawImage image = randomImage(width, height, bit_depth, colour_type, seed++);
          // Small IDAT chunks too, so that the stream is joined from many.
          for (std::size_t chunk_size : {std::size_t{8192}, std::size_t{5}}) {
            const Bytes png = encodePng(image, filter_of, chunk_size);
            for (int flags : kFlags) {
              expectLikeImdecode(png, flags, handledRoute(),
                                 "depth " + std::to_string(bit_depth) + " colour type " + std::to_string(colour_type) +
                                     " " + std::to_string(width) + "x" + std::to_string(height) + " filter " +
                                     filter_name);
            }
          }
        }
      }
    }
  }
}

TEST(PngReader, UnhandledPngsAndFlagsGoToLibpng) {
  const RawImage rgb = randomImage(5, 4, 8, 2, 3);
  const auto paeth = [](std::uint32_t) { return 4; };
  // Flags other than COLOR / UNCHANGED.
  const Bytes plain = encodePng(rgb, paeth);
  for (int flags : {int{cv::IMREAD_GRAYSCALE}, cv::IMREAD_ANYDEPTH | cv::IMREAD_COLOR, int{cv::IMREAD_ANYCOLOR}})
    expectLikeImdecode(plain, flags, PngRoute::general, "flags");
  // Reduced sizes are not supported: an empty Mat, with the reason.
  PngReadInfo reduced;
  EXPECT_TRUE(decodePng(plain.data(), plain.size(), cv::IMREAD_REDUCED_COLOR_2, &reduced).empty());
  EXPECT_EQ(reduced.route, PngRoute::rejected);
  EXPECT_NE(reduced.reason.find("unsupported read flags"), std::string::npos) << reduced.reason;
  // COLOR with IMREAD_IGNORE_ORIENTATION is still decoded here.
  expectLikeImdecode(plain, cv::IMREAD_COLOR | cv::IMREAD_IGNORE_ORIENTATION, handledRoute(), "ignore orientation");

  const Bytes idat = zlibStored(filterRows(rgb, paeth));
  // A palette image (8-bit indices, a 4-colour PLTE).
  RawImage indexed = randomImage(5, 4, 8, 3, 4);
  for (auto& s : indexed.samples) s %= 4;
  const Bytes palette = PngBuilder()
                            .header(indexed)
                            .chunk("PLTE", {0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255})
                            .imageData(zlibStored(filterRows(indexed, paeth)), 8192)
                            .end();
  // A 1-bit grey image, as IMWRITE_PNG_BILEVEL writes.
  std::vector<std::uint8_t> bilevel_png;
  cv::imencode(".png", cv::Mat(9, 11, CV_8U, cv::Scalar(255)), bilevel_png, {cv::IMWRITE_PNG_BILEVEL, 1});
  // tRNS, which turns RGB into BGRA with IMREAD_UNCHANGED.
  const Bytes transparent =
      PngBuilder().header(rgb).chunk("tRNS", {0, 1, 0, 2, 0, 3}).imageData(idat, 8192).end();
  // eXIf, whose orientation cv::imread applies with IMREAD_COLOR (a little-endian TIFF header, no entries).
  const Bytes exif = PngBuilder()
                         .header(rgb)
                         .chunk("eXIf", {'I', 'I', 42, 0, 8, 0, 0, 0, 0, 0, 0, 0, 0, 0})
                         .imageData(idat, 8192)
                         .end();
  // Interlace flag set (the data is not Adam7: whatever libpng makes of it).
  const Bytes interlaced = PngBuilder().header(rgb, 1).imageData(idat, 8192).end();
  // IDAT chunks with an ancillary chunk between them.
  const Bytes split = PngBuilder()
                          .header(rgb)
                          .imageData(Bytes(idat.begin(), idat.begin() + 10), 8192)
                          .chunk("tEXt", {'a', 0, 'b'})
                          .imageData(Bytes(idat.begin() + 10, idat.end()), 8192)
                          .end();
  for (int flags : kFlags) {
    expectLikeImdecode(palette, flags, PngRoute::general, "palette");
    expectLikeImdecode(bilevel_png, flags, PngRoute::general, "1-bit grey");
    expectLikeImdecode(transparent, flags, PngRoute::general, "tRNS");
    expectLikeImdecode(interlaced, flags, PngRoute::general, "interlaced");
    expectLikeImdecode(split, flags, PngRoute::general, "IDAT chunks not consecutive");
  }
  expectLikeImdecode(exif, cv::IMREAD_COLOR, PngRoute::general, "eXIf");
  expectLikeImdecode(exif, cv::IMREAD_UNCHANGED, handledRoute(), "eXIf, UNCHANGED");
  // Ancillary chunks before and after the image data are skipped.
  const Bytes text = PngBuilder()
                         .header(rgb)
                         .chunk("tEXt", {'k', 0, 'v'})
                         .chunk("gAMA", {0, 0, 177, 143})
                         .imageData(idat, 8192)
                         .chunk("tIME", {7, 234, 1, 2, 3, 4, 5})
                         .end();
  for (int flags : kFlags) expectLikeImdecode(text, flags, handledRoute(), "ancillary chunks");
}

TEST_F(PngReaderFiles, OtherFormatsAndNonImagesAreReadLikeImread) {
  const cv::Mat image(6, 8, CV_8UC3, cv::Scalar(10, 100, 200));
  ASSERT_TRUE(cv::imwrite((dir_ / "photo.jpg").string(), image));
  fs::copy_file(dir_ / "photo.jpg", dir_ / "photo.png");  // a JPEG named .png
  std::ofstream(dir_ / "notes.png") << "not an image at all\n";
  for (const char* name : {"photo.png", "notes.png"}) {
    const std::string file = (dir_ / name).string();
    for (int flags : kFlags) {
      PngReadInfo info;
      EXPECT_TRUE(sameImage(readPng(file, flags, &info), cv::imread(file, flags))) << name;
      EXPECT_EQ(info.route, name == std::string("photo.png") ? PngRoute::general : PngRoute::rejected) << name;
    }
  }
  EXPECT_FALSE(readPng((dir_ / "photo.png").string(), cv::IMREAD_COLOR).empty());
  EXPECT_TRUE(readPng((dir_ / "notes.png").string(), cv::IMREAD_COLOR).empty());
}

// ---- Unreadable files: an empty Mat, never a crash ----

TEST_F(PngReaderFiles, EmptyMissingTruncatedAndCorruptFilesGiveAnEmptyMat) {
  const auto expectRejected = [](const fs::path& file, const std::string& reason_part) {
    for (int flags : kFlags) {
      PngReadInfo info;
      EXPECT_TRUE(readPng(file.string(), flags, &info).empty()) << file;
      EXPECT_TRUE(cv::imread(file.string(), flags).empty()) << file << ": cv::imread disagrees";
      if (!pngFastPathAvailable()) continue;
      EXPECT_EQ(info.route, PngRoute::rejected) << file;
      EXPECT_NE(info.reason.find(reason_part), std::string::npos) << file << ": " << info.reason;
    }
  };
  writeBytes(dir_ / "empty.png", {});
  expectRejected(dir_ / "empty.png", "empty file");
  expectRejected(dir_ / "missing.png", "cannot read");

  cv::Mat image(48, 64, CV_8UC3);
  cv::RNG(3).fill(image, cv::RNG::UNIFORM, 0, 256);
  ASSERT_TRUE(cv::imwrite((dir_ / "good.png").string(), image));
  const Bytes good = fileBytes(dir_ / "good.png");

  writeBytes(dir_ / "half.png", Bytes(good.begin(), good.begin() + good.size() / 2));
  expectRejected(dir_ / "half.png", "truncated");
  writeBytes(dir_ / "no_iend.png", Bytes(good.begin(), good.end() - 12));
  expectRejected(dir_ / "no_iend.png", "truncated");

  const std::size_t idat = findChunk(good, "IDAT");
  ASSERT_NE(idat, std::string::npos);
  Bytes corrupt = good;
  corrupt[idat + 8 + 40] ^= 0x5a;  // a byte of the compressed data, the CRC left as it was
  writeBytes(dir_ / "corrupt_idat.png", corrupt);
  expectRejected(dir_ / "corrupt_idat.png", "CRC mismatch in chunk IDAT");
  Bytes corrupt_ihdr = good;
  corrupt_ihdr[8 + 8 + 3] ^= 1;  // the width
  writeBytes(dir_ / "corrupt_ihdr.png", corrupt_ihdr);
  expectRejected(dir_ / "corrupt_ihdr.png", "CRC mismatch in chunk IHDR");
}

TEST(PngReader, HeaderSizeIsReadWithoutDecoding) {
  const fs::path dir = amos::testing::scratchDirForThisTest("amos_png_reader_test_");
  const fs::path png = dir / "a.png", text = dir / "a.txt";
  cv::imwrite(png.string(), cv::Mat(48, 64, CV_16UC1, cv::Scalar(7)));
  std::ofstream(text) << "not a PNG at all, but long enough";
  EXPECT_EQ(pngHeaderSize(png.string()), cv::Size(64, 48));
  EXPECT_EQ(pngHeaderSize(text.string()), std::nullopt);
  EXPECT_EQ(pngHeaderSize((dir / "missing.png").string()), std::nullopt);
  fs::remove_all(dir);
}

TEST(PngReader, EveryTruncationOfASmallPngIsRejected) {
  cv::Mat image(5, 7, CV_16UC3);
  cv::RNG(5).fill(image, cv::RNG::UNIFORM, 0, 65536);
  std::vector<std::uint8_t> png;
  ASSERT_TRUE(cv::imencode(".png", image, png));
  for (std::size_t size = 1; size < png.size(); ++size) {
    const Bytes prefix(png.begin(), png.begin() + size);
    for (int flags : kFlags) {
      PngReadInfo info;
      EXPECT_TRUE(decodePng(prefix.data(), prefix.size(), flags, &info).empty()) << size << " bytes";
      EXPECT_TRUE(decodeWithOpenCv(prefix, flags).empty()) << size << " bytes: cv::imdecode disagrees";
      EXPECT_EQ(info.route, PngRoute::rejected) << size << " bytes: " << info.reason;
    }
  }
  PngReadInfo info;
  EXPECT_TRUE(decodePng(png.data(), 0, cv::IMREAD_COLOR, &info).empty());
  EXPECT_EQ(info.route, PngRoute::rejected);
}

TEST(PngReader, BadImageDataIsRejectedHereOrByLibpng) {
  const RawImage image = randomImage(9, 6, 8, 6, 11);
  const auto filter_of = [](std::uint32_t y) { return int(y % 5); };
  // Image data one row short, and one row too long.
  RawImage shorter = image, longer = image;
  shorter.height -= 1;
  shorter.samples.resize(shorter.rowBytes() * shorter.height);
  longer.height += 1;
  longer.samples.resize(longer.rowBytes() * longer.height, 7);
  const Bytes too_short = PngBuilder().header(image).imageData(zlibStored(filterRows(shorter, filter_of)), 8192).end();
  const Bytes too_long = PngBuilder().header(image).imageData(zlibStored(filterRows(longer, filter_of)), 8192).end();
  const Bytes bad_filter = encodePng(image, [](std::uint32_t y) { return y == 3 ? 5 : 1; });
  // Deflate's limit: a 30000x30000 RGBA image cannot come out of 18 bytes; nothing that large is allocated.
  RawImage huge = image;
  huge.width = huge.height = 30000;
  const Bytes claims_huge = PngBuilder().header(huge).imageData(zlibStored(Bytes(7, 0)), 8192).end();
  // A broken deflate stream with right CRCs.
  Bytes broken = encodePng(image, filter_of);
  const std::size_t idat = findChunk(broken, "IDAT");
  broken[idat + 8 + 2] = 0x07;  // block type 3, which does not exist
  fixCrc(broken, idat);

  const auto expectRoute = [](const Bytes& png, PngRoute route, const std::string& reason_part) {
    for (int flags : kFlags) {
      PngReadInfo info;
      const cv::Mat ours = decodePng(png.data(), png.size(), flags, &info);
      EXPECT_TRUE(ours.empty()) << reason_part;
      if (!pngFastPathAvailable()) continue;
      EXPECT_EQ(info.route, route) << reason_part << ": " << info.reason;
      EXPECT_NE(info.reason.find(reason_part), std::string::npos) << info.reason;
    }
  };
  expectRoute(too_short, PngRoute::rejected, "too short");
  expectRoute(bad_filter, PngRoute::rejected, "row 3 has the invalid filter type 5");
  expectRoute(claims_huge, PngRoute::rejected, "too short for 30000x30000");
  // libdeflate hands it to libpng, whose zlib rejects it too.
  expectRoute(broken, PngRoute::rejected, "IDAT: invalid block type");
  for (int flags : kFlags) {
    EXPECT_TRUE(decodeWithOpenCv(too_short, flags).empty());
    EXPECT_TRUE(decodeWithOpenCv(bad_filter, flags).empty());
    EXPECT_TRUE(decodeWithOpenCv(broken, flags).empty());
    // More data than the image needs: libpng warns and decodes, here as in OpenCV.
    expectLikeImdecode(too_long, flags, PngRoute::general, "too much data");
  }
}

// A header that claims more pixels than its image data can inflate to is refused before anything of its size is
// allocated, also when the PNG would otherwise go to libpng (which allocates the declared image before it reads
// the data): interlaced, palette, 1-bit, a tRNS chunk, other flags.
TEST(PngReader, HeadersClaimingMoreThanTheImageDataHoldsAreRejectedBeforeLibpng) {
  if (!pngFastPathAvailable()) GTEST_SKIP() << "built without libdeflate: every PNG is libpng's";
  const Bytes seven_zeros = zlibStored(Bytes(7, 0));
  RawImage rgb = randomImage(4, 4, 8, 2, 1), indexed = rgb, bilevel = rgb;
  rgb.width = rgb.height = indexed.width = indexed.height = 5000;
  indexed.colour_type = 3;
  bilevel.width = bilevel.height = 20000;  // 1 bit a pixel: 50 MB
  bilevel.colour_type = 0;
  bilevel.bit_depth = 1;
  const std::vector<std::pair<std::string, Bytes>> lying = {
      {"interlaced", PngBuilder().header(rgb, 1).imageData(seven_zeros, 8192).end()},
      {"palette", PngBuilder().header(indexed).chunk("PLTE", {0, 0, 0}).imageData(seven_zeros, 8192).end()},
      {"1-bit", PngBuilder().header(bilevel).imageData(seven_zeros, 8192).end()},
      {"tRNS", PngBuilder().header(rgb).chunk("tRNS", {0, 1, 0, 2, 0, 3}).imageData(seven_zeros, 8192).end()}};
  for (const auto& [what, png] : lying) {
    for (int flags : {int{cv::IMREAD_COLOR}, int{cv::IMREAD_UNCHANGED}, int{cv::IMREAD_GRAYSCALE}}) {
      PngReadInfo info;
      EXPECT_TRUE(decodePng(png.data(), png.size(), flags, &info).empty()) << what;
      EXPECT_EQ(info.route, PngRoute::rejected) << what << " flags " << flags << ": " << info.reason;
      EXPECT_NE(info.reason.find("is too short for"), std::string::npos) << what << ": " << info.reason;
    }
  }
  // The same kinds with enough data still go to libpng.
  RawImage small = randomImage(5, 4, 8, 2, 3);
  const Bytes interlaced =
      PngBuilder().header(small, 1).imageData(zlibStored(filterRows(small, [](std::uint32_t) { return 0; })), 64).end();
  for (int flags : kFlags) expectLikeImdecode(interlaced, flags, PngRoute::general, "interlaced, enough data");
}

// Sizes beyond libpng's limit of 1000000 a side or OpenCV's of 2^30 pixels (for which cv::imdecode throws) are
// rejected here, whatever the flags.
TEST(PngReader, SizesBeyondTheLimitsAreRejected) {
  if (!pngFastPathAvailable()) GTEST_SKIP() << "built without libdeflate: every PNG is libpng's";
  const Bytes data = zlibStored(Bytes(7, 0));
  for (const auto& [width, height] : {std::pair<std::uint32_t, std::uint32_t>{1000001, 1}, {1, 1000001},
                                      {40000, 40000}}) {
    RawImage image = randomImage(1, 1, 8, 0, 1);
    image.width = width;
    image.height = height;
    const Bytes png = PngBuilder().header(image).imageData(data, 8192).end();
    for (int flags : {int{cv::IMREAD_COLOR}, int{cv::IMREAD_UNCHANGED}, int{cv::IMREAD_GRAYSCALE}}) {
      PngReadInfo info;
      EXPECT_TRUE(decodePng(png.data(), png.size(), flags, &info).empty()) << width << "x" << height;
      EXPECT_EQ(info.route, PngRoute::rejected) << width << "x" << height << ": " << info.reason;
      EXPECT_NE(info.reason.find("beyond the limits"), std::string::npos) << info.reason;
    }
  }
}

// Random damage that gets past the CRCs: to the scanlines before compression (a valid zlib stream of rows with wrong
// samples or filter types) or to the zlib stream (CRC recomputed). Ours equals cv::imdecode's, empty or not.
TEST(PngReader, RandomlyDamagedImagesDecodeLikeImdecode) {
  std::mt19937 rng(21);
  std::map<PngRoute, int> routes;
  for (int trial = 0; trial < 400; ++trial) {
    const int colour_type = std::array<int, 4>{0, 2, 4, 6}[trial % 4];
    const RawImage image = randomImage(1 + rng() % 20, 1 + rng() % 10, trial % 8 < 4 ? 8 : 16, colour_type, rng());
    Bytes scanlines = filterRows(image, [&](std::uint32_t y) { return int((y + trial) % 5); });
    const bool damage_stream = trial % 2 == 1;
    const int flips = 1 + int(rng() % 3);
    if (!damage_stream) {
      for (int k = 0; k < flips; ++k) scanlines[rng() % scanlines.size()] ^= static_cast<std::uint8_t>(1 + rng() % 255);
    }
    Bytes png = PngBuilder().header(image).imageData(zlibStored(scanlines), 64).end();
    if (damage_stream) {
      const std::size_t idat = findChunk(png, "IDAT");
      const std::size_t idat_length = (std::size_t{png[idat + 2]} << 8) | png[idat + 3];
      for (int k = 0; k < flips; ++k) png[idat + 8 + rng() % idat_length] ^= static_cast<std::uint8_t>(1 + rng() % 255);
      fixCrc(png, idat);
    }
    for (int flags : kFlags) {
      PngReadInfo info;
      const cv::Mat ours = decodePng(png.data(), png.size(), flags, &info);
      EXPECT_TRUE(sameImage(ours, decodeWithOpenCv(png, flags))) << "trial " << trial << ": " << info.reason;
      ++routes[info.route];
    }
  }
  // Each outcome happened: wrong samples decoded here, invalid filter types rejected, broken streams left to libpng.
  if (pngFastPathAvailable()) {
    EXPECT_GT(routes[PngRoute::decoded], 0);
    EXPECT_GT(routes[PngRoute::rejected], 0);
    EXPECT_GT(routes[PngRoute::general], 0);
  }
}

TEST(PngReader, ThreadsDecodeConcurrently) {
  const RawImage image = randomImage(64, 48, 8, 2, 9);
  const Bytes png = encodePng(image, [](std::uint32_t y) { return int(y % 5); });
  const cv::Mat expected = decodeWithOpenCv(png, cv::IMREAD_COLOR);
  std::vector<int> equal(2, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 2; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < 50; ++i)
        equal[t] += sameImage(decodePng(png.data(), png.size(), cv::IMREAD_COLOR), expected) ? 1 : 0;
    });
  }
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(equal, std::vector<int>(2, 50));
}

}  // namespace
}  // namespace amos::io
