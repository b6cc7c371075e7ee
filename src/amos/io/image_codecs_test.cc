#include "amos/io/image_codecs.h"

#include <gtest/gtest.h>
#include <png.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <csetjmp>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "amos/core/error.h"
#include "amos/testing/error_of.h"
#include "amos/testing/same_image.h"
#include "amos/testing/scratch_dir.h"

namespace amos::io {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

static_assert(kReadUnchanged == cv::IMREAD_UNCHANGED && kReadGrayscale == cv::IMREAD_GRAYSCALE &&
              kReadColor == cv::IMREAD_COLOR && kReadAnyDepth == cv::IMREAD_ANYDEPTH &&
              kReadAnyColor == cv::IMREAD_ANYCOLOR && kReadIgnoreOrientation == cv::IMREAD_IGNORE_ORIENTATION);

// The flags the comparisons with OpenCV go through.
const int kAllFlags[] = {cv::IMREAD_UNCHANGED,
                         cv::IMREAD_GRAYSCALE,
                         cv::IMREAD_COLOR,
                         cv::IMREAD_ANYDEPTH,
                         cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR,
                         cv::IMREAD_ANYCOLOR,
                         cv::IMREAD_COLOR | cv::IMREAD_IGNORE_ORIENTATION,
                         cv::IMREAD_GRAYSCALE | cv::IMREAD_IGNORE_ORIENTATION};

using testing::sameImage;

cv::Mat imdecodeBytes(const Bytes& bytes, int flags) {
  return cv::imdecode(cv::Mat(1, static_cast<int>(bytes.size()), CV_8U, const_cast<std::uint8_t*>(bytes.data())),
                      flags);
}

Bytes imencodeBytes(const std::string& ext, const cv::Mat& image, const std::vector<int>& params = {}) {
  std::vector<uchar> bytes;
  EXPECT_TRUE(cv::imencode(ext, image, bytes, params)) << ext;
  return Bytes(bytes.begin(), bytes.end());
}

// Smooth structure plus noise, so that compression and chroma subsampling have something to work on.
cv::Mat testImage(int rows, int cols, int type, unsigned seed) {
  cv::Mat image(rows, cols, type);
  const double top = CV_MAT_DEPTH(type) == CV_16U ? 65535 : 255;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-0.05, 0.05);
  for (int y = 0; y < rows; ++y) {
    for (int x = 0; x < cols; ++x) {
      for (int c = 0; c < image.channels(); ++c) {
        const double v = 0.5 + 0.4 * std::sin(0.11 * x + 0.07 * y + c) + noise(rng);
        const double sample = std::clamp(v, 0.0, 1.0) * top;
        if (image.depth() == CV_16U)
          image.ptr<std::uint16_t>(y)[x * image.channels() + c] = static_cast<std::uint16_t>(sample);
        else
          image.ptr<std::uint8_t>(y)[x * image.channels() + c] = static_cast<std::uint8_t>(sample);
      }
    }
  }
  return image;
}

// ---- PNG ----

TEST(ImageCodecs, PngBytesEqualImencodeForEveryTypeAndCompression) {
  for (int type : {CV_8UC1, CV_8UC3, CV_8UC4, CV_16UC1, CV_16UC3, CV_16UC4}) {
    const cv::Mat image = testImage(37, 53, type, 1);
    EXPECT_EQ(encodeImage(".png", image), imencodeBytes(".png", image)) << cv::typeToString(type);
    for (int level : {0, 1, 6, 9}) {
      EXPECT_EQ(encodeImage(".png", image, pngCompression(level)),
                imencodeBytes(".png", image, {cv::IMWRITE_PNG_COMPRESSION, level}))
          << cv::typeToString(type) << " level " << level;
    }
  }
}

TEST(ImageCodecs, PngRoundTripsAreLossless) {
  for (int type : {CV_8UC1, CV_8UC3, CV_8UC4, CV_16UC1, CV_16UC3, CV_16UC4}) {
    const cv::Mat image = testImage(20, 31, type, 2);
    EXPECT_TRUE(sameImage(decodeImage(encodeImage("png", image), kReadUnchanged), image)) << cv::typeToString(type);
  }
}

// ---- Odd PNGs (the libpng route): written with libpng here, decoded like cv::imdecode. ----

struct OddPng {
  int colour_type = PNG_COLOR_TYPE_RGB;
  int bit_depth = 8;
  bool interlaced = false;
  Bytes transparency;  // tRNS chunk contents (palette alphas, or the grey / RGB sample that is transparent)
  int orientation = 0;  // an eXIf chunk with this orientation when not 0
};

OddPng odd(int colour_type, int bit_depth, bool interlaced = false, Bytes transparency = {}, int orientation = 0) {
  return {colour_type, bit_depth, interlaced, std::move(transparency), orientation};
}

void appendPngBytes(png_structp png, png_bytep data, png_size_t size) {
  auto* out = static_cast<Bytes*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + size);
}

// A little-endian TIFF block with one entry: the orientation.
Bytes exifWithOrientation(int orientation) {
  return {'I', 'I', 42, 0, 8, 0, 0, 0,                                                // header, IFD at 8
          1, 0,                                                                       // one entry
          0x12, 0x01, 3, 0, 1, 0, 0, 0, static_cast<std::uint8_t>(orientation), 0, 0, 0,  // SHORT orientation
          0, 0, 0, 0};                                                                // no next IFD
}

// Random samples of the PNG's layout (packed as libpng expects: 1/2/4-bit pixels packed, 16-bit big-endian).
bool writeOddPng(const OddPng& spec, int width, int height, const Bytes& samples, std::size_t row_bytes, Bytes& out) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, &out, appendPngBytes, nullptr);
  png_set_IHDR(png, info, width, height, spec.bit_depth, spec.colour_type,
               spec.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  if (spec.colour_type == PNG_COLOR_TYPE_PALETTE) {
    png_color palette[16];
    for (int i = 0; i < 16; ++i)
      palette[i] = {static_cast<png_byte>(i * 16), static_cast<png_byte>(255 - i * 9), static_cast<png_byte>(i * 5)};
    png_set_PLTE(png, info, palette, 1 << std::min(spec.bit_depth, 4));
  }
  png_color_16 colour_key{};
  if (!spec.transparency.empty()) {
    const Bytes& t = spec.transparency;
    if (spec.colour_type == PNG_COLOR_TYPE_PALETTE) {
      png_set_tRNS(png, info, t.data(), static_cast<int>(t.size()), nullptr);
    } else {
      colour_key.gray = t[0];
      colour_key.red = t[0];
      colour_key.green = t.size() > 1 ? t[1] : 0;
      colour_key.blue = t.size() > 2 ? t[2] : 0;
      png_set_tRNS(png, info, nullptr, 0, &colour_key);
    }
  }
  Bytes exif;
  if (spec.orientation != 0) {
    exif = exifWithOrientation(spec.orientation);
    png_set_eXIf_1(png, info, static_cast<png_uint_32>(exif.size()), exif.data());
  }
  png_write_info(png, info);
  std::vector<png_bytep> rows(height);
  for (int y = 0; y < height; ++y) rows[y] = const_cast<png_bytep>(samples.data() + y * row_bytes);
  png_write_image(png, rows.data());
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

Bytes oddPng(const OddPng& spec, int width, int height, unsigned seed) {
  const int channels = spec.colour_type == PNG_COLOR_TYPE_GRAY || spec.colour_type == PNG_COLOR_TYPE_PALETTE ? 1
                       : spec.colour_type == PNG_COLOR_TYPE_GRAY_ALPHA                                      ? 2
                       : spec.colour_type == PNG_COLOR_TYPE_RGB                                             ? 3
                                                                                                            : 4;
  const std::size_t row_bytes = (static_cast<std::size_t>(width) * channels * spec.bit_depth + 7) / 8;
  Bytes samples(row_bytes * height);
  std::mt19937 rng(seed);
  for (auto& s : samples) s = static_cast<std::uint8_t>(rng());
  if (spec.colour_type == PNG_COLOR_TYPE_PALETTE && spec.bit_depth == 8)
    for (auto& s : samples) s %= 16;  // indices within the palette
  if (!spec.transparency.empty() && spec.colour_type != PNG_COLOR_TYPE_PALETTE)
    for (std::size_t i = 0; i + channels <= samples.size(); i += 7 * channels)  // some pixels are the colour key
      for (int c = 0; c < channels; ++c) samples[i + c] = spec.transparency[std::min<std::size_t>(c, 2)];
  Bytes out;
  EXPECT_TRUE(writeOddPng(spec, width, height, samples, row_bytes, out));
  return out;
}

TEST(ImageCodecs, OddPngsDecodeLikeImdecode) {
  struct Case {
    const char* name;
    OddPng spec;
  };
  const Case cases[] = {
      {"palette 8-bit", odd(PNG_COLOR_TYPE_PALETTE, 8)},
      {"palette 4-bit", odd(PNG_COLOR_TYPE_PALETTE, 4)},
      {"palette with tRNS", odd(PNG_COLOR_TYPE_PALETTE, 8, false, {0, 128, 255, 7})},
      {"grey 1-bit", odd(PNG_COLOR_TYPE_GRAY, 1)},
      {"grey 2-bit", odd(PNG_COLOR_TYPE_GRAY, 2)},
      {"grey 4-bit interlaced", odd(PNG_COLOR_TYPE_GRAY, 4, true)},
      {"grey with tRNS", odd(PNG_COLOR_TYPE_GRAY, 8, false, {17})},
      {"grey+alpha 16-bit", odd(PNG_COLOR_TYPE_GRAY_ALPHA, 16)},
      {"RGB interlaced", odd(PNG_COLOR_TYPE_RGB, 8, true)},
      {"RGB with tRNS", odd(PNG_COLOR_TYPE_RGB, 8, false, {10, 20, 30})},
      {"RGB 16-bit interlaced", odd(PNG_COLOR_TYPE_RGB, 16, true)},
      {"RGBA 16-bit", odd(PNG_COLOR_TYPE_RGB_ALPHA, 16)},
      {"RGBA 16-bit interlaced", odd(PNG_COLOR_TYPE_RGB_ALPHA, 16, true)},
      {"RGB eXIf orientation 3", odd(PNG_COLOR_TYPE_RGB, 8, false, {}, 3)},
      {"RGB eXIf orientation 6", odd(PNG_COLOR_TYPE_RGB, 8, false, {}, 6)},
      {"grey eXIf orientation 8", odd(PNG_COLOR_TYPE_GRAY, 8, false, {}, 8)},
  };
  for (const Case& c : cases) {
    const Bytes png = oddPng(c.spec, 13, 9, 5);
    ASSERT_FALSE(png.empty()) << c.name;
    for (int flags : kAllFlags) {
      std::string problem;
      const cv::Mat ours = decodeImage(png, flags, &problem);
      EXPECT_FALSE(ours.empty()) << c.name << " flags " << flags << ": " << problem;
      EXPECT_TRUE(sameImage(ours, imdecodeBytes(png, flags))) << c.name << " flags " << flags;
    }
  }
}

// ---- JPEG ----

double psnr(const cv::Mat& a, const cv::Mat& b) { return cv::PSNR(a, b); }

TEST(ImageCodecs, JpegIsWithinAFractionOfADecibelOfImencodesAtTheSameQuality) {
  for (int type : {CV_8UC1, CV_8UC3, CV_8UC4}) {
    const cv::Mat image = testImage(48, 64, type, 3);
    cv::Mat reference = image;
    if (type == CV_8UC4) cv::cvtColor(image, reference, cv::COLOR_BGRA2BGR);
    for (int quality : {50, 90, 95}) {
      const Bytes ours = encodeImage(".jpg", image, jpegQuality(quality));
      const Bytes opencv = imencodeBytes(".jpg", image, {cv::IMWRITE_JPEG_QUALITY, quality});
      const cv::Mat ours_decoded = imdecodeBytes(ours, cv::IMREAD_UNCHANGED);
      const cv::Mat opencv_decoded = imdecodeBytes(opencv, cv::IMREAD_UNCHANGED);
      ASSERT_FALSE(ours_decoded.empty());
      // Both encoders are libjpeg-turbo with the same settings: the same quality against the original.
      EXPECT_NEAR(psnr(ours_decoded, reference), psnr(opencv_decoded, reference), 0.1)
          << cv::typeToString(type) << " quality " << quality;
      // And against each other, far above the coding noise (about 30-45 dB here).
      EXPECT_GE(psnr(ours_decoded, opencv_decoded), 60) << cv::typeToString(type) << " quality " << quality;
    }
  }
}

// A JPEG with an APP1 Exif segment carrying `orientation`, inserted after SOI.
Bytes withExifOrientation(const Bytes& jpeg, int orientation) {
  Bytes app1 = {'E', 'x', 'i', 'f', 0, 0};
  const Bytes tiff = exifWithOrientation(orientation);
  app1.insert(app1.end(), tiff.begin(), tiff.end());
  const std::size_t length = app1.size() + 2;
  Bytes out;
  out.reserve(jpeg.size() + length + 2);
  for (std::uint8_t byte : {jpeg[0], jpeg[1], std::uint8_t{0xff}, std::uint8_t{0xe1},
                            static_cast<std::uint8_t>(length >> 8), static_cast<std::uint8_t>(length)})
    out.push_back(byte);
  out.insert(out.end(), app1.begin(), app1.end());
  out.insert(out.end(), jpeg.begin() + 2, jpeg.end());
  return out;
}

TEST(ImageCodecs, JpegsDecodeLikeImdecode) {
  for (int type : {CV_8UC1, CV_8UC3}) {
    const Bytes plain = imencodeBytes(".jpg", testImage(30, 45, type, 4), {cv::IMWRITE_JPEG_QUALITY, 80});
    for (int orientation : {0, 2, 3, 5, 6, 7, 8}) {
      const Bytes jpeg = orientation == 0 ? plain : withExifOrientation(plain, orientation);
      for (int flags : kAllFlags) {
        std::string problem;
        const cv::Mat ours = decodeImage(jpeg, flags, &problem);
        EXPECT_FALSE(ours.empty()) << problem;
        EXPECT_TRUE(sameImage(ours, imdecodeBytes(jpeg, flags)))
            << cv::typeToString(type) << " orientation " << orientation << " flags " << flags;
      }
    }
  }
}

// ---- PGM / PPM ----

TEST(ImageCodecs, PnmBytesEqualImencodeAndDecodeLikeImdecode) {
  for (int type : {CV_8UC1, CV_8UC3, CV_16UC1, CV_16UC3}) {
    const cv::Mat image = testImage(11, 17, type, 6);
    const std::string ext = CV_MAT_CN(type) == 1 ? ".pgm" : ".ppm";
    const cv::Mat original = image.clone();
    const Bytes ours = encodeImage(ext, image);
    EXPECT_TRUE(sameImage(image, original)) << cv::typeToString(type) << ": the encoder changed its input";
    EXPECT_EQ(ours, imencodeBytes(ext, image)) << cv::typeToString(type);
    EXPECT_TRUE(sameImage(decodeImage(ours, kReadUnchanged), image)) << cv::typeToString(type);
    for (int flags : kAllFlags) {
      EXPECT_TRUE(sameImage(decodeImage(ours, flags), imdecodeBytes(ours, flags)))
          << cv::typeToString(type) << " flags " << flags;
    }
  }
}

TEST(ImageCodecs, PgmHeaderCommentsAndTruncationAreHandled) {
  const std::string header = "P5\n# a map_server comment\n3 2\n# another\n255\n";
  Bytes pgm(header.begin(), header.end());
  for (std::uint8_t v : {0, 205, 254, 254, 0, 205}) pgm.push_back(v);
  const cv::Mat grid = decodeImage(pgm, kReadGrayscale);
  ASSERT_EQ(grid.size(), cv::Size(3, 2));
  EXPECT_EQ(grid.at<std::uint8_t>(1, 0), 254);
  EXPECT_TRUE(sameImage(grid, imdecodeBytes(pgm, cv::IMREAD_GRAYSCALE)));
  pgm.pop_back();
  std::string problem;
  EXPECT_TRUE(decodeImage(pgm, kReadGrayscale, &problem).empty());
  EXPECT_NE(problem.find("truncated"), std::string::npos) << problem;
}

// ---- Files and errors ----

class ImageCodecFiles : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::scratchDirForThisTest("image_codecs_"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(ImageCodecFiles, WrittenFilesEqualImwritesAndReadBackLikeImread) {
  const cv::Mat bgr = testImage(24, 32, CV_8UC3, 7), depth = testImage(24, 32, CV_16UC1, 8);
  for (const auto& [name, image] : {std::pair{"colour.png", bgr}, {"depth.png", depth}, {"photo.jpg", bgr},
                                    {"grid.pgm", depth}, {"colour.ppm", bgr}}) {
    const std::string ours = (dir_ / name).string(), theirs = (dir_ / ("cv_" + std::string(name))).string();
    writeImage(ours, image);
    ASSERT_TRUE(cv::imwrite(theirs, image));
    std::ifstream a(ours, std::ios::binary), b(theirs, std::ios::binary);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}), std::string(std::istreambuf_iterator<char>(b), {}))
        << name;
    for (int flags : kAllFlags) EXPECT_TRUE(sameImage(readImage(ours, flags), cv::imread(ours, flags))) << name;
  }
}

TEST_F(ImageCodecFiles, ErrorsNameTheFile) {
  const cv::Mat image(4, 4, CV_8UC3, cv::Scalar::all(9));
  const auto expectErrorNaming = [](const std::function<void()>& write, const std::string& file,
                                    const std::string& detail) {
    const std::string error = testing::errorOf(write);
    EXPECT_NE(error.find(file), std::string::npos) << "'" << error << "' does not name " << file;
    EXPECT_NE(error.find(detail), std::string::npos) << "'" << error << "' does not say " << detail;
  };
  const std::string missing_dir = (dir_ / "no" / "such" / "x.png").string();
  expectErrorNaming([&] { writeImage(missing_dir, image); }, missing_dir, "cannot write");
  const std::string bmp = (dir_ / "x.bmp").string();
  expectErrorNaming([&] { writeImage(bmp, image); }, bmp, "bmp");
  const std::string floats = (dir_ / "f.png").string();
  expectErrorNaming([&] { writeImage(floats, cv::Mat(3, 3, CV_32F)); }, floats, "32F");
  EXPECT_THROW(encodeImage(".jpg", cv::Mat(2, 2, CV_16UC1)), core::Error);
  EXPECT_THROW(encodeImage(".pgm", cv::Mat(2, 2, CV_8UC4)), core::Error);

  std::string problem;
  EXPECT_TRUE(readImage((dir_ / "absent.png").string(), kReadColor, &problem).empty());
  EXPECT_NE(problem.find("cannot read"), std::string::npos) << problem;
  std::ofstream(dir_ / "notes.jpg") << "not an image";
  EXPECT_TRUE(readImage((dir_ / "notes.jpg").string(), kReadColor, &problem).empty());
  EXPECT_NE(problem.find("not a PNG, JPEG"), std::string::npos) << problem;
  Bytes truncated = encodeImage(".jpg", image);
  truncated.resize(truncated.size() / 2);
  EXPECT_TRUE(sameImage(decodeImage(truncated, kReadColor), imdecodeBytes(truncated, cv::IMREAD_COLOR)));
}

}  // namespace
}  // namespace amos::io
