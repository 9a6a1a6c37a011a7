#include <cstdlib>
#include <depthtrack/error.hpp>

#include "compute/backend.hpp"
#include "compute/queue.hpp"
#include "filter/device_filter.hpp"
#include "filter/filter_backend.hpp"
#include "reference/reference_filter.hpp"

namespace depthtrack {

std::unique_ptr<FilterBackend> make_filter_backend(const Mesh& mesh, const Camera& working_camera,
                                                   const TrackerConfig& config) {
  const std::string backend = config.resolved_backend();
  const std::string origin = config.backend.empty() ? " (from DEPTHTRACK_DEVICE)" : "";
  if (backend == "reference") return std::make_unique<reference::ReferenceFilter>(mesh, working_camera, config);
  // Every other name selects a compute device of a registered backend: opencl, opencl:pocl, cuda:<n>...
  if (compute::find_backend(backend.substr(0, backend.find(':')))) {
    try {
      return std::make_unique<DeviceFilter>(compute::open_device(backend), mesh, working_camera, config);
    } catch (const InputError& e) {
      if (origin.empty()) throw;
      throw InputError(e.what() + origin);
    }
  }
  std::string available = "reference";
  for (const auto& device_backend : compute::backends()) available += ", " + device_backend.grammar;
  throw InputError("unknown backend '" + backend + "'" + origin + "; available: " + available +
                   " (`depthtrack info` lists the devices)");
}

}  // namespace depthtrack
