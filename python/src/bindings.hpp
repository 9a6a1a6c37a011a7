#pragma once
// One bind_* function per class of the Python module (module.cpp calls them in order), and the
// conversions from Python values that several of them share.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace depthtrack::python {

namespace py = pybind11;

void bind_errors(py::module_& m);         // depthtrack.Error, InputError (ValueError), BackendError (RuntimeError)
void bind_geometry(py::module_& m);       // Camera, Mesh
void bind_config(py::module_& m);         // TrackerConfig and its nested models, from the one field list
void bind_estimate(py::module_& m);       // StepTimings, Estimate
void bind_tracker(py::module_& m);        // Tracker
void bind_multi_tracker(py::module_& m);  // MultiTracker
void bind_devices(py::module_& m);        // Device, devices()
void bind_evaluation(py::module_& m);     // Sequence, perturb_pose, AddsMetric
void bind_frame_source(py::module_& m);   // Frame, FrameSource, open_source

}  // namespace depthtrack::python
