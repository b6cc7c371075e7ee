// import amos_slam: the public C++ API (include/amos/slam.h, sequence_folder.h, logging.h) for Python.
//   colour images: uint8 H x W x 3 arrays in OpenCV's BGR order (cv2.imread's), as amos::Slam::track takes them;
//   depth: uint16 H x W raw sensor values (metres = value / DepthMapFactor) or float32 H x W metres;
//   poses: 4 x 4 float64 arrays T_wc (camera to world); masks: uint8 H x W arrays (255 = dynamic).
// Results are small classes with attributes and a repr (FrameResult, Frame, StampedPose, KeyFrame, MapSummary;
// the dense map's: dense_bindings.h).
// The arrays given are read, never kept or written; the arrays returned are the caller's. The GIL is released while
// the library works (tracking, finishing, reading, and when a Slam or a folder is destroyed), so other Python
// threads run meanwhile and the library's threads can log through `logging` (python_logging.h).
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "amos/sequence_folder.h"
#include "amos/slam.h"
#include "arrays.h"
#include "dense_bindings.h"
#include "python_logging.h"

namespace py = pybind11;
namespace fs = std::filesystem;
using amos::python::arrayOf;
using amos::python::ArraySpec;
using amos::python::matOf;

namespace {

const ArraySpec kBgr{"bgr", "uint8 H x W x 3 (BGR order)", 3, false, CV_8U};
const ArraySpec kDepth{"depth", "uint16 H x W (raw) or float32 H x W (metres)", 1, true, CV_16U};
const ArraySpec kPriorMask{"prior_mask", "uint8 H x W (non-zero = dynamic)", 1, false, CV_8U};

// Destroys with the GIL released: a Slam's or a folder's destructor joins threads that may log through Python.
template <typename T>
struct ReleaseGilDelete {
  void operator()(T* p) const {
    if (PyGILState_Check()) {
      py::gil_scoped_release release;
      delete p;
    } else {
      delete p;
    }
  }
};
template <typename T>
using Holder = std::unique_ptr<T, ReleaseGilDelete<T>>;

// One frame read from a folder, its images as NumPy arrays (made once, shared with the folder's buffers).
struct Frame {
  py::array bgr, depth;
  double timestamp = 0;
  std::string rgb_file, depth_file;
};

Frame frameOf(amos::RgbdImages&& f) {
  return {arrayOf(f.bgr), arrayOf(f.depth), f.timestamp, std::move(f.rgb_file), std::move(f.depth_file)};
}

py::object matrixOrNone(const std::optional<Eigen::Matrix4d>& T) {
  if (!T) return py::none();
  return py::cast(Eigen::Matrix4d(*T));
}

amos::Mode modeOf(const py::object& mode) {
  if (py::isinstance<amos::Mode>(mode)) return mode.cast<amos::Mode>();
  if (py::isinstance<py::str>(mode)) {
    try {
      return amos::parseMode(mode.cast<std::string>());
    } catch (const std::runtime_error&) {
      throw py::value_error("argument 'mode' must be an amos_slam.Mode or one of 'none', 'prior', 'geometry', "
                            "'full', '' (the settings' Dynamic.mode), got '" + mode.cast<std::string>() + "'");
    }
  }
  throw py::type_error("argument 'mode' must be an amos_slam.Mode or a str");
}

// A frame given to track_frames: an object with bgr, depth, timestamp (and prior_mask) attributes (a Frame), or a
// tuple (bgr, depth, timestamp[, prior_mask]).
struct FrameArguments {
  py::object bgr, depth, prior_mask;
  double timestamp = 0;
};

FrameArguments argumentsOf(const py::handle& item) {
  FrameArguments a;
  if (py::hasattr(item, "bgr")) {
    a.bgr = item.attr("bgr");
    a.depth = item.attr("depth");
    a.timestamp = item.attr("timestamp").cast<double>();
    a.prior_mask = py::getattr(item, "prior_mask", py::none());
    return a;
  }
  if (py::isinstance<py::tuple>(item) || py::isinstance<py::list>(item)) {
    const py::sequence s = py::reinterpret_borrow<py::sequence>(item);
    if (s.size() == 3 || s.size() == 4) {
      a.bgr = s[0];
      a.depth = s[1];
      a.timestamp = s[2].cast<double>();
      a.prior_mask = s.size() == 4 ? py::object(s[3]) : py::none();
      return a;
    }
  }
  throw py::type_error("track_frames: each frame must be an amos_slam.Frame (or an object with bgr, depth, "
                       "timestamp attributes) or a tuple (bgr, depth, timestamp[, prior_mask])");
}

void submit(amos::Slam& slam, const py::object& bgr, const py::object& depth, double timestamp,
            const py::object& prior_mask) {
  const cv::Mat colour = matOf(bgr, kBgr), depth_mat = matOf(depth, kDepth);
  const cv::Mat mask = prior_mask.is_none() ? cv::Mat() : matOf(prior_mask, kPriorMask);
  py::gil_scoped_release release;  // the arrays stay referenced by the caller meanwhile; submit copies them
  slam.submit(colour, depth_mat, timestamp, mask);
}

// Slam.track_frames(iterable): the frames pulled one ahead of the results, so that the next frame's per-frame work
// overlaps the current one's tracking (as amos::Slam::trackFrames does in C++).
class FrameStream {
 public:
  FrameStream(py::object slam, const py::iterable& frames)
      : owner_(std::move(slam)), slam_(owner_.cast<amos::Slam&>()), frames_(py::iter(frames)) {}

  amos::FrameResult next() {
    while (more_ && slam_.pending() < 2) pull();
    if (slam_.pending() == 0) throw py::stop_iteration();
    py::gil_scoped_release release;
    return slam_.next();
  }

 private:
  void pull() {
    PyObject* item = PyIter_Next(frames_.ptr());
    if (item == nullptr) {
      if (PyErr_Occurred()) throw py::error_already_set();
      more_ = false;
      return;
    }
    const py::object frame = py::reinterpret_steal<py::object>(item);
    const FrameArguments a = argumentsOf(frame);
    submit(slam_, a.bgr, a.depth, a.timestamp, a.prior_mask);
  }

  py::object owner_;  // keeps the Slam alive
  amos::Slam& slam_;
  py::iterator frames_;
  bool more_ = true;
};

std::string matrixRepr(const std::optional<Eigen::Matrix4d>& T) {
  if (!T) return "None";
  return fmt::format("[t {:.3f} {:.3f} {:.3f}]", (*T)(0, 3), (*T)(1, 3), (*T)(2, 3));
}

// {"key": "value"} or [("key", "value")], values converted with str().
std::vector<std::pair<std::string, std::string>> overridesOf(const py::object& overrides) {
  std::vector<std::pair<std::string, std::string>> out;
  if (overrides.is_none()) return out;
  const py::object items = py::isinstance<py::dict>(overrides) ? overrides.attr("items")() : overrides;
  for (const py::handle item : items) {
    const py::tuple pair = py::reinterpret_borrow<py::object>(item).cast<py::tuple>();
    if (pair.size() != 2)
      throw py::type_error("argument 'overrides' must be a dict {key: value} or (key, value) pairs");
    out.emplace_back(py::str(pair[0]).cast<std::string>(), py::str(pair[1]).cast<std::string>());
  }
  return out;
}

Holder<amos::Slam> makeSlam(const py::object& settings_file, const py::object& mode, bool deterministic,
                            const py::object& models_dir, const py::object& map_file, bool localization_only,
                            const std::string& settings_yaml, const py::object& overrides, bool dense) {
  amos::Options o;
  if (!settings_file.is_none()) o.settings_file = settings_file.cast<fs::path>().string();
  o.settings_yaml = settings_yaml;
  o.overrides = overridesOf(overrides);
  o.mode = modeOf(mode);
  o.deterministic = deterministic;
  if (!models_dir.is_none()) o.models_dir = models_dir.cast<fs::path>().string();
  if (!map_file.is_none()) o.map_file = map_file.cast<fs::path>().string();
  o.localization_only = localization_only;
  o.dense = dense;
  py::gil_scoped_release release;
  return Holder<amos::Slam>(new amos::Slam(o));
}

void bindValues(py::module_& m) {
  py::enum_<amos::TrackingState>(m, "TrackingState", "Whether a frame was tracked.")
      .value("NOT_INITIALIZED", amos::TrackingState::kNotInitialized, "No map yet.")
      .value("OK", amos::TrackingState::kOk, "Tracked: FrameResult.T_wc is the frame's pose.")
      .value("LOST", amos::TrackingState::kLost, "Not tracked (the system relocalises when it can).");

  py::enum_<amos::Mode>(m, "Mode", "The dynamic front end: which of its stages judge what moves.")
      .value("NONE", amos::Mode::kNone, "Every keypoint is used, apart from the caller's prior masks.")
      .value("PRIOR", amos::Mode::kPrior, "The person segmentation network's masks.")
      .value("GEOMETRY", amos::Mode::kGeometry, "The geometric stage alone (no network).")
      .value("FULL", amos::Mode::kFull, "Both.")
      .value("FROM_SETTINGS", amos::Mode::kFromSettings, "The settings' Dynamic.mode.");

  py::class_<amos::FrameResult>(m, "FrameResult", "What Slam.track returns for one frame.")
      .def_readonly("frame", &amos::FrameResult::frame, "0-based number of the frame in this Slam.")
      .def_readonly("timestamp", &amos::FrameResult::timestamp, "The frame's time stamp, as given (seconds).")
      .def_readonly("state", &amos::FrameResult::state, "The TrackingState after the frame.")
      .def_property_readonly(
          "T_wc", [](const amos::FrameResult& r) { return matrixOrNone(r.T_wc); },
          "The frame's pose as tracked now (4 x 4 float64, camera to world), or None when it was not tracked.")
      .def_readonly("new_keyframe", &amos::FrameResult::new_keyframe, "Whether the frame became a keyframe.")
      .def_readonly("relocalized", &amos::FrameResult::relocalized, "Whether it was tracked again after being lost.")
      .def_property_readonly(
          "dynamic_mask", [](const amos::FrameResult& r) { return arrayOf(r.dynamic_mask); },
          "uint8 H x W, 255 = judged dynamic (the front end's regions and the caller's prior mask).")
      .def_readonly("keypoints", &amos::FrameResult::keypoints, "ORB keypoints extracted.")
      .def_readonly("keypoints_removed", &amos::FrameResult::keypoints_removed,
                    "Of those, inside the dynamic mask (not used).")
      .def_readonly("extract_ms", &amos::FrameResult::extract_ms, "Wall ms of this frame's ORB extraction.")
      .def_readonly("build_ms", &amos::FrameResult::build_ms, "Wall ms of building the frame (depth, grid).")
      .def_readonly("track_ms", &amos::FrameResult::track_ms, "Wall ms of tracking the frame.")
      .def("__repr__", [](const amos::FrameResult& r) {
        return fmt::format("FrameResult(frame={}, timestamp={:.6f}, state={}, T_wc={}, keypoints={}, removed={})",
                           r.frame, r.timestamp, amos::toString(r.state), matrixRepr(r.T_wc), r.keypoints,
                           r.keypoints_removed);
      }, "A one-line summary.");

  py::class_<amos::StampedPose>(m, "StampedPose", "A pose at a time: an entry of Slam.trajectory().")
      .def_readonly("timestamp", &amos::StampedPose::timestamp, "Seconds, as given to track().")
      .def_property_readonly("T_wc", [](const amos::StampedPose& p) { return Eigen::Matrix4d(p.T_wc); },
                             "4 x 4 float64, camera to world.")
      .def("__repr__", [](const amos::StampedPose& p) {
        return fmt::format("StampedPose(timestamp={:.6f}, T_wc={})", p.timestamp, matrixRepr(p.T_wc));
      }, "A one-line summary.");

  py::class_<amos::KeyFrame>(m, "KeyFrame",
                             "A keyframe of the map (Slam.keyframes() and Slam.take_keyframe_events()).")
      .def_readonly("id", &amos::KeyFrame::id, "The map's id of the keyframe.")
      .def_readonly("timestamp", &amos::KeyFrame::timestamp, "Time stamp of the frame it was made from.")
      .def_property_readonly("T_wc", [](const amos::KeyFrame& k) { return Eigen::Matrix4d(k.T_wc); },
                             "Its pose (4 x 4 float64, camera to world).")
      .def("__repr__", [](const amos::KeyFrame& k) {
        return fmt::format("KeyFrame(id={}, timestamp={:.6f}, T_wc={})", k.id, k.timestamp, matrixRepr(k.T_wc));
      }, "A one-line summary.");

  py::class_<amos::MapSummary>(m, "MapSummary", "Counts of the map and the frames (Slam.summary()).")
      .def_readonly("keyframes", &amos::MapSummary::keyframes, "Keyframes in the map.")
      .def_readonly("map_points", &amos::MapSummary::map_points, "Map points in the map.")
      .def_readonly("loops_closed", &amos::MapSummary::loops_closed, "Loops closed.")
      .def_readonly("frames", &amos::MapSummary::frames, "Frames tracked (of every state).")
      .def_readonly("tracked", &amos::MapSummary::tracked, "Of them, with state OK.")
      .def_readonly("lost", &amos::MapSummary::lost, "Of them, with state LOST.")
      .def("__repr__", [](const amos::MapSummary& s) {
        return fmt::format("MapSummary(keyframes={}, map_points={}, loops_closed={}, frames={}, tracked={}, lost={})",
                           s.keyframes, s.map_points, s.loops_closed, s.frames, s.tracked, s.lost);
      }, "A one-line summary.");

  py::class_<Frame>(m, "Frame", "One frame of a SequenceFolder (what Slam.track_frames takes).")
      .def_readonly("bgr", &Frame::bgr, "uint8 H x W x 3, BGR order.")
      .def_readonly("depth", &Frame::depth, "uint16 H x W raw depth, as stored.")
      .def_readonly("timestamp", &Frame::timestamp, "Time stamp of the colour image (seconds).")
      .def_readonly("rgb_file", &Frame::rgb_file, "The colour image's file.")
      .def_readonly("depth_file", &Frame::depth_file, "The depth image's file.")
      .def("__repr__", [](const Frame& f) {
        return fmt::format("Frame(timestamp={:.6f}, rgb_file='{}', {}x{})", f.timestamp, f.rgb_file,
                           f.bgr.ndim() > 1 ? f.bgr.shape(1) : 0, f.bgr.ndim() > 1 ? f.bgr.shape(0) : 0);
      }, "A one-line summary.");
}

void bindSlam(py::module_& m) {
  py::class_<FrameStream>(m, "FrameStream", "The iterator of Slam.track_frames: one FrameResult per frame.")
      .def("__iter__", [](py::object self) { return self; }, "Itself.")
      .def("__next__", &FrameStream::next, "Tracks the next frame and returns its FrameResult.");

  py::class_<amos::Slam, Holder<amos::Slam>>(m, "Slam", R"(The SLAM system, fed one RGB-D frame at a time.

    with amos_slam.Slam("configs/tum2.yaml", mode=amos_slam.Mode.FULL) as slam:
        for result in slam.track_frames(amos_slam.SequenceFolder("data/seq")):
            print(result.state, result.T_wc)
        slam.write_trajectory("trajectory.txt")

Calls on one Slam from several threads are serialised. Errors: RuntimeError naming the file, key or argument at
fault (TypeError / ValueError for an argument of the wrong kind or shape).)")
      .def(py::init(&makeSlam), py::arg("settings_file") = py::none(), py::arg("mode") = amos::Mode::kFromSettings,
           py::arg("deterministic") = false, py::arg("models_dir") = py::none(), py::arg("map_file") = py::none(),
           py::arg("localization_only") = false, py::arg("settings_yaml") = "",
           py::arg("overrides") = py::none(), py::arg("dense") = false,
           R"(Reads the settings and loads the models, the vocabulary and the map.

settings_file: the settings (YAML, as configs/*.yaml; str or pathlib.Path), or settings_yaml: their text.
mode: an amos_slam.Mode or its name ('none', 'prior', 'geometry', 'full'); default: the settings' Dynamic.mode.
deterministic: same input, same trajectory, bit for bit (what `amos-slam run --deterministic` does).
models_dir: the folder of the models and vocabulary (default: Segmentation.modelsDir, $AMOS_MODELS, the installed
data folder, ./models, ../shared/models). map_file: start from a saved map; localization_only: never extend it.
overrides: settings keys over the file's values, e.g. {"ORBextractor.nFeatures": "1500"} (unknown keys are errors).
dense: fuse the dense static map as `amos-slam run --dense` (Dense.* settings): dense_map() after finish(),
dense_snapshot() while running. Only when amos_slam.dense_available (the library built with Open3D).)")
      .def(
          "track",
          [](amos::Slam& slam, const py::object& bgr, const py::object& depth, double timestamp,
             const py::object& prior_mask) {
            const cv::Mat colour = matOf(bgr, kBgr), depth_mat = matOf(depth, kDepth);
            const cv::Mat mask = prior_mask.is_none() ? cv::Mat() : matOf(prior_mask, kPriorMask);
            py::gil_scoped_release release;  // the arrays stay referenced by the caller meanwhile
            return slam.track(colour, depth_mat, timestamp, mask);
          },
          py::arg("bgr"), py::arg("depth"), py::arg("timestamp"), py::arg("prior_mask") = py::none(),
          R"(Tracks one frame and returns its FrameResult.

bgr: uint8 H x W x 3 in BGR order; depth: uint16 H x W raw (metres = value / DepthMapFactor) or float32 metres;
both of the settings' camera size, C-contiguous. timestamp: seconds, finite, greater than the last frame's.
prior_mask: optional uint8 H x W, non-zero where your own detector found something dynamic.)")
      .def(
          "track_frames",
          [](py::object self, const py::iterable& frames) { return FrameStream(std::move(self), frames); },
          py::arg("frames"),
          R"(Tracks every frame of an iterable and yields one FrameResult per frame, in order.

Each frame is an amos_slam.Frame (a SequenceFolder yields them), an object with bgr, depth, timestamp (and
prior_mask) attributes, or a tuple (bgr, depth, timestamp[, prior_mask]). The next frame is taken one ahead, so its
per-frame work overlaps the current one's tracking: `amos-slam run`'s speed from a loop of your own.)")
      .def("submit", &submit, py::arg("bgr"), py::arg("depth"), py::arg("timestamp"),
           py::arg("prior_mask") = py::none(),
           "Hands a frame over (the arguments as track's) and returns at once; next() returns its result.")
      .def("next", &amos::Slam::next, py::call_guard<py::gil_scoped_release>(),
           "Finishes the oldest submitted frame and returns its FrameResult.")
      .def("pending", &amos::Slam::pending, py::call_guard<py::gil_scoped_release>(),
           "Frames submitted and not yet returned by next().")
      .def("load_map", [](amos::Slam& s, const fs::path& path) {
             py::gil_scoped_release release;
             s.loadMap(path.string());
           }, py::arg("path"), "Starts from a saved map (str or pathlib.Path); only before the first frame.")
      .def("finish", &amos::Slam::finish, py::call_guard<py::gil_scoped_release>(),
           "Tracks the frames still submitted, lets local mapping settle and stops it. Idempotent.")
      .def_property_readonly("finished",
                             py::cpp_function(&amos::Slam::finished, py::call_guard<py::gil_scoped_release>()),
                             "Whether finish() was called.")
      .def("save_map", [](const amos::Slam& s, const fs::path& path) {
             py::gil_scoped_release release;
             s.saveMap(path.string());
           }, py::arg("path"), "Writes the map (after finish(): the settled map).")
      .def("write_trajectory", [](const amos::Slam& s, const fs::path& path) {
             py::gil_scoped_release release;
             s.writeTrajectory(path.string());
           }, py::arg("path"), "Writes trajectory() as a TUM file, as `amos-slam run` writes trajectory.txt.")
      .def("trajectory", &amos::Slam::trajectory, py::call_guard<py::gil_scoped_release>(),
           "A StampedPose per tracked frame, with the map's corrections (the final trajectory after finish()).")
      .def("keyframes", &amos::Slam::keyFrames, py::call_guard<py::gil_scoped_release>(),
           "The map's keyframes (KeyFrame: id, timestamp, T_wc), by id.")
      .def("take_keyframe_events", &amos::Slam::takeKeyFrameEvents,
           "The keyframes mapped since the last call (KeyFrame: id, timestamp, T_wc).")
      .def("map_points",
           [](const amos::Slam& slam) {
             std::vector<Eigen::Vector3d> points;
             {
               py::gil_scoped_release release;
               points = slam.mapPoints();
             }
             py::array_t<double> out(std::vector<py::ssize_t>{static_cast<py::ssize_t>(points.size()), 3});
             auto a = out.mutable_unchecked<2>();
             for (std::size_t i = 0; i < points.size(); ++i)
               for (int k = 0; k < 3; ++k) a(i, k) = points[i][k];
             return out;
           },
           "The good map points' world positions, an N x 3 float64 array.")
      .def("summary", &amos::Slam::summary, py::call_guard<py::gil_scoped_release>(),
           "A MapSummary: counts of the map and the frames.")
      .def("dense_map", &amos::Slam::denseMap, py::call_guard<py::gil_scoped_release>(),
           "The DenseMap fused with the final trajectory, as `amos-slam run --dense` (after finish(); dense=True).")
      .def("dense_snapshot", &amos::Slam::denseSnapshot, py::call_guard<py::gil_scoped_release>(),
           "The live volume's surface so far (DenseSnapshot), or None before the first (dense=True).")
      .def("dense_live_grid", &amos::Slam::denseLiveGrid, py::call_guard<py::gil_scoped_release>(),
           "The floor plan (OccupancyGrid) of the live surface so far, or None before a floor is found (dense=True).")
      .def_property_readonly("image_size", [](const amos::Slam& s) {
        const cv::Size size = s.imageSize();
        return py::make_tuple(size.width, size.height);
      }, "(width, height) every frame must have: the settings' camera size.")
      .def("__enter__", [](py::object self) { return self; }, "Returns the Slam itself.")
      .def("__exit__", [](amos::Slam& s, const py::object&, const py::object&, const py::object&) {
             py::gil_scoped_release release;
             s.finish();
             return false;
           }, "Finishes the Slam (finish()); exceptions propagate.")
      .def("__repr__", [](const amos::Slam& s) {
        py::gil_scoped_release release;
        const amos::MapSummary m = s.summary();
        return fmt::format("Slam(frames={}, keyframes={}, map_points={}, finished={})", m.frames, m.keyframes,
                           m.map_points, s.finished() ? "True" : "False");
      }, "A one-line summary.");
}

void bindSequenceFolder(py::module_& m) {
  py::class_<amos::SequenceFolder, Holder<amos::SequenceFolder>>(m, "SequenceFolder",
                                                                 R"(A recorded TUM/Bonn-layout folder or ROS 1 bag.

    for frame in amos_slam.SequenceFolder("data/seq"):   # Frame: bgr, depth, timestamp, ...
        ...
    with amos_slam.SequenceFolder("fr1_xyz.bag", groundtruth_topic="/tf") as bag:
        poses = bag.ground_truth                            # [StampedPose], from /tf's /world -> /kinect

A path ending in ".bag" is read as `amos-slam run --sequence X.bag` reads it (docs/ros.md); only by a module built
with the ROS part (amos_slam.bags_available), else a RuntimeError naming the bag. The keyword arguments choose the
bag's topics (None: the TUM, OpenNI2 or RealSense driver's names) and the ground truth's; for a folder they must be
left out. Iterating reads the frames in order, decoded ahead in a thread of the sequence's own; a frame that cannot
be read is skipped with a warning (logger "amos_slam") and counted in `skipped`, as `amos-slam run` does. One pass:
a second loop goes on where the first stopped. As a context manager it stops that thread on leaving.)")
      .def(py::init([](const fs::path& dir, const std::optional<std::string>& rgb_topic,
                       const std::optional<std::string>& depth_topic,
                       const std::optional<std::string>& camera_info_topic,
                       const std::optional<std::string>& groundtruth_topic,
                       const std::optional<std::string>& groundtruth_parent_frame,
                       const std::optional<std::string>& groundtruth_child_frame) {
             amos::SequenceOptions o;
             for (const auto& [value, target] :
                  {std::pair{&rgb_topic, &o.rgb_topic}, std::pair{&depth_topic, &o.depth_topic},
                   std::pair{&camera_info_topic, &o.camera_info_topic},
                   std::pair{&groundtruth_topic, &o.groundtruth_topic},
                   std::pair{&groundtruth_parent_frame, &o.groundtruth_parent_frame},
                   std::pair{&groundtruth_child_frame, &o.groundtruth_child_frame}}) {
               if (*value) *target = **value;
             }
             py::gil_scoped_release release;
             return Holder<amos::SequenceFolder>(new amos::SequenceFolder(dir.string(), o));
           }),
           py::arg("dir"), py::kw_only(), py::arg("rgb_topic") = py::none(), py::arg("depth_topic") = py::none(),
           py::arg("camera_info_topic") = py::none(), py::arg("groundtruth_topic") = py::none(),
           py::arg("groundtruth_parent_frame") = py::none(), py::arg("groundtruth_child_frame") = py::none(),
           "Indexes the folder or bag (str or pathlib.Path); the topics and frames as keywords (bags only).")
      .def("__len__", &amos::SequenceFolder::size, "The associated frames.")
      .def(
          "read",
          [](const amos::SequenceFolder& folder, std::size_t i) {
            amos::RgbdImages f;
            {
              py::gil_scoped_release release;
              f = folder.read(i);
            }
            return frameOf(std::move(f));
          },
          py::arg("i"), "Frame i (0-based) as a Frame; an unreadable frame is an error naming its file.")
      .def("__iter__", [](py::object self) { return self; }, "The folder itself: its frames in order (one pass).")
      .def(
          "__next__",
          [](amos::SequenceFolder& folder) {
            std::optional<amos::RgbdImages> f;
            {
              py::gil_scoped_release release;
              f = folder.next();
            }
            if (!f) throw py::stop_iteration();
            return frameOf(std::move(*f));
          },
          "The next readable frame (bad frames skipped).")
      .def_property_readonly("skipped",
                             py::cpp_function(&amos::SequenceFolder::skipped,
                                              py::call_guard<py::gil_scoped_release>()),
                             "Frames skipped so far because they could not be read (or their files are missing).")
      .def_property_readonly("ground_truth_file", &amos::SequenceFolder::groundTruthFile,
                             "The sequence's ground truth file ('' when it has none).")
      .def_property_readonly("ground_truth", py::cpp_function(&amos::SequenceFolder::groundTruth,
                                                              py::call_guard<py::gil_scoped_release>()),
                             "The ground truth's poses ([StampedPose]) from the file or the bag's topic; [] if none.")
      .def_property_readonly("is_bag", &amos::SequenceFolder::isBag, "Whether it is a ROS 1 bag.")
      .def_property_readonly("dir", &amos::SequenceFolder::dir, "The folder or bag, as given.")
      .def("__enter__", [](py::object self) { return self; }, "Returns the sequence itself.")
      .def("__exit__",
           [](amos::SequenceFolder& folder, const py::object&, const py::object&, const py::object&) {
             // Its read-ahead thread ends with it: the object left behind is a moved-from one (each use an error).
             py::gil_scoped_release release;
             amos::SequenceFolder gone(std::move(folder));
             return false;
           }, "Stops reading ahead and closes the folder or bag; using it afterwards is an error.")
      .def("__repr__", [](const amos::SequenceFolder& f) {
        py::gil_scoped_release release;
        return fmt::format("SequenceFolder('{}', frames={}, skipped={})", f.dir(), f.size(), f.skipped());
      }, "A one-line summary.");
}

}  // namespace

PYBIND11_MODULE(amos_slam, m) {
  m.doc() = "Amos-SLAM: RGB-D SLAM for dynamic scenes (docs/api.md). The library logs through the `logging` logger "
            "\"amos_slam\" (set_log_level).";
  m.attr("__version__") = amos::kVersion;
  amos::python::bindLogging(m);
  bindValues(m);
  amos::python::bindDense(m);
  bindSlam(m);
  bindSequenceFolder(m);
  m.attr("bags_available") = amos::bagReadingAvailable();
}
