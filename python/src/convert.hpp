#pragma once
// Python values -> the library's types, each checked with a message naming the problem
// (InputError, so Python sees depthtrack.InputError, a ValueError).
#include <depthtrack/camera.hpp>
#include <depthtrack/depth_view.hpp>
#include <depthtrack/pose.hpp>
#include <optional>

#include "bindings.hpp"

namespace depthtrack::python {

// A 4x4 camera-from-object matrix (metres): finite, last row 0 0 0 1, a rotation in the upper 3x3.
Pose pose_from_matrix(py::handle matrix);
py::array_t<double> pose_to_matrix(const Pose& pose);

// A depth image as the tracker reads it: the caller's numpy buffer itself when its rows are
// contiguous (any row stride), else a C-contiguous copy; `array` keeps whichever is read alive.
struct DepthInput {
  py::array array;
  DepthView view;
};
// float32 metres (metres_per_unit must be None) or uint16 units (metres_per_unit required), 2-D, of
// the sensor's size: a shape other than (sensor.height, sensor.width) is refused before any copy.
DepthInput depth_input(py::handle depth, std::optional<double> metres_per_unit, const Camera& sensor);

}  // namespace depthtrack::python
