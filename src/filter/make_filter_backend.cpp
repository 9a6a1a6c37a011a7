#include <depthtrack/error.hpp>

#include <cstdlib>

#include "compute/queue.hpp"
#include "filter/device_filter.hpp"
#include "filter/filter_backend.hpp"
#include "reference/reference_filter.hpp"

namespace depthtrack {

std::unique_ptr<FilterBackend> make_filter_backend(const Mesh& mesh, const Camera& working_camera,
                                                   const TrackerConfig& config) {
  if (config.backend == "reference") return std::make_unique<reference::ReferenceFilter>(mesh, working_camera, config);
  // Every other name selects a compute device: opencl, opencl:pocl, opencl:<p>.<d>, cuda, cuda:<n>.
  if (config.backend.rfind("opencl", 0) == 0 || config.backend.rfind("cuda", 0) == 0)
    return std::make_unique<DeviceFilter>(compute::open_device(config.backend), mesh, working_camera, config);
  throw InputError("unknown backend '" + config.backend +
                   "'; available: reference, opencl, opencl:pocl, opencl:nvidia, opencl:<platform>.<device>, cuda, "
                   "cuda:<n> (`depthtrack info` lists the devices)");
}

}  // namespace depthtrack
