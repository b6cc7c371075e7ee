#include "amos/io/realtime_replay.h"

#include <gtest/gtest.h>

#include "amos/testing/scratch_dir.h"

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <algorithm>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "amos/core/error.h"
#include "amos/io/newest_frame_slot.h"

namespace amos::io {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// A tiny TUM-layout sequence (64 x 48) with the given time stamps, in a fresh temporary folder.
class ReplaySequence : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = amos::testing::scratchDirForThisTest("amos_replay_test_");
    fs::create_directories(dir_ / "rgb");
    fs::create_directories(dir_ / "depth");
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Frame i has colour value i and depth (1 + i) m; `bad_depth` names a frame whose depth image is 8-bit.
  SequenceIndex write(const std::vector<double>& stamps, int bad_depth = -1) {
    std::ofstream rgb(dir_ / "rgb.txt"), depth(dir_ / "depth.txt");
    for (std::size_t i = 0; i < stamps.size(); ++i) {
      const std::string stamp = fmt::format("{:.6f}", stamps[i]);
      cv::imwrite((dir_ / "rgb" / (stamp + ".png")).string(),
                  cv::Mat(48, 64, CV_8UC3, cv::Scalar::all(static_cast<double>(i + 1))));  // not black: a black frame is skipped
      cv::Mat d(48, 64, CV_16U, cv::Scalar(5000.0 * static_cast<double>(1 + i)));
      if (static_cast<int>(i) == bad_depth) d = cv::Mat(48, 64, CV_8U, cv::Scalar(200));
      cv::imwrite((dir_ / "depth" / (stamp + ".png")).string(), d);
      rgb << stamp << " rgb/" << stamp << ".png\n";
      depth << stamp << " depth/" << stamp << ".png\n";
    }
    rgb.close();
    depth.close();
    return indexSequence(dir_.string());
  }
  static ReaderOptions smallOptions() {
    ReaderOptions o;
    o.width = 64;
    o.height = 48;
    return o;
  }
  static std::vector<double> evenStamps(std::size_t n, double period_s) {
    std::vector<double> t;
    for (std::size_t i = 0; i < n; ++i) t.push_back(100.0 + period_s * static_cast<double>(i));
    return t;
  }
  static Clock::time_point due(Clock::time_point t0, double stamp, double first) {
    return t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(stamp - first));
  }
  fs::path dir_;
};

TEST(NewestFrameSlot, NewestWinsAndOlderWaitingFramesCountAsDropped) {
  NewestFrameSlot slot;
  EXPECT_FALSE(slot.tryTake());
  for (std::size_t i = 0; i < 3; ++i) {
    RgbdFrame f;
    f.index = i;
    ASSERT_TRUE(slot.put(f));
    EXPECT_FALSE(slot.closed());
  }
  const auto taken = slot.tryTake();
  ASSERT_TRUE(taken);
  EXPECT_EQ(taken->index, 2u);
  EXPECT_FALSE(slot.tryTake());
  EXPECT_EQ(slot.stats().delivered, 3u);
  EXPECT_EQ(slot.stats().dropped, 2u);
  RgbdFrame last;
  last.index = 7;
  ASSERT_TRUE(slot.put(last));
  slot.close();
  EXPECT_FALSE(slot.put(RgbdFrame{}));   // closed: refused, not counted
  EXPECT_EQ(slot.take()->index, 7u);     // what waited is still handed out after close()
  EXPECT_FALSE(slot.take());             // then the end, without blocking
  EXPECT_EQ(slot.stats().delivered, 4u);
}

TEST(NewestFrameSlot, TakeWaitsForAProducerThreadAndStampsArrival) {
  NewestFrameSlot slot;
  const Clock::time_point start = Clock::now();
  std::thread producer([&] {
    std::this_thread::sleep_for(milliseconds(30));  // stands for a camera's frame interval
    RgbdFrame f;
    f.index = 5;
    slot.put(f);
  });
  const auto frame = slot.take();
  producer.join();
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->index, 5u);
  EXPECT_GE(frame->arrival - start, milliseconds(30));
  EXPECT_LE(frame->arrival, Clock::now());
}

TEST(NewestFrameSlot, CloseWithAnErrorRethrowsItOnceEmpty) {
  NewestFrameSlot slot;
  slot.close(std::make_exception_ptr(core::Error("device lost")));
  slot.close();  // the first close decides
  EXPECT_THROW(slot.take(), core::Error);
  EXPECT_FALSE(slot.tryTake());
}

// A consumer that takes every frame at once gets all of them, none before its time and each soon after it.
TEST_F(ReplaySequence, FastConsumerGetsEveryFrameAtItsRecordedTime) {
  const std::vector<double> stamps = evenStamps(8, 0.06);
  RealtimeReplay replay(write(stamps), smallOptions());
  EXPECT_EQ(replay.size(), 8u);
  std::vector<RgbdFrame> got;
  while (auto frame = replay.next()) {
    got.push_back(std::move(*frame));
    if (got.size() == 1) {
      EXPECT_FALSE(replay.poll());  // the next one is due 60 ms later
    }
  }
  ASSERT_EQ(got.size(), 8u);
  const auto t0 = replay.startTime();
  ASSERT_TRUE(t0);
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].index, i);
    EXPECT_DOUBLE_EQ(got[i].timestamp, stamps[i]);
    EXPECT_EQ(got[i].bgr.at<cv::Vec3b>(0, 0)[0], i + 1);
    const Clock::time_point on_time = due(*t0, stamps[i], stamps[0]);
    EXPECT_GE(got[i].arrival, on_time) << "frame " << i << " released early";
    EXPECT_LT(got[i].arrival - on_time, milliseconds(30)) << "frame " << i << " released late";
  }
  EXPECT_EQ(replay.stats().delivered, 8u);
  EXPECT_EQ(replay.stats().dropped, 0u);
}

// A consumer that needs 100 ms per frame of a 30 ms sequence gets the newest frame each time; the frames it never
// saw are counted as dropped, the last frame always reaches it, and delivered = processed + dropped.
TEST_F(ReplaySequence, SlowConsumerGetsTheNewestFrameAndDropsAreCounted) {
  const std::vector<double> stamps = evenStamps(12, 0.03);
  RealtimeReplay replay(write(stamps), smallOptions());
  std::vector<std::size_t> got;
  while (auto frame = replay.next()) {
    got.push_back(frame->index);
    std::this_thread::sleep_for(milliseconds(100));  // the consumer's work on this frame
  }
  ASSERT_GE(got.size(), 2u);
  EXPECT_LT(got.size(), 12u);
  EXPECT_EQ(got.back(), 11u);
  for (std::size_t k = 1; k < got.size(); ++k) EXPECT_GT(got[k], got[k - 1]);
  const SourceStats s = replay.stats();
  EXPECT_EQ(s.delivered, 12u);
  EXPECT_GT(s.dropped, 0u);
  EXPECT_EQ(s.delivered, got.size() + s.dropped);
}

TEST_F(ReplaySequence, PollHandsOutAWaitingFrameWithoutBlocking) {
  const std::vector<double> stamps = evenStamps(3, 0.03);
  RealtimeReplay replay(write(stamps), smallOptions());
  ASSERT_EQ(replay.next()->index, 0u);
  std::this_thread::sleep_for(milliseconds(150));  // every frame has been released meanwhile
  const auto waiting = replay.poll();
  ASSERT_TRUE(waiting);
  EXPECT_EQ(waiting->index, 2u);
  EXPECT_FALSE(replay.poll());
  EXPECT_FALSE(replay.next());
  EXPECT_EQ(replay.stats().dropped, 1u);
}

// A bad frame is skipped by the reader underneath: the replay goes on and counts it.
TEST_F(ReplaySequence, BadFrameIsSkippedAndCounted) {
  RealtimeReplay replay(write(evenStamps(4, 0.01), 2), smallOptions());
  std::vector<std::size_t> frames;
  while (auto f = replay.next()) frames.push_back(f->index);
  EXPECT_FALSE(frames.empty());
  EXPECT_EQ(std::count(frames.begin(), frames.end(), 2u), 0);
  EXPECT_EQ(frames.back(), 3u);
  const SourceStats stats = replay.stats();
  EXPECT_EQ(stats.skipped.count(FrameProblem::kWrongFormat), 1u);
  EXPECT_EQ(stats.delivered, 3u);
}

// --strict: the load error reaches the consumer, after the frames before it.
TEST_F(ReplaySequence, StrictLoadErrorReachesTheConsumerAfterTheFramesBeforeIt) {
  ReaderOptions options = smallOptions();
  options.strict = true;
  RealtimeReplay replay(write(evenStamps(4, 0.01), 2), options);
  std::size_t frames = 0;
  try {
    while (replay.next()) ++frames;
    FAIL() << "expected a core::Error";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("depth"), std::string::npos) << e.what();
  }
  EXPECT_LE(frames, 2u);
}

// Destroying the replay while its clock waits for a frame due in 30 s returns at once.
TEST_F(ReplaySequence, DestructionWakesTheWaitingClock) {
  Clock::time_point destroyed_at;
  const Clock::time_point start = Clock::now();
  {
    RealtimeReplay replay(write({1.0, 31.0}), smallOptions());
    ASSERT_EQ(replay.next()->index, 0u);
  }
  destroyed_at = Clock::now();
  EXPECT_LT(destroyed_at - start, std::chrono::seconds(5));
}

// A stop request reaches a consumer that waits in next() for a frame due in ten minutes: cancel() from another
// thread ends the wait at once (before, Ctrl-C waited out a long gap in the time stamps).
TEST_F(ReplaySequence, CancelEndsAWaitForALateFrameAtOnce) {
  RealtimeReplay replay(write({1.0, 601.0}), smallOptions());
  ASSERT_EQ(replay.next()->index, 0u);
  const Clock::time_point start = Clock::now();
  std::thread canceller([&] {
    std::this_thread::sleep_for(milliseconds(100));
    replay.cancel();
  });
  EXPECT_FALSE(replay.next().has_value());
  canceller.join();
  EXPECT_LT(Clock::now() - start, std::chrono::seconds(5));
  EXPECT_FALSE(replay.next().has_value());
}

}  // namespace
}  // namespace amos::io
