// depthtrack.MultiTracker: several objects in one depth stream on one Device. update() reads the numpy
// depth in place (a copy when mutual occlusion masks it) and runs with the GIL released; a mutex per
// tracker keeps two Python threads from running it at once.
#include <pybind11/stl.h>

#include <depthtrack/error.hpp>
#include <depthtrack/multi_tracker.hpp>
#include <mutex>
#include <optional>

#include "bindings.hpp"
#include "convert.hpp"

namespace depthtrack::python {

namespace {

class PyMultiTracker {
 public:
  PyMultiTracker(const std::vector<Mesh>& meshes, const Camera& camera, const TrackerConfig& config,
                 std::shared_ptr<Device> device, bool mutual_occlusion)
      : tracker_(device ? device : Device::open(config.resolved_backend()), meshes, camera, config, mutual_occlusion) {}

  void initialize(size_t object, py::handle pose, double spread_metres, double spread_radians) {
    const Pose start = pose_from_matrix(pose);
    const std::lock_guard lock(mutex_);
    tracker_.initialize(object, start, InitialSpread{spread_metres, spread_radians});
  }

  std::vector<Estimate> update(py::handle depth, double timestamp, std::optional<double> metres_per_unit) {
    const DepthInput in = depth_input(depth, metres_per_unit);  // holds the array while the GIL is released
    const py::gil_scoped_release release;
    const std::lock_guard lock(mutex_);
    return tracker_.update(in.view, timestamp);
  }

  size_t size() const { return tracker_.size(); }
  std::string device() const { return tracker_.device().selector(); }

 private:
  MultiTracker tracker_;
  std::mutex mutex_;
};

}  // namespace

void bind_multi_tracker(py::module_& m) {
  py::class_<PyMultiTracker>(m, "MultiTracker",
                             "Several objects in one depth stream: a tracker per mesh on one Device, updated in "
                             "turn; with mutual_occlusion the pixels the others' estimates hide are missing for "
                             "each object")
      .def(py::init<const std::vector<Mesh>&, const Camera&, const TrackerConfig&, std::shared_ptr<Device>, bool>(),
           py::arg("meshes"), py::arg("camera"), py::arg("config") = TrackerConfig{}, py::arg("device") = nullptr,
           py::arg("mutual_occlusion") = true, py::call_guard<py::gil_scoped_release>(),
           "device: None opens config.backend's device for all the objects")
      .def("initialize", &PyMultiTracker::initialize, py::arg("object"), py::arg("pose"),
           py::arg("spread_metres") = InitialSpread{}.metres, py::arg("spread_radians") = InitialSpread{}.radians,
           "Object `object`'s particles around pose (4x4 camera-from-object, metres)")
      .def("update", &PyMultiTracker::update, py::arg("depth"), py::arg("timestamp"),
           py::arg("metres_per_unit") = py::none(),
           "One frame for every object (as Tracker.update takes it); a list of Estimates in the meshes' order")
      .def("__len__", &PyMultiTracker::size)
      .def_property_readonly("device", &PyMultiTracker::device, "the shared device's selector");
}

}  // namespace depthtrack::python
