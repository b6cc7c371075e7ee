#include "amos/mapio/map_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <cstdint>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <random>

#include "amos/core/error.h"
#include "amos/core/binary_stream.h"
#include "amos/testing/scratch_dir.h"

namespace amos::mapio {
namespace {

core::CameraIntrinsics testIntrinsics() {
  core::CameraIntrinsics c;
  c.fx = 520;
  c.fy = 521;
  c.cx = 320;
  c.cy = 240;
  c.k1 = 0.01;
  return c;
}

std::shared_ptr<const map::Sensor> testSensor(core::CameraIntrinsics c = testIntrinsics()) {
  return std::make_shared<map::Sensor>(c, map::SensorOptions{}, feature::OrbOptions{});
}

// A keyframe of n keypoints on a grid (depth 2 m on all but every fifth), random descriptors, a thumbnail.
map::KeyFramePtr makeKeyFrame(map::Map& m, const std::shared_ptr<const map::Sensor>& sensor, map::FrameId frame_id,
                              int n, double x, unsigned seed) {
  auto f = std::make_shared<map::FrameFeatures>();
  std::mt19937 rng(seed);
  f->descriptors.create(n, 32, CV_8U);
  cv::randu(f->descriptors, 0, 256);
  for (int i = 0; i < n; ++i) {
    f->keys.emplace_back(cv::Point2f(20.5f + 10.0f * (i % 60), 20.25f + 10.0f * (i / 60)), 7.0f + i % 3,
                         0.5f * i, 0.01f * i, i % 8);
    const bool depth = i % 5 != 0;
    f->depth.push_back(depth ? 2.0f + 0.001f * i : -1.0f);
    f->u_right.push_back(depth ? f->keys.back().pt.x - static_cast<float>(sensor->bf() / 2.0) : -1.0f);
  }
  f->grid = feature::KeypointGrid(cv::Rect2d(0, 0, 640, 480), f->keys);
  cv::Mat thumbnail(30, 40, CV_32F);
  cv::randu(thumbnail, -50.0f, 50.0f);
  map::Frame frame = map::makeFrame(frame_id, 0.033 * frame_id, sensor, f, thumbnail, cv::Mat());
  core::SE3 T = core::SE3::Identity();
  T.linear() = Eigen::AngleAxisd(0.05 * x, Eigen::Vector3d(0.2, 1, 0.1).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(-x, 0.01 * x, 0.3);
  frame.setPose(T);
  auto kf = std::make_shared<map::KeyFrame>(m.newKeyFrameId(), frame);
  m.addKeyFrame(kf);
  return kf;
}

// Five keyframes sharing points in a chain, covisibility and spanning tree from Map::updateConnections, counters
// bumped, one keyframe culled (a removed-keyframe record), points fused (gaps in the ids).
void buildMap(map::Map& m, const std::shared_ptr<const map::Sensor>& sensor) {
  std::unique_lock lock(m.mutex());
  std::vector<map::KeyFramePtr> kfs;
  for (int k = 0; k < 5; ++k) kfs.push_back(makeKeyFrame(m, sensor, 10 * k + 3, 120, 0.1 * k, 7 + k));
  std::vector<map::MapPointPtr> points;
  for (int i = 0; i < 100; ++i) {
    points.push_back(m.createMapPoint(Eigen::Vector3d(0.01 * i, 0.02 * (i % 7), 2 + 0.001 * i), kfs[0], i, 3));
  }
  for (int k = 1; k < 5; ++k) {
    for (int i = 10 * k; i < 100; ++i) m.addObservation(points[i], kfs[k], i);
  }
  for (int i = 0; i < 100; i += 3) {
    m.updateDescriptor(points[i]);
    m.updateNormalAndDepth(points[i]);
    points[i]->increaseVisible(i);
    points[i]->increaseFound(i / 2);
    points[i]->increaseDynamicHits(i % 4);
    points[i]->increaseMaskedViews(i % 9);
  }
  for (const auto& kf : kfs) m.updateConnections(kf);
  m.replaceMapPoint(points[98], points[97]);
  m.setKeyFrameBad(kfs[2]);
}

void expectSamePose(const core::SE3& a, const core::SE3& b) { EXPECT_TRUE(a.matrix() == b.matrix()); }

void expectSameMat(const cv::Mat& a, const cv::Mat& b) {
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.type(), b.type());
  if (!a.empty()) {
    EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  }
}

// Entity by entity: every saved field of every keyframe and map point, and the map's own records.
void expectSameMap(const map::Map& a, const map::Map& b) {
  EXPECT_EQ(a.nextKeyFrameId(), b.nextKeyFrameId());
  EXPECT_EQ(a.nextMapPointId(), b.nextMapPointId());
  EXPECT_EQ(a.firstKeyFrameId(), b.firstKeyFrameId());
  ASSERT_EQ(a.removedKeyFrames().size(), b.removedKeyFrames().size());
  for (const auto& [id, r] : a.removedKeyFrames()) {
    ASSERT_TRUE(b.removedKeyFrames().count(id));
    EXPECT_EQ(r.parent, b.removedKeyFrames().at(id).parent);
    expectSamePose(r.T_cp, b.removedKeyFrames().at(id).T_cp);
  }
  ASSERT_EQ(a.numKeyFrames(), b.numKeyFrames());
  for (const auto& ka : a.keyFrames()) {
    SCOPED_TRACE("keyframe " + std::to_string(ka->id()));
    const map::KeyFramePtr kb = b.keyFrame(ka->id());
    ASSERT_TRUE(kb);
    EXPECT_EQ(ka->frameId(), kb->frameId());
    EXPECT_EQ(ka->timestamp(), kb->timestamp());
    expectSamePose(ka->T_cw(), kb->T_cw());
    ASSERT_EQ(ka->size(), kb->size());
    for (int i = 0; i < ka->size(); ++i) {
      const cv::KeyPoint &x = ka->features().keys[i], &y = kb->features().keys[i];
      EXPECT_EQ(x.pt, y.pt);
      EXPECT_EQ(x.size, y.size);
      EXPECT_EQ(x.angle, y.angle);
      EXPECT_EQ(x.response, y.response);
      EXPECT_EQ(x.octave, y.octave);
      EXPECT_EQ(ka->features().depth[i], kb->features().depth[i]);
      EXPECT_EQ(ka->features().u_right[i], kb->features().u_right[i]);
      const map::MapPointPtr &pa = ka->mapPoint(i), &pb = kb->mapPoint(i);
      ASSERT_EQ(pa == nullptr, pb == nullptr) << "keypoint " << i;
      if (pa) {
        EXPECT_EQ(pa->id(), pb->id());
      }
      EXPECT_EQ(ka->features().grid.featuresInArea(x.pt.x, x.pt.y, 3),
                kb->features().grid.featuresInArea(x.pt.x, x.pt.y, 3));
    }
    expectSameMat(ka->features().descriptors, kb->features().descriptors);
    expectSameMat(ka->thumbnail(), kb->thumbnail());
    EXPECT_EQ(ka->connectionWeights(), kb->connectionWeights());
    EXPECT_EQ(ka->orderedConnections(), kb->orderedConnections());
    EXPECT_EQ(ka->parent(), kb->parent());
    EXPECT_EQ(ka->children(), kb->children());
    EXPECT_EQ(ka->hasFirstConnection(), kb->hasFirstConnection());
  }
  ASSERT_EQ(a.numMapPoints(), b.numMapPoints());
  for (const auto& pa : a.mapPoints()) {
    SCOPED_TRACE("map point " + std::to_string(pa->id()));
    const map::MapPointPtr pb = b.mapPoint(pa->id());
    ASSERT_TRUE(pb);
    EXPECT_EQ(pa->firstFrame(), pb->firstFrame());
    EXPECT_EQ(pa->firstKeyFrame(), pb->firstKeyFrame());
    EXPECT_EQ(pa->referenceKeyFrame(), pb->referenceKeyFrame());
    EXPECT_TRUE(pa->position() == pb->position());
    EXPECT_TRUE(pa->normal() == pb->normal());
    EXPECT_EQ(pa->minDistance(), pb->minDistance());
    EXPECT_EQ(pa->maxDistance(), pb->maxDistance());
    expectSameMat(pa->descriptor(), pb->descriptor());
    EXPECT_EQ(pa->observations(), pb->observations());
    EXPECT_EQ(pa->numObservations(), pb->numObservations());
    EXPECT_EQ(pa->visible(), pb->visible());
    EXPECT_EQ(pa->found(), pb->found());
    EXPECT_EQ(pa->dynamicHits(), pb->dynamicHits());
    EXPECT_EQ(pa->maskedViews(), pb->maskedViews());
  }
}

TEST(MapFile, SavedThenLoadedEqualsTheOriginalEntityByEntity) {
  const auto sensor = testSensor();
  map::Map original;
  buildMap(original, sensor);
  ASSERT_EQ(original.numKeyFrames(), 4u);  // one culled
  ASSERT_EQ(original.removedKeyFrames().size(), 1u);
  const auto dir = testing::scratchDirForThisTest("mapio_");
  const std::string path = (dir / "room.map").string();
  const MapFileSummary saved = saveMap(path, original, *sensor);
  EXPECT_EQ(saved.keyframes, 4u);
  EXPECT_EQ(saved.map_points, original.numMapPoints());
  EXPECT_EQ(saved.bytes, std::filesystem::file_size(path));
  map::Map loaded;
  const MapFileSummary summary = loadMap(path, sensor, loaded);
  EXPECT_EQ(summary.keyframes, 4u);
  EXPECT_EQ(summary.max_frame_id, 43u);
  expectSameMap(original, loaded);
  // Saving the loaded map again gives the same bytes.
  EXPECT_EQ(encodeMap(loaded, *sensor), encodeMap(original, *sensor));
  // A loaded map goes on with fresh ids.
  EXPECT_EQ(loaded.newKeyFrameId(), original.nextKeyFrameId());
}

TEST(MapFile, EmptyMapRoundTrips) {
  const auto sensor = testSensor();
  map::Map original, loaded;
  decodeMap(encodeMap(original, *sensor), "empty.map", sensor, loaded);
  expectSameMap(original, loaded);
}

// Loads `bytes` as "<name>" and returns the error message (empty when it loaded).
std::string loadError(const std::string& bytes, const std::shared_ptr<const map::Sensor>& sensor) {
  map::Map m;
  try {
    decodeMap(bytes, "bad/room.map", sensor, m);
  } catch (const core::Error& e) {
    return e.what();
  }
  return "";
}

class MapFileErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    map::Map m;
    buildMap(m, sensor_);
    bytes_ = encodeMap(m, *sensor_);
    ASSERT_EQ(loadError(bytes_, sensor_), "");
  }
  std::shared_ptr<const map::Sensor> sensor_ = testSensor();
  std::string bytes_;
};

TEST_F(MapFileErrors, TruncatedFileNamesTheFileAndTheMissingBytes) {
  const std::string message = loadError(bytes_.substr(0, bytes_.size() - 100), sensor_);
  EXPECT_NE(message.find("bad/room.map"), std::string::npos) << message;
  EXPECT_NE(message.find("truncated"), std::string::npos) << message;
  EXPECT_NE(loadError(bytes_.substr(0, 20), sensor_).find("shorter than the 32-byte header"), std::string::npos);
  EXPECT_NE(loadError("", sensor_).find("bad/room.map"), std::string::npos);
}

TEST_F(MapFileErrors, FlippedByteIsACorruptChecksum) {
  for (const std::size_t at : {kMapHeaderBytes + 5, bytes_.size() / 2, bytes_.size() - 1}) {
    std::string bad = bytes_;
    bad[at] = static_cast<char>(bad[at] ^ 0x10);
    const std::string message = loadError(bad, sensor_);
    EXPECT_NE(message.find("bad/room.map: corrupt: checksum"), std::string::npos) << at << ": " << message;
  }
  EXPECT_NE(loadError(bytes_ + "x", sensor_).find("corrupt"), std::string::npos);
}

TEST_F(MapFileErrors, OtherVersionAndNotAMapFile) {
  std::string other = bytes_;
  other[8] = 7;  // version 7
  const std::string message = loadError(other, sensor_);
  EXPECT_NE(message.find("bad/room.map: map format version 7, this program reads version 1"), std::string::npos)
      << message;
  std::string png = bytes_;
  png.replace(0, 4, "\x89PNG");
  EXPECT_NE(loadError(png, sensor_).find("not an Amos-SLAM map file"), std::string::npos);
}

TEST_F(MapFileErrors, OtherCalibrationNamesTheDifference) {
  core::CameraIntrinsics c = testIntrinsics();
  c.fx = 535.4;
  const std::string message = loadError(bytes_, testSensor(c));
  EXPECT_NE(message.find("bad/room.map: built with another camera calibration"), std::string::npos) << message;
  EXPECT_NE(message.find("fx 520 in the map, 535.4 here"), std::string::npos) << message;
  const auto other_orb = std::make_shared<map::Sensor>(testIntrinsics(), map::SensorOptions{},
                                                       feature::OrbOptions{1000, 1.2, 4, 20, 7});
  EXPECT_NE(loadError(bytes_, other_orb).find("ORBextractor.nLevels 8 in the map, 4 here"), std::string::npos);
}

// The bytes with the header's payload size and checksum made to fit, so that a change reaches the payload's checks.
std::string resealed(std::string bytes) {
  const std::string_view payload(bytes.data() + kMapHeaderBytes, bytes.size() - kMapHeaderBytes);
  const std::uint64_t size = payload.size();
  const std::uint32_t crc = core::crc32(payload);
  bytes.replace(16, 8, reinterpret_cast<const char*>(&size), 8);
  bytes.replace(24, 4, reinterpret_cast<const char*>(&crc), 4);
  return bytes;
}

// The bytes with the first `old` replaced by `replacement`, resealed.
std::string patchedAndResealed(std::string bytes, const std::string& old, const std::string& replacement) {
  const std::size_t at = bytes.find(old);
  EXPECT_NE(at, std::string::npos);
  if (at != std::string::npos) bytes.replace(at, old.size(), replacement);
  return resealed(std::move(bytes));
}

std::string int32s(std::initializer_list<std::int32_t> values) {
  std::string out;
  for (const std::int32_t v : values) out.append(reinterpret_cast<const char*>(&v), sizeof v);
  return out;
}

// A thumbnail claiming more than the file holds is refused before it is allocated (it took up to 64 MB before the
// read failed); non-finite poses and positions and counters below their start are refused (a counter of INT_MIN
// was decremented: signed overflow).
TEST_F(MapFileErrors, LyingSizesNonFiniteValuesAndBadCountersNameTheFile) {
  const std::string thumbnail = int32s({30, 40, CV_32F});
  std::string message = loadError(patchedAndResealed(bytes_, thumbnail, int32s({4096, 4096, CV_32F})), sensor_);
  EXPECT_NE(message.find("bad/room.map: malformed: thumbnail of 4096 x 4096 type 5 is more than the"),
            std::string::npos) << message;

  // The first pose of the payload: the removed keyframe's, after the camera (100 bytes), three ids, the count of
  // removed keyframes and the record's id and parent.
  std::string nan_pose = bytes_;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  nan_pose.replace(kMapHeaderBytes + 100 + 3 * 8 + 3 * 8, 8, reinterpret_cast<const char*>(&nan), 8);
  message = loadError(resealed(nan_pose), sensor_);
  EXPECT_NE(message.find("bad/room.map: malformed: removed keyframe pose holds nan"), std::string::npos) << message;

  // Point 99's counters (visible 100, found 50, dynamic hits 3, masked views 0; buildMap); the pattern is unique.
  const std::string counters = int32s({100, 50, 3, 0});
  message = loadError(patchedAndResealed(bytes_, counters, int32s({INT32_MIN, 50, 3, 0})), sensor_);
  EXPECT_NE(message.find("bad/room.map: malformed: map point"), std::string::npos) << message;
  EXPECT_NE(message.find("has a counter of -2147483648, below 1"), std::string::npos) << message;
}

TEST(MapFile, MissingFileIsAnErrorNamingIt) {
  map::Map m;
  try {
    loadMap("/nonexistent/room.map", testSensor(), m);
    FAIL() << "no error";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/room.map: cannot open"), std::string::npos);
  }
}

TEST(MapFile, AFolderOrASymlinkLoopIsAnErrorNamingIt) {
  const std::filesystem::path dir = testing::scratchDirForThisTest("mapio_");
  std::filesystem::create_symlink(dir / "b.map", dir / "a.map");
  std::filesystem::create_symlink(dir / "a.map", dir / "b.map");
  const auto message = [](const std::string& path) {
    map::Map m;
    try {
      loadMap(path, testSensor(), m);
    } catch (const core::Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(dir.string()), dir.string() + ": is a folder, not a map file");
  EXPECT_EQ(message((dir / "a.map").string()), (dir / "a.map").string() + ": cannot open the map file");
}

TEST(MapFile, LoadsOnlyIntoAnEmptyMap) {
  const auto sensor = testSensor();
  map::Map m;
  buildMap(m, sensor);
  EXPECT_THROW(decodeMap(encodeMap(m, *sensor), "x.map", sensor, m), core::Error);
}

}  // namespace
}  // namespace amos::mapio
