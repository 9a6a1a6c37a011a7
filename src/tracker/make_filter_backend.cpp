#include "tracker/make_filter_backend.hpp"

#include <charconv>
#include <cstdlib>
#include <depthtrack/error.hpp>

#include "compute/backend.hpp"
#include "compute/queue.hpp"
#include "core/thread_pool.hpp"
#include "filter/device_filter.hpp"
#include "reference/reference_filter.hpp"

namespace depthtrack {

namespace {

// cpu: the hardware's threads; cpu:N: N of them (1 to 1024).
int cpu_backend_threads(const std::string& backend) {
  if (backend == "cpu") return hardware_threads();
  const std::string count = backend.substr(4);
  int threads = 0;
  const auto [end, error] = std::from_chars(count.data(), count.data() + count.size(), threads);
  if (error != std::errc() || end != count.data() + count.size() || threads < 1 || threads > 1024)
    throw InputError("backend '" + backend + "': cpu:N takes a thread count N from 1 to 1024, not '" + count + "'");
  return threads;
}

}  // namespace

std::unique_ptr<FilterBackend> make_filter_backend(const Mesh& mesh, const Camera& working_camera,
                                                   const TrackerConfig& config) {
  const std::string backend = config.resolved_backend();
  const std::string origin = config.backend.empty() ? " (from DEPTHTRACK_DEVICE)" : "";
  if (backend == "reference") return std::make_unique<reference::ReferenceFilter>(mesh, working_camera, config);
  // The reference filter with its per-particle loops on a thread pool: the same results, bit for bit.
  if (backend == "cpu" || backend.rfind("cpu:", 0) == 0)
    return std::make_unique<reference::ReferenceFilter>(mesh, working_camera, config, cpu_backend_threads(backend));
  // Every other name selects a compute device of a registered backend: opencl, opencl:pocl, cuda:<n>...
  if (compute::find_backend(backend.substr(0, backend.find(':')))) {
    try {
      return std::make_unique<DeviceFilter>(compute::open_device(backend), mesh, working_camera, config);
    } catch (const InputError& e) {
      if (origin.empty()) throw;
      throw InputError(e.what() + origin);
    }
  }
  std::string available = "reference, cpu, cpu:<threads>";
  for (const auto& device_backend : compute::backends()) available += ", " + device_backend.grammar;
  throw InputError("unknown backend '" + backend + "'" + origin + "; available: " + available +
                   " (`depthtrack info` lists the devices)");
}

}  // namespace depthtrack
