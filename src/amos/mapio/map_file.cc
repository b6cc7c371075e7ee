#include "amos/mapio/map_file.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <shared_mutex>
#include <vector>

#include "amos/core/error.h"
#include "amos/io/atomic_file.h"
#include "amos/core/binary_stream.h"

namespace amos::mapio {

using core::ByteReader;
using core::ByteWriter;
using core::crc32;

namespace {

constexpr char kMagic[8] = {'A', 'M', 'O', 'S', 'M', 'A', 'P', '\0'};
constexpr std::uint32_t kEndianProbe = 0x01020304u;
constexpr int kDescriptorBytes = 32;

// ---- the camera ----

struct CameraRecord {
  double fx, fy, cx, cy, k1, k2, p1, p2, k3;
  std::int32_t width, height;
  double bf, scale_factor;
  std::int32_t num_levels;
};

CameraRecord cameraOf(const map::Sensor& sensor) {
  const core::CameraIntrinsics& c = sensor.camera().intrinsics();
  return {c.fx, c.fy, c.cx, c.cy, c.k1, c.k2, c.p1, c.p2, c.k3, c.width, c.height, sensor.bf(),
          static_cast<double>(sensor.scaleFactor()), sensor.numLevels()};
}

void putCamera(ByteWriter& w, const CameraRecord& c) {
  for (const double v : {c.fx, c.fy, c.cx, c.cy, c.k1, c.k2, c.p1, c.p2, c.k3}) w.put(v);
  w.put(c.width);
  w.put(c.height);
  w.put(c.bf);
  w.put(c.scale_factor);
  w.put(c.num_levels);
}

CameraRecord getCamera(ByteReader& r) {
  CameraRecord c{};
  for (double* v : {&c.fx, &c.fy, &c.cx, &c.cy, &c.k1, &c.k2, &c.p1, &c.p2, &c.k3}) *v = r.get<double>("camera");
  c.width = r.get<std::int32_t>("camera width");
  c.height = r.get<std::int32_t>("camera height");
  c.bf = r.get<double>("camera bf");
  c.scale_factor = r.get<double>("ORB scale factor");
  c.num_levels = r.get<std::int32_t>("ORB levels");
  return c;
}

bool same(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max({1.0, std::abs(a), std::abs(b)}); }

// The differences between the map's camera and the run's, e.g. "fx 535.4 in the map, 517.3 here".
std::vector<std::string> calibrationDifferences(const CameraRecord& saved, const CameraRecord& here) {
  std::vector<std::string> out;
  auto check = [&](const char* name, double a, double b) {
    if (!same(a, b)) out.push_back(fmt::format("{} {} in the map, {} here", name, a, b));
  };
  check("fx", saved.fx, here.fx);
  check("fy", saved.fy, here.fy);
  check("cx", saved.cx, here.cx);
  check("cy", saved.cy, here.cy);
  check("k1", saved.k1, here.k1);
  check("k2", saved.k2, here.k2);
  check("p1", saved.p1, here.p1);
  check("p2", saved.p2, here.p2);
  check("k3", saved.k3, here.k3);
  check("width", saved.width, here.width);
  check("height", saved.height, here.height);
  check("bf", saved.bf, here.bf);
  check("ORBextractor.scaleFactor", saved.scale_factor, here.scale_factor);
  check("ORBextractor.nLevels", saved.num_levels, here.num_levels);
  return out;
}

// ---- poses and small matrices ----

void putPose(ByteWriter& w, const core::SE3& T) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) w.put(T.matrix()(r, c));
}

// A double that must be finite (poses, positions): a NaN or infinity would spread through every later estimate.
double getFinite(ByteReader& r, const char* what) {
  const auto v = r.get<double>(what);
  if (!std::isfinite(v)) r.fail(fmt::format("malformed: {} holds {}, not a finite number", what, v));
  return v;
}

core::SE3 getPose(ByteReader& r, const char* what) {
  core::SE3 T = core::SE3::Identity();
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 4; ++c) T.matrix()(i, c) = getFinite(r, what);
  return T;
}

void putVector3(ByteWriter& w, const Eigen::Vector3d& v) {
  for (int i = 0; i < 3; ++i) w.put(v[i]);
}

Eigen::Vector3d getVector3(ByteReader& r, const char* what) {
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = getFinite(r, what);
  return v;
}

void putImage(ByteWriter& w, const cv::Mat& image) {
  const cv::Mat m = image.isContinuous() ? image : image.clone();
  w.put(static_cast<std::int32_t>(m.rows));
  w.put(static_cast<std::int32_t>(m.cols));
  w.put(static_cast<std::int32_t>(m.type()));
  if (!m.empty()) w.putBytes(m.data, m.total() * m.elemSize());
}

cv::Mat getImage(ByteReader& r, const char* what) {
  const auto rows = r.get<std::int32_t>(what);
  const auto cols = r.get<std::int32_t>(what);
  const auto type = r.get<std::int32_t>(what);
  if (rows == 0 || cols == 0) return cv::Mat();
  if (rows < 0 || cols < 0 || rows > 4096 || cols > 4096 || (type != CV_32F && type != CV_8U)) {
    r.fail(fmt::format("malformed: {} of {} x {} type {}", what, rows, cols, type));
  }
  // Checked before the allocation: a corrupt size would otherwise take up to 64 MB before the read fails.
  const std::size_t bytes = std::size_t(rows) * std::size_t(cols) * CV_ELEM_SIZE(type);
  if (bytes > r.remaining()) {
    r.fail(fmt::format("malformed: {} of {} x {} type {} is more than the {} bytes left", what, rows, cols, type,
                       r.remaining()));
  }
  cv::Mat m(rows, cols, type);
  r.getBytes(m.data, bytes, what);
  return m;
}

// ---- the map ----

void putKeyFrame(ByteWriter& w, const map::KeyFrame& kf) {
  w.put<std::uint64_t>(kf.id());
  w.put<std::uint64_t>(kf.frameId());
  w.put(kf.timestamp());
  putPose(w, kf.T_cw());
  w.put<std::uint64_t>(kf.parent());
  w.put<std::uint8_t>(kf.hasFirstConnection() ? 1 : 0);
  const map::FrameFeatures& f = kf.features();
  w.put<std::uint64_t>(f.size());
  for (std::size_t i = 0; i < f.size(); ++i) {
    const cv::KeyPoint& k = f.keys[i];
    w.put(k.pt.x);
    w.put(k.pt.y);
    w.put(k.size);
    w.put(k.angle);
    w.put(k.response);
    w.put<std::int32_t>(k.octave);
    w.put<std::int32_t>(k.class_id);
    w.put(f.depth[i]);
    w.put(f.u_right[i]);
    w.putBytes(f.descriptors.ptr(static_cast<int>(i)), kDescriptorBytes);
  }
  putImage(w, kf.thumbnail());
  std::vector<std::pair<std::int32_t, std::uint64_t>> points;
  for (int i = 0; i < kf.size(); ++i) {
    if (const map::MapPointPtr& p = kf.mapPoint(i); p && !p->isBad()) points.emplace_back(i, p->id());
  }
  w.put<std::uint64_t>(points.size());
  for (const auto& [i, id] : points) {
    w.put(i);
    w.put(id);
  }
  w.put<std::uint64_t>(kf.connectionWeights().size());
  for (const auto& [id, weight] : kf.connectionWeights()) {
    w.put<std::uint64_t>(id);
    w.put<std::int32_t>(weight);
  }
  w.put<std::uint64_t>(kf.children().size());
  for (const map::KeyFrameId c : kf.children()) w.put<std::uint64_t>(c);
}

void putMapPoint(ByteWriter& w, const map::MapPoint& p) {
  w.put<std::uint64_t>(p.id());
  w.put<std::uint64_t>(p.firstFrame());
  w.put<std::uint64_t>(p.firstKeyFrame());
  w.put<std::uint64_t>(p.referenceKeyFrame());
  putVector3(w, p.position());
  putVector3(w, p.normal());
  w.put(p.minDistanceUnpadded());
  w.put(p.maxDistanceUnpadded());
  w.putBytes(p.descriptor().ptr(), kDescriptorBytes);
  w.put<std::int32_t>(p.visible());
  w.put<std::int32_t>(p.found());
  w.put<std::int32_t>(p.dynamicHits());
  w.put<std::int32_t>(p.maskedViews());
  w.put<std::uint64_t>(p.observations().size());
  for (const auto& [kf, index] : p.observations()) {
    w.put<std::uint64_t>(kf);
    w.put<std::int32_t>(index);
  }
}

}  // namespace

std::string encodeMap(const map::Map& map, const map::Sensor& sensor, MapFileSummary* summary) {
  ByteWriter payload;
  std::vector<map::KeyFramePtr> keyframes;
  std::vector<map::MapPointPtr> points;
  {
    std::shared_lock lock(map.mutex());
    keyframes = map.keyFrames();
    points = map.mapPoints();
    keyframes.erase(std::remove_if(keyframes.begin(), keyframes.end(), [](const auto& k) { return k->isBad(); }),
                    keyframes.end());
    points.erase(std::remove_if(points.begin(), points.end(), [](const auto& p) { return p->isBad(); }),
                 points.end());
    putCamera(payload, cameraOf(sensor));
    payload.put<std::uint64_t>(map.nextKeyFrameId());
    payload.put<std::uint64_t>(map.nextMapPointId());
    payload.put<std::uint64_t>(map.firstKeyFrameId());
    payload.put<std::uint64_t>(map.removedKeyFrames().size());
    for (const auto& [id, record] : map.removedKeyFrames()) {
      payload.put<std::uint64_t>(id);
      payload.put<std::uint64_t>(record.parent);
      putPose(payload, record.T_cp);
    }
    payload.put<std::uint64_t>(keyframes.size());
    for (const auto& kf : keyframes) putKeyFrame(payload, *kf);
    payload.put<std::uint64_t>(points.size());
    for (const auto& p : points) putMapPoint(payload, *p);
    if (summary) {
      summary->keyframes = keyframes.size();
      summary->map_points = points.size();
      summary->removed_keyframes = map.removedKeyFrames().size();
      summary->max_frame_id = 0;
      for (const auto& kf : keyframes) summary->max_frame_id = std::max(summary->max_frame_id, kf->frameId());
      for (const auto& p : points) summary->max_frame_id = std::max(summary->max_frame_id, p->firstFrame());
    }
  }
  ByteWriter file;
  file.putBytes(kMagic, sizeof(kMagic));
  file.put(kMapFormatVersion);
  file.put(kEndianProbe);
  file.put<std::uint64_t>(payload.bytes().size());
  file.put(crc32(payload.bytes()));
  file.put<std::uint32_t>(0);
  file.bytes() += payload.bytes();
  if (summary) summary->bytes = file.bytes().size();
  return std::move(file.bytes());
}

MapFileSummary saveMap(const std::string& path, const map::Map& map, const map::Sensor& sensor) {
  MapFileSummary summary;
  const std::string bytes = encodeMap(map, sensor, &summary);
  io::writeFileAtomically(path, bytes);
  return summary;
}

MapFileSummary decodeMap(const std::string& bytes, const std::string& source,
                         const std::shared_ptr<const map::Sensor>& sensor, map::Map& into) {
  auto fail = [&](const std::string& problem) { throw core::Error(source + ": " + problem); };
  if (bytes.size() < kMapHeaderBytes) {
    fail(fmt::format("not a map file or truncated: {} bytes, shorter than the {}-byte header", bytes.size(),
                     kMapHeaderBytes));
  }
  ByteReader header(std::string_view(bytes.data(), kMapHeaderBytes), source);
  char magic[8];
  header.getBytes(magic, sizeof(magic), "magic");
  if (!std::equal(std::begin(magic), std::end(magic), std::begin(kMagic))) {
    fail("not an Amos-SLAM map file (it does not start with \"AMOSMAP\")");
  }
  const auto version = header.get<std::uint32_t>("version");
  if (version != kMapFormatVersion) {
    fail(fmt::format("map format version {}, this program reads version {} (save the map again with this "
                     "program's version)",
                     version, kMapFormatVersion));
  }
  if (header.get<std::uint32_t>("byte order") != kEndianProbe) {
    fail("written on a machine of another byte order");
  }
  const auto payload_size = header.get<std::uint64_t>("payload size");
  const auto checksum = header.get<std::uint32_t>("checksum");
  const std::size_t have = bytes.size() - kMapHeaderBytes;
  if (have < payload_size) {
    fail(fmt::format("truncated: the header announces {} bytes of map data, the file has {}", payload_size, have));
  }
  if (have > payload_size) {
    fail(fmt::format("corrupt: {} bytes after the {} bytes of map data the header announces", have - payload_size,
                     payload_size));
  }
  const std::string_view payload(bytes.data() + kMapHeaderBytes, have);
  const std::uint32_t actual = crc32(payload);
  if (actual != checksum) {
    fail(fmt::format("corrupt: checksum of the map data is {:08x}, the header says {:08x}", actual, checksum));
  }

  ByteReader r(payload, source);
  const CameraRecord saved = getCamera(r);
  const std::vector<std::string> differences = calibrationDifferences(saved, cameraOf(*sensor));
  if (!differences.empty()) {
    std::string list;
    for (const auto& d : differences) list += (list.empty() ? "" : "; ") + d;
    fail("built with another camera calibration than this run's settings: " + list);
  }

  std::unique_lock lock(into.mutex());
  if (into.numKeyFrames() != 0 || into.numMapPoints() != 0) fail("cannot load into a map that is not empty");
  MapFileSummary summary;
  summary.bytes = bytes.size();
  const auto next_kf = r.get<std::uint64_t>("next keyframe id");
  const auto next_mp = r.get<std::uint64_t>("next map point id");
  const auto first_kf = r.get<std::uint64_t>("first keyframe id");
  const std::size_t n_removed = r.getCount(16 + 96, "removed keyframes");
  for (std::size_t k = 0; k < n_removed; ++k) {
    const auto id = r.get<std::uint64_t>("removed keyframe");
    map::Map::RemovedKeyFrame record;
    record.parent = r.get<std::uint64_t>("removed keyframe parent");
    record.T_cp = getPose(r, "removed keyframe pose");
    into.restoreRemovedKeyFrame(id, record);
  }
  summary.removed_keyframes = n_removed;

  // Keyframes first (their map-point slots are filled once the points exist).
  const map::Sensor& s = *sensor;
  const cv::Rect2d bounds(s.minU(), s.minV(), s.maxU() - s.minU(), s.maxV() - s.minV());
  std::vector<map::KeyFramePtr> keyframes;
  std::vector<std::vector<std::pair<std::int32_t, std::uint64_t>>> slots;
  const std::size_t n_kf = r.getCount(8, "keyframes");
  for (std::size_t k = 0; k < n_kf; ++k) {
    const auto id = r.get<std::uint64_t>("keyframe id");
    if (id >= next_kf) fail(fmt::format("malformed: keyframe id {} is not below the next id {}", id, next_kf));
    if (!keyframes.empty() && id <= keyframes.back()->id()) fail("malformed: keyframe ids are not increasing");
    const auto frame_id = r.get<std::uint64_t>("keyframe frame id");
    const auto timestamp = r.get<double>("keyframe time stamp");
    const core::SE3 T_cw = getPose(r, "keyframe pose");
    const auto parent = r.get<std::uint64_t>("keyframe parent");
    const bool first_connection = r.get<std::uint8_t>("keyframe flags") != 0;
    const std::size_t n = r.getCount(7 * 4 + 2 * 4 + kDescriptorBytes, "keypoints");
    auto f = std::make_shared<map::FrameFeatures>();
    f->keys.resize(n);
    f->depth.resize(n);
    f->u_right.resize(n);
    f->descriptors.create(static_cast<int>(n), kDescriptorBytes, CV_8U);
    for (std::size_t i = 0; i < n; ++i) {
      cv::KeyPoint& key = f->keys[i];
      key.pt.x = r.get<float>("keypoint");
      key.pt.y = r.get<float>("keypoint");
      key.size = r.get<float>("keypoint");
      key.angle = r.get<float>("keypoint");
      key.response = r.get<float>("keypoint");
      key.octave = r.get<std::int32_t>("keypoint");
      key.class_id = r.get<std::int32_t>("keypoint");
      if (key.octave < 0 || key.octave >= s.numLevels()) {
        fail(fmt::format("malformed: keyframe {} keypoint {} on pyramid level {}", id, i, key.octave));
      }
      f->depth[i] = r.get<float>("keypoint depth");
      f->u_right[i] = r.get<float>("keypoint right coordinate");
      r.getBytes(f->descriptors.ptr(static_cast<int>(i)), kDescriptorBytes, "descriptor");
    }
    f->grid = feature::KeypointGrid(bounds, f->keys);
    cv::Mat thumbnail = getImage(r, "thumbnail");
    map::Frame frame = map::makeFrame(frame_id, timestamp, sensor, std::move(f), std::move(thumbnail), cv::Mat());
    frame.T_cw = T_cw;  // as saved, bit for bit (setPose would re-orthonormalise)
    frame.has_pose = true;
    auto kf = std::make_shared<map::KeyFrame>(id, frame);
    kf->setParent(parent);
    if (first_connection) kf->markFirstConnectionDone();
    std::vector<std::pair<std::int32_t, std::uint64_t>> kf_slots(r.getCount(12, "keyframe map points"));
    for (auto& [i, pid] : kf_slots) {
      i = r.get<std::int32_t>("keyframe map point");
      pid = r.get<std::uint64_t>("keyframe map point");
      if (i < 0 || i >= kf->size()) fail(fmt::format("malformed: keyframe {} map point at keypoint {}", id, i));
    }
    std::map<map::KeyFrameId, int> weights;
    const std::size_t n_conn = r.getCount(12, "covisibility links");
    for (std::size_t c = 0; c < n_conn; ++c) {
      const auto other = r.get<std::uint64_t>("covisibility link");
      weights[other] = r.get<std::int32_t>("covisibility weight");
    }
    kf->setConnections(std::move(weights));
    const std::size_t n_children = r.getCount(8, "children");
    for (std::size_t c = 0; c < n_children; ++c) kf->addChild(r.get<std::uint64_t>("child"));
    summary.max_frame_id = std::max(summary.max_frame_id, frame_id);
    into.addKeyFrame(kf);
    keyframes.push_back(kf);
    slots.push_back(std::move(kf_slots));
  }
  if (!keyframes.empty() && into.firstKeyFrameId() != first_kf) {
    fail(fmt::format("malformed: first keyframe {} is not the oldest saved keyframe {}", first_kf,
                     into.firstKeyFrameId()));
  }

  const std::size_t n_mp = r.getCount(8, "map points");
  for (std::size_t k = 0; k < n_mp; ++k) {
    const auto id = r.get<std::uint64_t>("map point id");
    if (id >= next_mp) fail(fmt::format("malformed: map point id {} is not below the next id {}", id, next_mp));
    const auto first_frame = r.get<std::uint64_t>("map point first frame");
    const auto first_kf_of_point = r.get<std::uint64_t>("map point first keyframe");
    const auto reference = r.get<std::uint64_t>("map point reference keyframe");
    const Eigen::Vector3d position = getVector3(r, "map point position");
    const Eigen::Vector3d normal = getVector3(r, "map point normal");
    const auto min_d = getFinite(r, "map point distance");
    const auto max_d = getFinite(r, "map point distance");
    auto p = std::make_shared<map::MapPoint>(id, position, first_kf_of_point, first_frame);
    p->setReferenceKeyFrame(reference);
    p->setNormalAndDistances(normal, min_d, max_d);
    cv::Mat descriptor(1, kDescriptorBytes, CV_8U);
    r.getBytes(descriptor.data, kDescriptorBytes, "map point descriptor");
    p->setDescriptor(descriptor);
    // The counters start at visible = found = 1 (MapPoint's constructor) and only grow.
    const auto counter = [&](std::int32_t least) {
      const auto n = r.get<std::int32_t>("map point counters");
      if (n < least) fail(fmt::format("malformed: map point {} has a counter of {}, below {}", id, n, least));
      return n;
    };
    p->increaseVisible(counter(1) - 1);
    p->increaseFound(counter(1) - 1);
    p->increaseDynamicHits(counter(0));
    p->increaseMaskedViews(counter(0));
    const std::size_t n_obs = r.getCount(12, "observations");
    for (std::size_t o = 0; o < n_obs; ++o) {
      const auto kf_id = r.get<std::uint64_t>("observation");
      const auto index = r.get<std::int32_t>("observation");
      const map::KeyFramePtr kf = into.keyFrame(kf_id);
      if (!kf || index < 0 || index >= kf->size()) {
        fail(fmt::format("malformed: map point {} observed at keypoint {} of keyframe {}, which the map lacks", id,
                         index, kf_id));
      }
      p->addObservation(kf_id, index, kf->features().hasDepth(index));
    }
    summary.max_frame_id = std::max(summary.max_frame_id, static_cast<map::FrameId>(first_frame));
    into.addMapPoint(p);
  }
  if (r.remaining() != 0) fail(fmt::format("malformed: {} bytes left after the map points", r.remaining()));
  for (std::size_t k = 0; k < keyframes.size(); ++k) {
    for (const auto& [i, pid] : slots[k]) {
      map::MapPointPtr p = into.mapPoint(pid);
      if (!p) fail(fmt::format("malformed: keyframe {} refers to map point {}, which the map lacks", keyframes[k]->id(), pid));
      keyframes[k]->setMapPoint(i, std::move(p));
    }
  }
  into.restoreNextIds(next_kf, next_mp);
  summary.keyframes = keyframes.size();
  summary.map_points = n_mp;
  return summary;
}

MapFileSummary loadMap(const std::string& path, const std::shared_ptr<const map::Sensor>& sensor, map::Map& into) {
  // Said before opening: a stream opens a folder, then fails with the C++ library's words on the first read.
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw core::Error(path + ": is a folder, not a map file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw core::Error(path + ": cannot open the map file");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw core::Error(path + ": cannot read the map file");
  return decodeMap(bytes, path, sensor, into);
}

}  // namespace amos::mapio
