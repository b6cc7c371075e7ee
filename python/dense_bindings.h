#pragma once
// The dense map's classes of the Python module (include/amos/dense_map.h): DenseMap, Mesh, Cloud, OccupancyGrid,
// DenseSnapshot, their arrays as NumPy arrays (copies the caller owns), and the writers.
#include <pybind11/pybind11.h>

namespace amos::python {

void bindDense(pybind11::module_& m);

}  // namespace amos::python
