// depthtrack.Device (open by selector, shared by trackers) and depthtrack.devices(): every compute device
// of every backend, the facts `depthtrack info` lists.
#include <pybind11/stl.h>

#include <depthtrack/device.hpp>

#include "bindings.hpp"
#include "compute/queue.hpp"
#include "io/device_info_json.hpp"

namespace depthtrack::python {

void bind_devices(py::module_& m) {
  py::class_<Device, std::shared_ptr<Device>>(m, "Device",
                                              "A device trackers share: Tracker(..., device=d) for several objects "
                                              "on one compute queue, each kernel program compiled once")
      .def_static("open", &Device::open, py::arg("selector"), py::call_guard<py::gil_scoped_release>(),
                  "reference, cpu, cpu:N, or a compute selector (opencl, opencl:pocl, cuda:0, ...)")
      .def_static(
          "list",
          [] {
            py::list out;
            for (const DeviceDescription& d : Device::list()) {
              py::dict j;
              j["selector"] = d.selector;
              j["backend"] = d.backend;
              j["name"] = d.name;
              j["platform"] = d.platform;
              j["gpu"] = d.is_gpu;
              out.append(j);
            }
            return out;
          },
          "The compute devices as dicts (selector, backend, name, platform, gpu); devices() has every detail")
      .def_property_readonly("selector", &Device::selector)
      .def_property_readonly("name", &Device::name)
      .def_property_readonly("is_host", &Device::is_host)
      .def_property_readonly("program_builds", &Device::program_builds,
                             "kernel programs compiled on this device so far (0 on the host)")
      .def("__repr__", [](const Device& d) { return "<depthtrack.Device " + d.selector() + " (" + d.name() + ")>"; });

  m.def(
      "devices",
      [] {
        py::list out;
        const py::object loads = py::module_::import("json").attr("loads");
        for (const compute::DeviceInfo& d : compute::list_devices()) {
          nlohmann::ordered_json j = io::device_facts_json(d);
          j["backend"] = d.backend;
          j["extensions"] = d.extensions;
          out.append(loads(j.dump()));
        }
        return out;
      },
      "The compute devices (OpenCL, CUDA) as dicts; 'selector' is what TrackerConfig.backend takes");
}

}  // namespace depthtrack::python
