// depthtrack.Camera (pinhole intrinsics) and depthtrack.Mesh (the object's triangles, metres).
#include <pybind11/eigen.h>
#include <pybind11/stl/filesystem.h>

#include <depthtrack/camera.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/mesh.hpp>
#include <sstream>

#include "bindings.hpp"

namespace depthtrack::python {

namespace {

Camera camera_from_matrix(int width, int height, py::handle k) {
  const auto K = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(k);
  if (!K) {
    PyErr_Clear();
    throw InputError("K must be a 3x3 matrix of numbers");
  }
  if (K.ndim() != 2 || K.shape(0) != 3 || K.shape(1) != 3) throw InputError("K must be a 3x3 matrix");
  Eigen::Matrix3d m;
  for (py::ssize_t i = 0; i < 3; ++i)
    for (py::ssize_t j = 0; j < 3; ++j) m(i, j) = K.at(i, j);
  return Camera::from_matrix(width, height, m);
}

std::string describe(const Camera& c) {
  std::ostringstream out;
  out << "Camera(width=" << c.width << ", height=" << c.height << ", fx=" << c.fx << ", fy=" << c.fy << ", cx=" << c.cx
      << ", cy=" << c.cy << ")";
  return out.str();
}

}  // namespace

void bind_geometry(py::module_& m) {
  py::class_<Camera>(m, "Camera",
                     "Pinhole intrinsics of the depth images (pixels; OpenCV convention, pixel (u, v) centred at "
                     "(u, v)); checked on construction")
      .def(py::init(&Camera::make), py::arg("width"), py::arg("height"), py::arg("fx"), py::arg("fy"), py::arg("cx"),
           py::arg("cy"))
      .def_static("from_matrix", &camera_from_matrix, py::arg("width"), py::arg("height"), py::arg("K"),
                  "From a 3x3 K = [[fx, 0, cx], [0, fy, cy], [0, 0, 1]]; skew is an InputError")
      .def_readonly("width", &Camera::width)
      .def_readonly("height", &Camera::height)
      .def_readonly("fx", &Camera::fx)
      .def_readonly("fy", &Camera::fy)
      .def_readonly("cx", &Camera::cx)
      .def_readonly("cy", &Camera::cy)
      .def_property_readonly("K", &Camera::matrix, "3x3 intrinsic matrix")
      .def("__repr__", &describe);

  py::class_<Mesh>(m, "Mesh", "A triangle mesh in the object's frame, metres")
      .def_static("load", &Mesh::load, py::arg("path"), py::arg("unit_scale") = 1.0,
                  "Any format assimp reads (OBJ, PLY, STL, glTF, ...); coordinates times unit_scale give metres")
      .def_static("builtin", &builtin_demo_mesh, "The built-in asymmetric demo object (two joined boxes)")
      .def_property_readonly(
          "vertices",
          [](const Mesh& mesh) {
            py::array_t<float> out({static_cast<py::ssize_t>(mesh.vertices.size()), py::ssize_t{3}});
            auto v = out.mutable_unchecked<2>();
            for (size_t i = 0; i < mesh.vertices.size(); ++i)
              for (int j = 0; j < 3; ++j) v(static_cast<py::ssize_t>(i), j) = mesh.vertices[i][j];
            return out;
          },
          "(N, 3) float32 copy of the vertices, metres")
      .def_property_readonly(
          "triangles",
          [](const Mesh& mesh) {
            py::array_t<int> out({static_cast<py::ssize_t>(mesh.triangles.size()), py::ssize_t{3}});
            auto t = out.mutable_unchecked<2>();
            for (size_t i = 0; i < mesh.triangles.size(); ++i)
              for (int j = 0; j < 3; ++j) t(static_cast<py::ssize_t>(i), j) = mesh.triangles[i][j];
            return out;
          },
          "(M, 3) int32 copy of the vertex indices")
      .def_property_readonly("centre", [](const Mesh& mesh) { return Eigen::Vector3d(mesh.centre().cast<double>()); })
      .def_property_readonly("radius", &Mesh::radius)
      .def_readonly("dropped_degenerate", &Mesh::dropped_degenerate)
      .def("__repr__", [](const Mesh& mesh) {
        return "Mesh(" + std::to_string(mesh.vertices.size()) + " vertices, " + std::to_string(mesh.triangles.size()) +
               " triangles)";
      });
}

}  // namespace depthtrack::python
