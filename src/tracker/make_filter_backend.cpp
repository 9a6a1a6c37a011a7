#include "tracker/make_filter_backend.hpp"

#include <cstdlib>
#include <depthtrack/error.hpp>

#include "compute/queue.hpp"
#include "filter/device_filter.hpp"
#include "reference/reference_filter.hpp"

namespace depthtrack {

std::unique_ptr<FilterBackend> make_filter_backend(const Mesh& mesh, const Camera& working_camera,
                                                   const TrackerConfig& config) {
  const std::string backend = config.resolved_backend();
  const std::string origin = config.backend.empty() ? " (from DEPTHTRACK_DEVICE)" : "";
  if (backend == "reference") return std::make_unique<reference::ReferenceFilter>(mesh, working_camera, config);
  // Every other name selects a compute device: opencl, opencl:pocl, opencl:<p>.<d>, cuda, cuda:<n>.
  if (backend.rfind("opencl", 0) == 0 || backend.rfind("cuda", 0) == 0) {
    try {
      return std::make_unique<DeviceFilter>(compute::open_device(backend), mesh, working_camera, config);
    } catch (const InputError& e) {
      if (origin.empty()) throw;
      throw InputError(e.what() + origin);
    }
  }
  throw InputError("unknown backend '" + backend + "'" + origin +
                   "; available: reference, opencl, opencl:pocl, opencl:nvidia, opencl:<platform>.<device>, cuda, "
                   "cuda:<n> (`depthtrack info` lists the devices)");
}

}  // namespace depthtrack
