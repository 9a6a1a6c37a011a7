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
                 std::shared_ptr<Device> device, bool mutual_occlusion, int host_threads)
      : tracker_(device ? device : Device::open(config.resolved_backend()), meshes, camera, config, mutual_occlusion,
                 host_threads),
        sensor_(camera) {}

  void initialize(size_t object, py::handle pose, double spread_metres, double spread_radians) {
    const Pose start = pose_from_matrix(pose);
    const std::lock_guard lock(mutex_);
    tracker_.initialize(object, start, InitialSpread{spread_metres, spread_radians});
  }

  std::vector<Estimate> update(py::handle depth, double timestamp, std::optional<double> metres_per_unit) {
    const DepthInput in = depth_input(depth, metres_per_unit, sensor_);  // holds the array while the GIL is released
    const py::gil_scoped_release release;
    const std::lock_guard lock(mutex_);
    return tracker_.update(in.view, timestamp);
  }

  MultiStageTimings last_timings() {
    const std::lock_guard lock(mutex_);
    return tracker_.last_timings();
  }

  size_t size() const { return tracker_.size(); }
  std::string device() const { return tracker_.device().selector(); }

 private:
  MultiTracker tracker_;
  Camera sensor_;  // the size update() takes
  std::mutex mutex_;
};

}  // namespace

void bind_multi_tracker(py::module_& m) {
  py::class_<MultiStageTimings>(m, "MultiStageTimings",
                                "Host wall time (ms) of each stage of a MultiTracker's last update")
      .def_readonly("working_ms", &MultiStageTimings::working_ms, "the frame checked and decimated, once")
      .def_readonly("occluders_ms", &MultiStageTimings::occluders_ms, "mutual occlusion: the occluder layers")
      .def_readonly("masks_ms", &MultiStageTimings::masks_ms, "mutual occlusion: each object's masked frame")
      .def_readonly("enqueue_ms", &MultiStageTimings::enqueue_ms, "every object's frame started")
      .def_readonly("object_enqueue_ms", &MultiStageTimings::object_enqueue_ms, "each object's start, in order")
      .def_readonly("collect_ms", &MultiStageTimings::collect_ms, "from the last start to the last estimate")
      .def_readonly("confidence_ms", &MultiStageTimings::confidence_ms,
                    "confidences, statuses and next layers still running after that")
      .def_readonly("total_ms", &MultiStageTimings::total_ms, "the whole update");
  py::class_<PyMultiTracker>(m, "MultiTracker",
                             "Several objects in one depth stream: a tracker per mesh on one Device, updated in "
                             "turn; with mutual_occlusion the pixels the others' estimates hide are missing for "
                             "each object")
      .def(
          py::init<const std::vector<Mesh>&, const Camera&, const TrackerConfig&, std::shared_ptr<Device>, bool, int>(),
          py::arg("meshes"), py::arg("camera"), py::arg("config") = TrackerConfig{}, py::arg("device") = nullptr,
          py::arg("mutual_occlusion") = true, py::arg("host_threads") = 0, py::call_guard<py::gil_scoped_release>(),
          "device: None opens config.backend's device for all the objects; host_threads: the threads the objects' "
          "host steps share (0: one per object, at most the hardware's; any count gives the same estimates)")
      .def("initialize", &PyMultiTracker::initialize, py::arg("object"), py::arg("pose"),
           py::arg("spread_metres") = InitialSpread{}.metres, py::arg("spread_radians") = InitialSpread{}.radians,
           "Object `object`'s particles around pose (4x4 camera-from-object, metres)")
      .def("update", &PyMultiTracker::update, py::arg("depth"), py::arg("timestamp"),
           py::arg("metres_per_unit") = py::none(),
           "One frame for every object (as Tracker.update takes it); a list of Estimates in the meshes' order")
      .def_property_readonly("last_timings", &PyMultiTracker::last_timings,
                             "MultiStageTimings of the last update: where a several-object frame's time goes")
      .def("__len__", &PyMultiTracker::size)
      .def_property_readonly("device", &PyMultiTracker::device, "the shared device's selector");
}

}  // namespace depthtrack::python
