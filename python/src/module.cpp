// The extension module depthtrack._depthtrack (python/depthtrack/__init__.py re-exports it).
#include "bindings.hpp"

PYBIND11_MODULE(_depthtrack, m) {
  using namespace depthtrack::python;
  m.doc() = "depthtrack: 6-DoF tracking of a known rigid object in depth images";
  m.attr("__version__") = DEPTHTRACK_VERSION;
  bind_errors(m);
  bind_geometry(m);
  bind_config(m);
  bind_estimate(m);
  bind_devices(m);  // before Tracker, whose constructor takes a Device
  bind_tracker(m);
  bind_multi_tracker(m);
  bind_evaluation(m);
  bind_frame_source(m);
}
