// What a Python script needs to score itself on a recorded clip as `depthtrack track` does: the clip
// (depthtrack.Sequence: frames, truth, depth as numpy), the CLI's perturbed start (perturb_pose) and
// ADD-S (AddsMetric), each the C++ function itself, so the numbers agree with the CLI's to the digit.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/sequence.hpp>
#include <optional>

#include "bindings.hpp"
#include "convert.hpp"

namespace depthtrack::python {

namespace {
// Frame i's depth as a (height, width) float32 array of metres, NaN where missing.
py::array_t<float> depth_array(const Sequence& sequence, size_t i) {
  if (i >= sequence.frames.size())
    throw InputError("frame " + std::to_string(i) + " does not exist: the sequence has " +
                     std::to_string(sequence.frames.size()));
  const DepthImage depth = sequence.load_depth(i);
  py::array_t<float> out({static_cast<py::ssize_t>(depth.height()), static_cast<py::ssize_t>(depth.width())});
  std::copy(depth.data().begin(), depth.data().end(), out.mutable_data());
  return out;
}

std::optional<py::array_t<double>> truth_matrix(const SequenceFrame& frame) {
  if (!frame.ground_truth) return std::nullopt;
  return pose_to_matrix(*frame.ground_truth);
}
}  // namespace

void bind_evaluation(py::module_& m) {
  py::class_<SequenceFrame>(m, "SequenceFrame", "One frame of a recorded clip")
      .def_readonly("name", &SequenceFrame::name)
      .def_readonly("timestamp", &SequenceFrame::timestamp, "seconds")
      .def_property_readonly("ground_truth", &truth_matrix,
                             "4x4 camera-from-object of the selected object (metres), or None");
  py::class_<Sequence>(m, "Sequence", "A recorded clip (depthtrack's layout, YCB-Video or BOP)")
      .def_static("load", &load_sequence, py::arg("path"), py::arg("object") = "",
                  "The clip in path, with the ground truth of `object` (a name or obj_id; may be omitted when "
                  "the clip has only one)")
      .def_readonly("camera", &Sequence::camera)
      .def_readonly("metres_per_unit", &Sequence::metres_per_unit)
      .def_readonly("frames", &Sequence::frames)
      .def("load_depth", &depth_array, py::arg("index"), "Frame index's depth: float32 metres, NaN = missing");
  m.def(
      "perturb_pose",
      [](py::handle pose, const Eigen::Vector3d& centre, double metres, double degrees, uint64_t seed) {
        return pose_to_matrix(perturb_pose(pose_from_matrix(pose), centre, metres, degrees, seed));
      },
      py::arg("pose"), py::arg("centre"), py::arg("metres"), py::arg("degrees"), py::arg("seed"),
      "pose moved by exactly `metres` and turned by exactly `degrees` about centre (object frame), drawn from "
      "seed: the start `track --init-perturb \"metres degrees\" --seed seed` takes");
  py::class_<AddsMetric>(m, "AddsMetric",
                         "ADD-S of a mesh: mean distance from each vertex placed by the "
                         "estimate to the nearest vertex placed by the truth")
      .def(py::init<const Mesh&>(), py::arg("mesh"))
      .def(
          "__call__",
          [](const AddsMetric& adds, py::handle estimate, py::handle truth) {
            return adds(pose_from_matrix(estimate), pose_from_matrix(truth));
          },
          py::arg("estimate"), py::arg("truth"), "metres");
}

}  // namespace depthtrack::python
