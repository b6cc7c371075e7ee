// import amos_slam: the public C++ API (include/amos/slam.h, sequence_folder.h) for Python.
//   colour images: uint8 H x W x 3 arrays in OpenCV's BGR order (cv2.imread's), as amos::Slam::track takes them;
//   depth: uint16 H x W raw sensor values (metres = value / DepthMapFactor) or float32 H x W metres;
//   poses: 4 x 4 float64 arrays T_wc (camera to world); masks: uint8 H x W arrays (255 = dynamic).
// Every array returned is a copy the caller owns; the arrays given are read, never kept or written. The GIL is
// released while the library works (track, finish, constructing, maps), so other Python threads run meanwhile.
// Lifetime as in C++: a Slam owns its threads and stops them in finish() or when it is collected. Keyframes are
// polled (take_keyframe_events): a callback from the mapping thread into Python could wait for the GIL that a
// caller of finish() holds.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>

#include "amos/sequence_folder.h"
#include "amos/slam.h"

namespace py = pybind11;

namespace {

// A cv::Mat header over the array's pixels (no copy; the array must stay alive while it is used).
cv::Mat matOf(const py::array& array, const char* what) {
  const py::buffer_info info = array.request();
  if (!(array.flags() & py::array::c_style))
    throw std::invalid_argument(std::string(what) + " must be a C-contiguous array (numpy.ascontiguousarray)");
  int depth = -1;
  if (info.format == py::format_descriptor<std::uint8_t>::format()) depth = CV_8U;
  if (info.format == py::format_descriptor<std::uint16_t>::format()) depth = CV_16U;
  if (info.format == py::format_descriptor<float>::format()) depth = CV_32F;
  if (depth < 0) throw std::invalid_argument(std::string(what) + ": expected uint8, uint16 or float32 elements");
  if (info.ndim == 2) return cv::Mat(int(info.shape[0]), int(info.shape[1]), CV_MAKETYPE(depth, 1), info.ptr);
  if (info.ndim == 3)
    return cv::Mat(int(info.shape[0]), int(info.shape[1]), CV_MAKETYPE(depth, int(info.shape[2])), info.ptr);
  throw std::invalid_argument(std::string(what) + ": expected an H x W or H x W x C array");
}

// A new array with the image's pixels.
py::array arrayOf(const cv::Mat& image) {
  if (image.empty()) return py::array_t<std::uint8_t>(std::vector<py::ssize_t>{0, 0});
  std::vector<py::ssize_t> shape{image.rows, image.cols};
  if (image.channels() > 1) shape.push_back(image.channels());
  py::array out;
  switch (image.depth()) {
    case CV_8U: out = py::array_t<std::uint8_t>(shape); break;
    case CV_16U: out = py::array_t<std::uint16_t>(shape); break;
    case CV_32F: out = py::array_t<float>(shape); break;
    default: throw std::runtime_error("unsupported image type");
  }
  const std::size_t row = image.cols * image.elemSize();
  auto* dst = static_cast<std::uint8_t*>(out.mutable_data());
  for (int r = 0; r < image.rows; ++r) std::memcpy(dst + r * row, image.ptr(r), row);
  return out;
}

py::dict frameDict(const amos::RgbdImages& f) {
  py::dict d;
  d["bgr"] = arrayOf(f.bgr);
  d["depth"] = arrayOf(f.depth);
  d["timestamp"] = f.timestamp;
  d["rgb_file"] = f.rgb_file;
  d["depth_file"] = f.depth_file;
  return d;
}

py::dict keyFrameDict(const amos::KeyFrameEvent& e) {
  py::dict d;
  d["id"] = e.id;
  d["timestamp"] = e.timestamp;
  d["T_wc"] = Eigen::Matrix4d(e.T_wc);
  return d;
}

}  // namespace

PYBIND11_MODULE(amos_slam, m) {
  m.doc() = "Amos-SLAM: RGB-D SLAM for dynamic scenes (see docs/api.md)";
  m.attr("__version__") = amos::kVersion;

  py::enum_<amos::TrackingState>(m, "TrackingState")
      .value("NOT_INITIALIZED", amos::TrackingState::kNotInitialized)
      .value("OK", amos::TrackingState::kOk)
      .value("LOST", amos::TrackingState::kLost);

  py::class_<amos::FrameResult>(m, "FrameResult")
      .def_readonly("frame", &amos::FrameResult::frame)
      .def_readonly("timestamp", &amos::FrameResult::timestamp)
      .def_readonly("state", &amos::FrameResult::state)
      .def_property_readonly("T_wc", [](const amos::FrameResult& r) { return Eigen::Matrix4d(r.T_wc); })
      .def_readonly("new_keyframe", &amos::FrameResult::new_keyframe)
      .def_readonly("relocalized", &amos::FrameResult::relocalized)
      .def_property_readonly("dynamic_mask", [](const amos::FrameResult& r) { return arrayOf(r.dynamic_mask); })
      .def_readonly("keypoints", &amos::FrameResult::keypoints)
      .def_readonly("keypoints_removed", &amos::FrameResult::keypoints_removed);

  py::class_<amos::Slam>(m, "Slam")
      .def(py::init([](const std::string& settings_file, const std::string& mode, bool deterministic,
                       const std::string& models_dir, const std::string& map_file, bool localization_only) {
             amos::Options o;
             o.settings_file = settings_file;
             o.mode = mode;
             o.deterministic = deterministic;
             o.models_dir = models_dir;
             o.map_file = map_file;
             o.localization_only = localization_only;
             py::gil_scoped_release release;
             return std::make_unique<amos::Slam>(o);
           }),
           py::arg("settings_file"), py::arg("mode") = "", py::arg("deterministic") = false,
           py::arg("models_dir") = "", py::arg("map_file") = "", py::arg("localization_only") = false,
           "Reads the settings (YAML, as configs/*.yaml) and loads the models; mode '' = the settings' "
           "Dynamic.mode; models_dir '' = the installed data folder, then ./models, ../shared/models")
      .def(
          "track",
          [](amos::Slam& slam, const py::array& bgr, const py::array& depth, double timestamp) {
            const cv::Mat colour = matOf(bgr, "bgr"), depth_mat = matOf(depth, "depth");
            py::gil_scoped_release release;  // the arrays stay referenced by the caller's frame meanwhile
            return slam.track(colour, depth_mat, timestamp);
          },
          py::arg("bgr"), py::arg("depth"), py::arg("timestamp"),
          "Tracks one frame: bgr uint8 HxWx3 (BGR order), depth uint16 raw or float32 metres")
      .def(
          "submit",
          [](amos::Slam& slam, const py::array& bgr, const py::array& depth, double timestamp) {
            const cv::Mat colour = matOf(bgr, "bgr"), depth_mat = matOf(depth, "depth");
            py::gil_scoped_release release;
            slam.submit(colour, depth_mat, timestamp);
          },
          py::arg("bgr"), py::arg("depth"), py::arg("timestamp"),
          "Hands a frame over and returns at once (its features start in the library's threads); next() returns "
          "its result")
      .def("next", &amos::Slam::next, py::call_guard<py::gil_scoped_release>(),
           "Finishes the oldest submitted frame and returns its FrameResult")
      .def("pending", &amos::Slam::pending)
      .def("load_map", &amos::Slam::loadMap, py::arg("path"), py::call_guard<py::gil_scoped_release>())
      .def("finish", &amos::Slam::finish, py::call_guard<py::gil_scoped_release>())
      .def("save_map", &amos::Slam::saveMap, py::arg("path"), py::call_guard<py::gil_scoped_release>())
      .def("write_trajectory", &amos::Slam::writeTrajectory, py::arg("path"),
           py::call_guard<py::gil_scoped_release>())
      .def("trajectory",
           [](const amos::Slam& slam) {
             py::list out;
             for (const amos::StampedPose& p : slam.trajectory())
               out.append(py::make_tuple(p.timestamp, Eigen::Matrix4d(p.T_wc)));
             return out;
           },
           "[(timestamp, T_wc 4x4)] of every tracked frame, with the map's corrections")
      .def("keyframes",
           [](const amos::Slam& slam) {
             py::list out;
             for (const amos::StampedPose& p : slam.keyFrames())
               out.append(py::make_tuple(p.timestamp, Eigen::Matrix4d(p.T_wc)));
             return out;
           })
      .def("take_keyframe_events",
           [](amos::Slam& slam) {
             py::list out;
             for (const amos::KeyFrameEvent& e : slam.takeKeyFrameEvents()) out.append(keyFrameDict(e));
             return out;
           },
           "The keyframes mapped since the last call: [{id, timestamp, T_wc}]")
      .def("map_points",
           [](const amos::Slam& slam) {
             const std::vector<Eigen::Vector3d> points = slam.mapPoints();
             py::array_t<double> out(std::vector<py::ssize_t>{static_cast<py::ssize_t>(points.size()), 3});
             auto a = out.mutable_unchecked<2>();
             for (std::size_t i = 0; i < points.size(); ++i)
               for (int k = 0; k < 3; ++k) a(i, k) = points[i][k];
             return out;
           })
      .def("summary", [](const amos::Slam& slam) {
        const amos::MapSummary s = slam.summary();
        py::dict d;
        d["keyframes"] = s.keyframes;
        d["map_points"] = s.map_points;
        d["loops_closed"] = s.loops_closed;
        d["frames"] = s.frames;
        d["tracked"] = s.tracked;
        d["lost"] = s.lost;
        return d;
      });

  py::class_<amos::SequenceFolder>(m, "SequenceFolder")
      .def(py::init<const std::string&>(), py::arg("dir"))
      .def("__len__", &amos::SequenceFolder::size)
      .def(
          "read",
          [](const amos::SequenceFolder& folder, std::size_t i) {
            amos::RgbdImages f;
            {
              py::gil_scoped_release release;
              f = folder.read(i);
            }
            return frameDict(f);
          },
          py::arg("i"), "Frame i: {bgr uint8 HxWx3, depth uint16 raw, timestamp, rgb_file, depth_file}")
      .def(
          "next",
          [](amos::SequenceFolder& folder) -> py::object {
            std::optional<amos::RgbdImages> f;
            {
              py::gil_scoped_release release;
              f = folder.next();
            }
            if (!f) return py::none();
            return frameDict(*f);
          },
          "The next frame in order (as read(i)), decoded ahead by the folder's own thread; None after the last")
      .def("ground_truth_file", &amos::SequenceFolder::groundTruthFile);
}
