// depthtrack.TrackerConfig and its nested models: one attribute per field of the C++ struct,
// generated from the field list that the JSON file uses too (core/tracker_config_fields.hpp).
#include <pybind11/stl/filesystem.h>

#include <depthtrack/config_file.hpp>
#include <depthtrack/tracker_config.hpp>
#include <string>
#include <type_traits>

#include "bindings.hpp"
#include "core/tracker_config_fields.hpp"

namespace depthtrack::python {

namespace {

namespace fields = config_fields;

// A class whose attributes are S's fields; enums read and written as their strings. Assigning an
// attribute that is not a field is an AttributeError (no __dict__), a wrong type a TypeError.
template <typename S>
py::class_<S> bind_fields(py::module_& m, const char* name, const char* doc) {
  py::class_<S> c(m, name, doc);
  c.def(py::init<>());
  fields::for_each_field<S>([&](const auto& f) {
    using M = typename std::decay_t<decltype(f)>::member_type;
    const auto member = f.member;
    if constexpr (fields::NamedEnum<M>) {
      c.def_property(
          f.name, [member](const S& s) { return std::string(to_string(s.*member)); },
          [member](S& s, const std::string& value) { fields::parse_named(value, s.*member); }, f.help);
    } else {
      c.def_readwrite(f.name, member, f.help);  // nested structs by reference: c.a.b = x changes c
    }
  });
  c.def("__eq__", [](const S& a, const S& b) { return fields::equal(a, b); });
  c.def("__copy__", [](const S& s) { return S(s); });
  c.def("__deepcopy__", [](const S& s, py::dict) { return S(s); });
  return c;
}

}  // namespace

void bind_config(py::module_& m) {
  bind_fields<ObservationModel>(m, "ObservationModel", "Per-pixel observation model");
  bind_fields<OcclusionModel>(m, "OcclusionModel", "Two-state Markov chain of each pixel's occlusion, per second");
  bind_fields<OcclusionWindow>(m, "OcclusionWindow", "Where particles keep occlusion state (0 x 0: the whole image)");
  bind_fields<MotionModel>(m, "MotionModel", "Damped random walk on the velocity");
  bind_fields<Refinement>(m, "Refinement", "Pose refinement after weighting");
  bind_fields<LossModel>(m, "LossModel", "When an estimate counts as lost");
  bind_fields<RecoveryModel>(m, "RecoveryModel", "Global search while lost");
  bind_fields<TrackerConfig>(m, "TrackerConfig", "Every parameter of the tracker, with dbot's defaults")
      .def("validate", &TrackerConfig::validate, "InputError naming the first impossible value")
      .def("to_json", &tracker_config_to_json, "Every field as the JSON that --config reads")
      .def_static(
          "from_json", [](const std::string& text) { return tracker_config_from_json(text); }, py::arg("text"),
          "Fields given override the defaults; unknown keys and wrong types are InputErrors naming the key")
      .def_static(
          "load", [](const std::filesystem::path& path) { return load_tracker_config(path); }, py::arg("path"),
          "A JSON configuration file (depthtrack config --dump prints one)")
      .def("__repr__", [](const TrackerConfig& c) { return "TrackerConfig(" + tracker_config_to_json(c) + ")"; });
}

}  // namespace depthtrack::python
