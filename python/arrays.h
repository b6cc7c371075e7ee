#pragma once
// NumPy arrays <-> cv::Mat for the Python module, with the checks a caller's arrays get: the argument named in
// every error (TypeError for the wrong kind of object or element type, ValueError for a wrong shape or layout).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <opencv2/core.hpp>

namespace amos::python {

namespace py = pybind11;

// What an argument must be.
struct ArraySpec {
  const char* name;      // the argument's name, for errors
  const char* expected;  // e.g. "uint8 H x W x 3 (BGR)"
  int channels;          // 1: H x W (or H x W x 1); 3: H x W x 3
  bool allow_float32;    // depth: uint16 or float32; else only the depth type below
  int depth;             // CV_8U or CV_16U
};

// A cv::Mat header over the array's pixels (no copy: the array must stay alive while the header is used).
cv::Mat matOf(const py::handle& object, const ArraySpec& spec);

// A NumPy array sharing the image's pixels (no copy): the array keeps the image's buffer alive.
py::array arrayOf(const cv::Mat& image);

}  // namespace amos::python
