// Checked conversions from Python values (numpy arrays, sequences) to poses and depth views.
#include "convert.hpp"

#include <array>
#include <cmath>
#include <depthtrack/error.hpp>
#include <sstream>
#include <string>

namespace depthtrack::python {

namespace {

std::string shape_text(const py::array& a) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) text += (i ? ", " : "") + std::to_string(a.shape(i));
  return text + (a.ndim() == 1 ? ",)" : ")");
}

std::string type_name(py::handle value) {
  return py::str(py::type::handle_of(value).attr("__name__"));
}

// A numpy array of T read in place when each row's pixels are adjacent (rows may be any distance
// apart, as in a slice of a larger image); otherwise (a column slice, Fortran order, negative or
// zero strides) a C-contiguous copy.
template <typename T>
py::array readable_rows(const py::array& a) {
  const auto item = static_cast<py::ssize_t>(sizeof(T));
  const bool rows_in_place = a.strides(1) == item && a.strides(0) >= a.shape(1) * item;
  if (rows_in_place) return a;
  return py::array_t<T, py::array::c_style>::ensure(a);
}

}  // namespace

Pose pose_from_matrix(py::handle matrix) {
  const auto m = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(matrix);
  if (!m) {
    PyErr_Clear();
    throw InputError("pose must be a 4x4 matrix of numbers, got " + type_name(matrix));
  }
  if (m.ndim() != 2 || m.shape(0) != 4 || m.shape(1) != 4)
    throw InputError("pose must be a 4x4 matrix (camera from object, metres), got shape " + shape_text(m));
  std::array<double, 16> values{};
  for (py::ssize_t i = 0; i < 4; ++i)
    for (py::ssize_t j = 0; j < 4; ++j) {
      const double v = m.at(i, j);
      if (!std::isfinite(v))
        throw InputError("pose has a non-finite entry " + std::to_string(v) + " at [" + std::to_string(i) + "][" +
                         std::to_string(j) + "]");
      values[static_cast<size_t>(i * 4 + j)] = v;
    }
  if (values[12] != 0 || values[13] != 0 || values[14] != 0 || values[15] != 1) {
    std::ostringstream message;
    message << "pose is not a rigid transform: its last row must be 0 0 0 1, got " << values[12] << " " << values[13]
            << " " << values[14] << " " << values[15];
    throw InputError(message.str());
  }
  try {
    return Pose::from_row_major(values);
  } catch (const InputError& e) {
    throw InputError(std::string("pose is not a rigid transform: ") + e.what());
  }
}

py::array_t<double> pose_to_matrix(const Pose& pose) {
  const Eigen::Matrix4d m = pose.matrix();
  py::array_t<double> out({4, 4});
  auto view = out.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < 4; ++i)
    for (py::ssize_t j = 0; j < 4; ++j) view(i, j) = m(i, j);
  return out;
}

DepthInput depth_input(py::handle depth, std::optional<double> metres_per_unit, const Camera& sensor) {
  if (!py::isinstance<py::array>(depth))
    throw InputError("depth must be a numpy array (float32 metres or uint16 units), got " + type_name(depth));
  const auto a = py::reinterpret_borrow<py::array>(depth);
  const std::string dtype = py::str(a.dtype());
  if (a.ndim() != 2)
    throw InputError("depth must be a 2-D array (height, width), got shape " + shape_text(a) + " of " + dtype);
  // Before readable_rows copies it: a broadcast array may claim terabytes it does not hold.
  if (a.shape(0) != sensor.height || a.shape(1) != sensor.width)
    throw InputError("depth of shape " + shape_text(a) + " does not fit the camera, which is " +
                     std::to_string(sensor.width) + "x" + std::to_string(sensor.height) + ": an array of shape (" +
                     std::to_string(sensor.height) + ", " + std::to_string(sensor.width) + ")");
  const int height = sensor.height, width = sensor.width;
  DepthInput in;
  if (py::isinstance<py::array_t<float>>(a)) {
    if (metres_per_unit)
      throw InputError("metres_per_unit is for uint16 depth; float32 depth is in metres already (pass None)");
    in.array = readable_rows<float>(a);
    in.view = DepthView::metres(static_cast<const float*>(in.array.data()), width, height,
                                static_cast<size_t>(in.array.strides(0)));
  } else if (py::isinstance<py::array_t<uint16_t>>(a)) {
    if (!metres_per_unit)
      throw InputError("uint16 depth needs metres_per_unit (e.g. 0.001 for millimetres; 0 = no measurement)");
    in.array = readable_rows<uint16_t>(a);
    in.view = DepthView::units(static_cast<const uint16_t*>(in.array.data()), width, height, *metres_per_unit,
                               static_cast<size_t>(in.array.strides(0)));
  } else {
    throw InputError(
        "depth must be float32 (metres, NaN = missing) or uint16 (units, with metres_per_unit), got "
        "dtype " +
        dtype);
  }
  return in;
}

}  // namespace depthtrack::python
