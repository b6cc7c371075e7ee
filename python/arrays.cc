#include "arrays.h"

#include <memory>
#include <string>
#include <vector>

namespace amos::python {

namespace {

[[noreturn]] void typeError(const ArraySpec& spec, const std::string& got) {
  throw py::type_error(std::string("argument '") + spec.name + "' must be a numpy array of " + spec.expected +
                       ", got " + got);
}
[[noreturn]] void valueError(const ArraySpec& spec, const std::string& got) {
  throw py::value_error(std::string("argument '") + spec.name + "' must be " + spec.expected + ", got " + got);
}

std::string shapeText(const py::array& a) {
  std::string s = "shape (";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

}  // namespace

cv::Mat matOf(const py::handle& object, const ArraySpec& spec) {
  if (!py::isinstance<py::array>(object)) typeError(spec, std::string(py::str(py::type::of(object).attr("__name__"))));
  const py::array array = py::reinterpret_borrow<py::array>(object);
  int depth = -1;
  // array_t's check compares element types as NumPy does (equivalent types, native byte order).
  if (py::isinstance<py::array_t<std::uint8_t>>(array) && spec.depth == CV_8U) depth = CV_8U;
  if (py::isinstance<py::array_t<std::uint16_t>>(array) && spec.depth == CV_16U) depth = CV_16U;
  if (py::isinstance<py::array_t<float>>(array) && spec.allow_float32) depth = CV_32F;
  if (depth < 0) typeError(spec, "dtype " + std::string(py::str(array.dtype())));
  const bool three_dims = array.ndim() == 3;
  const int channels = three_dims ? static_cast<int>(array.shape(2)) : 1;
  if (!(array.ndim() == 2 || three_dims) || channels != spec.channels || (spec.channels == 3 && !three_dims))
    valueError(spec, shapeText(array));
  if (!(array.flags() & py::array::c_style))
    valueError(spec, "an array that is not C-contiguous (numpy.ascontiguousarray makes one)");
  return cv::Mat(static_cast<int>(array.shape(0)), static_cast<int>(array.shape(1)), CV_MAKETYPE(depth, channels),
                 const_cast<void*>(array.data()));
}

py::array arrayOf(const cv::Mat& image) {
  if (image.empty()) return py::array_t<std::uint8_t>(std::vector<py::ssize_t>{0, 0});
  // A continuous copy of the header (the image's own buffer, shared): owned by the capsule, freed with the array.
  auto held = std::make_unique<cv::Mat>(image.isContinuous() ? image : image.clone());
  const cv::Mat* owner = held.get();
  py::capsule free_owner(held.get(), [](void* p) { delete static_cast<cv::Mat*>(p); });
  held.release();  // the capsule owns it now
  std::vector<py::ssize_t> shape{owner->rows, owner->cols};
  if (owner->channels() > 1) shape.push_back(owner->channels());
  py::dtype dtype;
  switch (owner->depth()) {
    case CV_8U: dtype = py::dtype::of<std::uint8_t>(); break;
    case CV_16U: dtype = py::dtype::of<std::uint16_t>(); break;
    case CV_32F: dtype = py::dtype::of<float>(); break;
    default: throw std::runtime_error("amos_slam: unsupported image type");
  }
  return py::array(dtype, shape, owner->data, free_owner);
}

}  // namespace amos::python
