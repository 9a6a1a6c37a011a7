// depthtrack.devices(): every compute device of every backend, the facts `depthtrack info` lists.
#include "bindings.hpp"
#include "compute/queue.hpp"

namespace depthtrack::python {

void bind_devices(py::module_& m) {
  m.def(
      "devices",
      [] {
        py::list out;
        for (const compute::DeviceInfo& d : compute::list_devices()) {
          py::dict j;
          j["backend"] = d.backend;
          j["selector"] = d.selector;
          j["name"] = d.name;
          j["platform"] = d.platform;
          j["vendor"] = d.vendor;
          j["driver"] = d.driver;
          j["version"] = d.version;
          j["gpu"] = d.is_gpu;
          j["global_memory_bytes"] = d.global_memory;
          j["max_allocation_bytes"] = d.max_allocation;
          j["local_memory_bytes"] = d.local_memory;
          j["max_work_group_size"] = d.max_work_group_size;
          j["compute_units"] = d.compute_units;
          j["gl_sharing"] = d.gl_sharing;
          j["external_memory"] = d.external_memory;
          j["fp64"] = d.fp64;
          j["subgroups"] = d.subgroups;
          py::list extensions;
          for (const auto& e : d.extensions) extensions.append(e);
          j["extensions"] = extensions;
          out.append(j);
        }
        return out;
      },
      "The compute devices (OpenCL, CUDA) as dicts; 'selector' is what TrackerConfig.backend takes");
}

}  // namespace depthtrack::python
