// depthtrack.Tracker: one object's filter. update() reads the numpy depth in place and runs with the
// GIL released; a per-tracker mutex keeps two Python threads from running one tracker at once, and trackers
// on one shared Device take one mutex between them (they enqueue on its one compute queue).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <depthtrack/error.hpp>
#include <depthtrack/tracker.hpp>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include "bindings.hpp"
#include "convert.hpp"

namespace depthtrack::python {

namespace {

// The mutex of the trackers on one Device, made with the first of them and gone with the last.
std::shared_ptr<std::mutex> device_mutex(const Device* device) {
  static std::mutex registry_mutex;
  static std::map<const Device*, std::weak_ptr<std::mutex>> registry;
  const std::lock_guard lock(registry_mutex);
  auto& slot = registry[device];
  auto mutex = slot.lock();
  if (!mutex) slot = mutex = std::make_shared<std::mutex>();
  return mutex;
}

Tracker make_tracker(const Mesh& mesh, const Camera& camera, const TrackerConfig& config,
                     const std::shared_ptr<Device>& device) {
  if (device) return Tracker(device, mesh, camera, config);
  return Tracker(mesh, camera, config);
}

class PyTracker {
 public:
  PyTracker(const Mesh& mesh, const Camera& camera, const TrackerConfig& config, std::shared_ptr<Device> device)
      : tracker_(make_tracker(mesh, camera, config, device)),
        sensor_(camera),
        mutex_(device ? device_mutex(device.get()) : std::make_shared<std::mutex>()),
        device_(std::move(device)) {}

  void initialize(py::handle pose, double spread_metres, double spread_radians) {
    const Pose start = pose_from_matrix(pose);
    const std::lock_guard lock(*mutex_);
    tracker_.initialize(start, InitialSpread{spread_metres, spread_radians});
  }

  Estimate update(py::handle depth, double timestamp, std::optional<double> metres_per_unit) {
    const DepthInput in = depth_input(depth, metres_per_unit, sensor_);  // holds the array while the GIL is released
    const py::gil_scoped_release release;
    const std::lock_guard lock(*mutex_);
    return tracker_.update(in.view, timestamp);
  }

  Estimate initialize_global(py::handle depth, double timestamp, std::optional<double> metres_per_unit,
                             std::optional<std::array<int, 4>> box, std::optional<Eigen::Vector3d> point) {
    if (box && point) throw InputError("initialize_global takes a box or a point, not both");
    const InitHint hint = box     ? InitHint::box((*box)[0], (*box)[1], (*box)[2], (*box)[3])
                          : point ? InitHint::near_point(*point)
                                  : InitHint::anywhere();
    const DepthInput in = depth_input(depth, metres_per_unit, sensor_);
    const py::gil_scoped_release release;
    const std::lock_guard lock(*mutex_);
    return tracker_.initialize_global(in.view, timestamp, hint);
  }

  void set_particle_count(int count) {
    const std::lock_guard lock(*mutex_);
    tracker_.set_particle_count(count);
  }

  Camera working_camera() const { return tracker_.working_camera(); }
  TrackerConfig config() const { return tracker_.config(); }
  std::string backend_description() const { return tracker_.backend_description(); }
  size_t mesh_triangles() const { return tracker_.mesh_triangles(); }
  size_t drawn_triangles() const { return tracker_.drawn_triangles(); }

 private:
  Tracker tracker_;
  Camera sensor_;  // the size update() takes
  std::shared_ptr<std::mutex> mutex_;
  std::shared_ptr<Device> device_;  // keeps device_mutex's key alive
};

}  // namespace

void bind_tracker(py::module_& m) {
  py::class_<PyTracker>(m, "Tracker",
                        "The particle filter of one object. camera: the intrinsics of the images update() gets "
                        "(decimated to config.width x config.height, which must divide them)")
      .def(py::init<const Mesh&, const Camera&, const TrackerConfig&, std::shared_ptr<Device>>(), py::arg("mesh"),
           py::arg("camera"), py::arg("config") = TrackerConfig{}, py::arg("device") = nullptr,
           py::call_guard<py::gil_scoped_release>(),
           "device: a depthtrack.Device to share with other trackers (its queue, programs compiled once; "
           "config.backend becomes its selector); None opens config.backend's device for this tracker alone")
      .def("initialize", &PyTracker::initialize, py::arg("pose"), py::arg("spread_metres") = InitialSpread{}.metres,
           py::arg("spread_radians") = InitialSpread{}.radians,
           "Particles drawn around pose (4x4 camera-from-object, metres) with these per-axis deviations")
      .def("update", &PyTracker::update, py::arg("depth"), py::arg("timestamp"),
           py::arg("metres_per_unit") = py::none(),
           "One frame: depth is float32 metres (NaN = missing) or uint16 units with metres_per_unit (0 = "
           "missing), shape (height, width); timestamp in seconds, increasing. Returns an Estimate")
      .def("initialize_global", &PyTracker::initialize_global, py::arg("depth"), py::arg("timestamp"),
           py::arg("metres_per_unit") = py::none(), py::arg("box") = py::none(), py::arg("point") = py::none(),
           "Finds the object in this frame without a pose, inside box (u0, v0, u1, v1: inclusive sensor pixels) "
           "or near point (camera frame, metres) when given, and runs the frame")
      .def("set_particle_count", &PyTracker::set_particle_count, py::arg("count"),
           "The following frames run with count particles, 1 to config.particles (every backend; "
           "not with config.budget_ms, which chooses the count itself)")
      .def_property_readonly("working_camera", &PyTracker::working_camera)
      .def_property_readonly("config", &PyTracker::config, "a copy of the configuration")
      .def_property_readonly("backend_description", &PyTracker::backend_description)
      .def_property_readonly("mesh_triangles", &PyTracker::mesh_triangles, "triangles of the mesh given")
      .def_property_readonly("drawn_triangles", &PyTracker::drawn_triangles,
                             "triangles of the mesh drawn (config.simplify_error simplified it)");
}

}  // namespace depthtrack::python
