#include "amos/io/dataset.h"

#include <gtest/gtest.h>

#include "amos/testing/scratch_dir.h"

#include <filesystem>
#include <fstream>
#include <functional>
#include <opencv2/imgcodecs.hpp>

#include "amos/core/error.h"
#include "amos/core/log_capture.h"
#include "amos/testing/shared_data.h"

namespace amos::io {
namespace {

namespace fs = std::filesystem;

// A tiny TUM-layout sequence in a fresh temporary folder.
class TinySequence : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = amos::testing::scratchDirForThisTest("amos_dataset_test_");
    fs::create_directories(dir_ / "rgb");
    fs::create_directories(dir_ / "depth");
  }
  void TearDown() override { fs::remove_all(dir_); }

  void writeImages(const std::string& stamp, cv::Size size = {64, 48}, int depth_type = CV_16U) {
    cv::imwrite((dir_ / "rgb" / (stamp + ".png")).string(), cv::Mat(size, CV_8UC3, cv::Scalar(10, 20, 30)));
    cv::Mat depth(size, depth_type, cv::Scalar(5000));
    if (depth_type == CV_8U) depth.setTo(200);
    cv::imwrite((dir_ / "depth" / (stamp + ".png")).string(), depth);
  }
  void writeFile(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
  ReaderOptions smallOptions() const {
    ReaderOptions o;
    o.width = 64;
    o.height = 48;
    return o;
  }
  // The error a --strict reader of the sequence ends with, after delivering `good` frames.
  FrameLoadError strictReaderError(std::size_t good) const {
    ReaderOptions options = smallOptions();
    options.strict = true;
    SequenceReader reader(indexSequence(dir_.string()), options);
    for (std::size_t k = 0; k < good; ++k) EXPECT_EQ(reader.next()->index, k);
    try {
      reader.next();
    } catch (const FrameLoadError& e) {
      return e;
    }
    ADD_FAILURE() << "expected a FrameLoadError";
    return FrameLoadError(FrameProblem::kUnreadable, "", "none");
  }
  fs::path dir_;
};

using Pair = std::pair<std::size_t, std::size_t>;

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const core::Error& e) {
    return e.what();
  }
  return "";
}

TEST(AssociateStamps, GreedyNearestWithinWindowLikeAssociatePy) {
  const std::vector<double> rgb = {0.00, 0.033, 0.066, 0.5};
  const std::vector<double> depth = {0.010, 0.030, 0.031, 0.070};
  const auto m = associateStamps(rgb, depth, 0.02);
  ASSERT_EQ(m.size(), 3u);  // 0.5 has no depth within 0.02 s
  EXPECT_EQ(m[0], Pair(0, 0));
  EXPECT_EQ(m[1], Pair(1, 2));  // 0.031 is closer than 0.030
  EXPECT_EQ(m[2], Pair(2, 3));
}

TEST(SequenceLists, ParsedFromTextAsIndexSequenceReadsThem) {
  AssociationStats stats;
  const auto rows = parseAssociationFile("# t_rgb rgb t_depth depth\n1.0 rgb/1.png 1.01 depth/1.png\n"
                                         "2.0 rgb/2.png 2.5 depth/2.png\n",
                                         "assoc.txt", 0.02, stats);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].rgb_file, "rgb/2.png");
  EXPECT_DOUBLE_EQ(rows[1].t_depth, 2.5);
  EXPECT_EQ(stats.file, "assoc.txt");
  EXPECT_EQ(stats.rows, 2u);
  EXPECT_EQ(stats.rows_beyond_window, 1u);
  EXPECT_NE(errorOf([] {
              AssociationStats s;
              parseAssociationFile("2.0 a 2.0 b\n1.0 c 1.0 d\n", "assoc.txt", 0.02, s);
            }).find("assoc.txt:2:"),
            std::string::npos);

  const auto frames = associateFrameLists("1.0 rgb/1.png\n2.0 rgb/2.png\n", "rgb.txt", "1.01 depth/1.png\n",
                                          "depth.txt", 0.02);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].rgb_file, "rgb/1.png");
  EXPECT_EQ(frames[0].depth_file, "depth/1.png");
  EXPECT_NE(errorOf([] { associateFrameLists("1.0 a\n", "rgb.txt", "x depth/1.png\n", "depth.txt", 0.02); })
                .find("depth.txt:1: timestamp is not a number: 'x'"),
            std::string::npos);
}

TEST_F(TinySequence, AssociatesListsAndSkipsMissingFile) {
  writeImages("1.000000");
  writeImages("1.033000");
  writeFile("rgb.txt", "# color images\n1.000000 rgb/1.000000.png\n1.033000 rgb/1.033000.png\n1.066 rgb/gone.png\n");
  writeFile("depth.txt", "# depth\r\n1.005 depth/1.000000.png\r\n1.040 depth/1.033000.png\r\n1.07 depth/x.png\r\n");
  const SequenceIndex index = indexSequence(dir_.string());
  ASSERT_EQ(index.frames.size(), 2u);
  EXPECT_DOUBLE_EQ(index.frames[1].t_depth, 1.040);
  EXPECT_TRUE(index.groundtruth_file.empty());
  SequenceReader reader(index, smallOptions());
  int count = 0;
  while (auto frame = reader.next()) {
    EXPECT_EQ(frame->index, static_cast<std::size_t>(count));
    EXPECT_FLOAT_EQ(frame->depth.at<float>(0, 0), 1.0f);
    ++count;
  }
  EXPECT_EQ(count, 2);
}

// An all-black frame (a covered lens) is skipped as blank, not passed on as a depth dropout "tracked from colour".
TEST_F(TinySequence, ABlackFrameIsSkippedAsBlank) {
  writeImages("1.0");
  cv::imwrite((dir_ / "rgb" / "2.0.png").string(), cv::Mat(48, 64, CV_8UC3, cv::Scalar::all(0)));
  cv::imwrite((dir_ / "depth" / "2.0.png").string(), cv::Mat(48, 64, CV_16U, cv::Scalar(0)));
  writeFile("associations.txt", "1.0 rgb/1.0.png 1.0 depth/1.0.png\n2.0 rgb/2.0.png 2.0 depth/2.0.png\n");
  SequenceReader reader(indexSequence(dir_.string()), smallOptions());
  std::size_t delivered = 0;
  while (reader.next()) ++delivered;
  EXPECT_EQ(delivered, 1u);
  EXPECT_EQ(reader.stats().skipped.count(FrameProblem::kBlank), 1u);
  EXPECT_STREQ(frameProblemName(FrameProblem::kBlank), "blank");
}

// A list appended twice: the repeated rows are left out and counted, not read as more frames.
TEST_F(TinySequence, RepeatedRowsOfTheListsAreLeftOutAndCounted) {
  writeImages("1.0");
  writeImages("2.0");
  const std::string rgb = "1.0 rgb/1.0.png\n2.0 rgb/2.0.png\n", depth = "1.0 depth/1.0.png\n2.0 depth/2.0.png\n";
  writeFile("rgb.txt", rgb + "2.0 rgb/2.0.png\n");
  writeFile("depth.txt", depth);
  const SequenceIndex index = indexSequence(dir_.string());
  EXPECT_EQ(index.frames.size(), 2u);
  EXPECT_EQ(index.association.duplicate_rows, 1u);
}

// As a FrameSource the folder reader delivers on demand: poll() is next(), nothing is dropped, and every frame
// is stamped when it is handed over.
TEST_F(TinySequence, ReaderIsAFrameSourceThatNeverDrops) {
  writeImages("1.000000");
  writeImages("1.033000");
  writeFile("rgb.txt", "1.000000 rgb/1.000000.png\n1.033000 rgb/1.033000.png\n");
  writeFile("depth.txt", "1.000000 depth/1.000000.png\n1.033000 depth/1.033000.png\n");
  SequenceReader reader(indexSequence(dir_.string()), smallOptions());
  FrameSource& source = reader;
  EXPECT_EQ(source.size(), 2u);
  const auto before = std::chrono::steady_clock::now();
  const auto first = source.poll();
  ASSERT_TRUE(first);
  EXPECT_EQ(first->index, 0u);
  EXPECT_GE(first->arrival, before);
  EXPECT_EQ(source.next()->index, 1u);
  EXPECT_FALSE(source.poll());
  EXPECT_EQ(source.stats().delivered, 2u);
  EXPECT_EQ(source.stats().dropped, 0u);
}

TEST_F(TinySequence, MalformedLineNamesFileAndLine) {
  writeFile("rgb.txt", "# header\n1.0 rgb/a.png\nnot-a-time rgb/b.png\n");
  writeFile("depth.txt", "1.0 depth/a.png\n");
  try {
    indexSequence(dir_.string());
    FAIL() << "expected an error";
  } catch (const core::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("rgb.txt:3"), std::string::npos) << what;
  }
}

TEST_F(TinySequence, AssociationFileWithTooFewFieldsIsAnError) {
  writeFile("associations.txt", "1.0 rgb/a.png 1.01\n");
  EXPECT_THROW(indexSequence(dir_.string()), core::Error);
}

TEST_F(TinySequence, AssociationRowsThatDoNotGoForwardInTimeAreAnErrorNamingTheLine) {
  writeImages("1.0");
  const std::string ok = "# rgb depth\n1.000 rgb/1.0.png 1.001 depth/1.0.png\n1.033 rgb/1.0.png 1.034 depth/1.0.png\n";
  const std::pair<std::string, std::string> cases[] = {
      {"1.020 rgb/1.0.png 1.050 depth/1.0.png\n", "RGB timestamp 1.020000 does not increase (line 3 has 1.033000)"},
      {"1.033 rgb/1.0.png 1.050 depth/1.0.png\n", "RGB timestamp 1.033000 does not increase"},
      {"1.066 rgb/1.0.png 1.020 depth/1.0.png\n", "depth timestamp 1.020000 does not increase"},
  };
  for (const auto& [row, expected] : cases) {
    writeFile("associations.txt", ok + row);
    const std::string e = errorOf([&] { indexSequence(dir_.string()); });
    EXPECT_NE(e.find("associations.txt:4: " + expected), std::string::npos) << e;
  }
  writeFile("associations.txt", ok);
  EXPECT_EQ(indexSequence(dir_.string()).frames.size(), 2u);
}

TEST_F(TinySequence, AssociationRowsBeyondTheWindowAreWarnedAboutOnceAndCounted) {
  writeImages("1.0");
  writeFile("associations.txt",
            "1.000 rgb/1.0.png 1.010 depth/1.0.png\n"
            "1.033 rgb/1.0.png 1.083 depth/1.0.png\n"
            "1.066 rgb/1.0.png 1.085 depth/1.0.png\n"  // 0.019 s: inside the window
            "1.100 rgb/1.0.png 1.200 depth/1.0.png\n");
  core::LogCapture log;
  const SequenceIndex index = indexSequence(dir_.string(), 0.02);
  EXPECT_EQ(index.frames.size(), 4u);  // kept: the run decides what to make of them
  EXPECT_EQ(index.association.file, (dir_ / "associations.txt").string());
  EXPECT_EQ(index.association.rows, 4u);
  EXPECT_EQ(index.association.rows_beyond_window, 2u);
  EXPECT_DOUBLE_EQ(index.association.window_s, 0.02);
  const auto lines = log.lines();
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("warning"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find("2 of 4 rows"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find("first: line 2, 0.050 s"), std::string::npos) << lines[0];
}

TEST_F(TinySequence, AssociatedListsHaveNoRowsBeyondTheWindow) {
  writeImages("1.0");
  writeFile("rgb.txt", "1.0 rgb/1.0.png\n1.5 rgb/1.0.png\n");
  writeFile("depth.txt", "1.01 depth/1.0.png\n1.6 depth/1.0.png\n");
  const SequenceIndex index = indexSequence(dir_.string());
  EXPECT_EQ(index.frames.size(), 1u);
  EXPECT_TRUE(index.association.file.empty());
  EXPECT_EQ(index.association.rows_beyond_window, 0u);
}

TEST_F(TinySequence, EmptySequenceIsAnError) {
  writeFile("rgb.txt", "# nothing\n");
  writeFile("depth.txt", "# nothing\n");
  EXPECT_THROW(indexSequence(dir_.string()), core::Error);
}

TEST_F(TinySequence, EightBitDepthIsAClearError) {
  writeImages("1.0", {64, 48}, CV_8U);
  writeFile("associations.txt", "1.0 rgb/1.0.png 1.0 depth/1.0.png\n");
  try {
    loadRgbdFrame(indexSequence(dir_.string()).frames[0], smallOptions(), 0);
    FAIL() << "expected an error";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("8-bit"), std::string::npos) << e.what();
  }
}

// Every way a listed frame can be unusable mid-sequence: each is skipped with a warning and counted by reason;
// the frames around them are delivered in order.
TEST_F(TinySequence, BadFramesAreSkippedAndCountedByReason) {
  std::string list;
  for (int i = 0; i < 6; ++i) {
    const std::string stamp = std::to_string(i + 1) + ".0";
    writeImages(stamp, i == 2 ? cv::Size(32, 48) : cv::Size(64, 48), i == 3 ? CV_8U : CV_16U);
    list += stamp + " rgb/" + stamp + ".png " + stamp + " depth/" + stamp + ".png\n";
  }
  list += "7.0 rgb/gone.png 7.0 depth/gone.png\n";  // missing before the run
  writeFile("associations.txt", list);
  // Frame 1: a PNG cut off half way (a copy interrupted, a full disk).
  const fs::path truncated = dir_ / "rgb" / "2.0.png";
  const auto size = fs::file_size(truncated);
  fs::resize_file(truncated, size / 2);
  const SequenceIndex index = indexSequence(dir_.string());
  ASSERT_EQ(index.frames.size(), 6u);
  ASSERT_EQ(index.missing.size(), 1u);
  fs::remove(dir_ / "depth" / "5.0.png");  // frame 4: missing once the run is under way
  ReaderOptions options = smallOptions();
  options.prefetch = 1;
  SequenceReader reader(index, options);
  std::vector<std::size_t> delivered;
  while (auto frame = reader.next()) delivered.push_back(frame->index);
  EXPECT_EQ(delivered, (std::vector<std::size_t>{0, 5}));
  const SkippedFrames skipped = reader.stats().skipped;
  EXPECT_EQ(skipped.count(FrameProblem::kUnreadable), 1u);
  EXPECT_EQ(skipped.count(FrameProblem::kWrongSize), 1u);
  EXPECT_EQ(skipped.count(FrameProblem::kWrongFormat), 1u);
  EXPECT_EQ(skipped.count(FrameProblem::kMissing), 2u);
  EXPECT_EQ(skipped.total(), 5u);
  EXPECT_EQ(reader.stats().delivered, 2u);
}

TEST_F(TinySequence, LoadErrorsNameTheFileAndTheReason) {
  writeImages("1.0", {32, 48});
  writeImages("2.0", {64, 48}, CV_8U);
  writeFile("associations.txt", "1.0 rgb/1.0.png 1.0 depth/1.0.png\n2.0 rgb/2.0.png 2.0 depth/2.0.png\n");
  const SequenceIndex index = indexSequence(dir_.string());
  try {
    loadRgbdFrame(index.frames[0], smallOptions(), 0);
    FAIL() << "expected a FrameLoadError";
  } catch (const FrameLoadError& e) {
    EXPECT_EQ(e.problem(), FrameProblem::kWrongSize);
    EXPECT_EQ(e.file(), index.frames[0].rgb_file);
    EXPECT_NE(std::string(e.what()).find("32x48"), std::string::npos) << e.what();
  }
  try {
    loadRgbdFrame(index.frames[1], smallOptions(), 1);
    FAIL() << "expected a FrameLoadError";
  } catch (const FrameLoadError& e) {
    EXPECT_EQ(e.problem(), FrameProblem::kWrongFormat);
    EXPECT_EQ(e.file(), index.frames[1].depth_file);
  }
  EXPECT_STREQ(frameProblemName(FrameProblem::kWrongFormat), "wrong_format");
}

// A PNG whose header declares a huge image is refused by its header, before any pixel is decoded (before, the
// whole image was decoded first: 2.45 GB for 20000x20000).
TEST_F(TinySequence, AnImageOfTheWrongSizeIsRefusedByItsHeaderBeforeDecoding) {
  writeImages("1.0");
  const fs::path rgb = dir_ / "rgb" / "1.0.png";
  std::fstream png(rgb, std::ios::in | std::ios::out | std::ios::binary);
  png.seekp(16);
  const char huge[8] = {0, 0, 0x4e, 0x20, 0, 0, 0x4e, 0x20};  // IHDR width and height 20000, big-endian
  png.write(huge, sizeof huge);
  png.close();
  writeFile("associations.txt", "1.0 rgb/1.0.png 1.0 depth/1.0.png\n");
  const SequenceIndex index = indexSequence(dir_.string());
  try {
    loadRgbdFrame(index.frames[0], smallOptions(), 0);
    FAIL() << "expected a FrameLoadError";
  } catch (const FrameLoadError& e) {
    EXPECT_EQ(e.problem(), FrameProblem::kWrongSize) << e.what();
    EXPECT_NE(std::string(e.what()).find("20000x20000, the settings say 64x48"), std::string::npos) << e.what();
  }
}

// --strict: the first bad frame ends the stream with its error, after the frames before it.
TEST_F(TinySequence, StrictReaderRethrowsTheFirstBadFrame) {
  writeImages("1.0");
  writeImages("2.0", {32, 48});
  writeImages("3.0");
  writeFile("associations.txt", "1.0 rgb/1.0.png 1.0 depth/1.0.png\n2.0 rgb/2.0.png 2.0 depth/2.0.png\n"
                                "3.0 rgb/3.0.png 3.0 depth/3.0.png\n");
  const FrameLoadError e = strictReaderError(1);
  EXPECT_EQ(e.problem(), FrameProblem::kWrongSize);
  EXPECT_NE(std::string(e.what()).find("2.0.png"), std::string::npos) << e.what();
}

TEST_F(TinySequence, StrictReaderRefusesAListedFileThatIsMissing) {
  writeImages("1.0");
  writeFile("associations.txt", "1.0 rgb/1.0.png 1.0 depth/1.0.png\n2.0 rgb/2.0.png 2.0 depth/2.0.png\n");
  const FrameLoadError e = strictReaderError(0);
  EXPECT_EQ(e.problem(), FrameProblem::kMissing);
  EXPECT_NE(std::string(e.what()).find("rgb/2.0.png"), std::string::npos) << e.what();
}

// A depth image with no valid pixel, or fewer than ReaderOptions::min_valid_depth (1 %), is a sensor dropout: the
// frame is delivered with its depth cleared and flagged; 2 % valid is an ordinary (if poor) depth image.
TEST_F(TinySequence, NearlyEmptyDepthIsADropoutNotAnError) {
  const cv::Mat rgb(48, 64, CV_8UC3, cv::Scalar(1, 2, 3));
  const int pixels = 48 * 64;
  auto depthWithValid = [&](int valid) {
    cv::Mat d(48, 64, CV_16U, cv::Scalar(0));
    for (int k = 0; k < valid; ++k) d.at<std::uint16_t>(k / 64, k % 64) = 5000;
    return d;
  };
  const std::vector<std::pair<int, bool>> cases = {{0, true}, {pixels / 200, true}, {pixels / 50, false}};
  std::string list;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string stamp = std::to_string(i + 1) + ".0";
    cv::imwrite((dir_ / "rgb" / (stamp + ".png")).string(), rgb);
    cv::imwrite((dir_ / "depth" / (stamp + ".png")).string(), depthWithValid(cases[i].first));
    list += stamp + " rgb/" + stamp + ".png " + stamp + " depth/" + stamp + ".png\n";
  }
  writeFile("associations.txt", list);
  const SequenceIndex index = indexSequence(dir_.string());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const RgbdFrame f = loadRgbdFrame(index.frames[i], smallOptions(), i);
    EXPECT_EQ(f.depth_dropout, cases[i].second) << cases[i].first << " valid pixels";
    if (f.depth_dropout) {
      EXPECT_EQ(cv::countNonZero(f.depth), 0);
    } else {
      EXPECT_EQ(cv::countNonZero(f.depth), cases[i].first);
    }
  }
  SequenceReader reader(index, smallOptions());
  std::size_t n = 0;
  while (reader.next()) ++n;
  EXPECT_EQ(n, 3u);
  EXPECT_EQ(reader.stats().skipped.total(), 0u);
}

TEST(RealSequences, ReadsTheSharedTumAndBonnSlices) {
  AMOS_REQUIRE_DATA("tum_fr2_desk_first50");
  AMOS_REQUIRE_DATA("tum_fr1_desk_first9");
  AMOS_REQUIRE_DATA("bonn_crowd_dev");
  const std::string data = testing::dataPath("");
  const auto fr2 = indexSequence(data + "tum_fr2_desk_first50");
  EXPECT_EQ(fr2.frames.size(), 50u);
  EXPECT_EQ(fr2.association.rows_beyond_window, 0u);
  EXPECT_FALSE(fr2.groundtruth_file.empty());
  // fr1's association file lists the whole sequence; only 9 frames' files are there.
  EXPECT_EQ(indexSequence(data + "tum_fr1_desk_first9").frames.size(), 9u);
  const auto bonn = indexSequence(data + "bonn_crowd_dev");
  EXPECT_EQ(bonn.frames.size(), 270u);
  ReaderOptions options;
  options.depth_factor = 5000;
  const RgbdFrame f = loadRgbdFrame(bonn.frames[0], options, 0);
  EXPECT_EQ(f.bgr.type(), CV_8UC3);
  EXPECT_EQ(f.depth.type(), CV_32F);
  double min_depth, max_depth;
  cv::minMaxLoc(f.depth, &min_depth, &max_depth);
  EXPECT_GT(max_depth, 1.0);
  EXPECT_LT(max_depth, 20.0);
}

}  // namespace
}  // namespace amos::io
