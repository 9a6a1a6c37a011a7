#include "tracker/make_filter_backend.hpp"

#include <charconv>
#include <depthtrack/error.hpp>

#include "atlas/gl_atlas_device.hpp"
#include "core/thread_pool.hpp"
#include "filter/device_filter.hpp"
#include "reference/reference_filter.hpp"
#include "tracker/device_access.hpp"

namespace depthtrack {

int cpu_backend_threads(const std::string& backend) {
  if (backend == "cpu") return hardware_threads();
  const std::string count = backend.substr(4);
  int threads = 0;
  const auto [end, error] = std::from_chars(count.data(), count.data() + count.size(), threads);
  if (error != std::errc() || end != count.data() + count.size() || threads < 1 || threads > 1024)
    throw InputError("backend '" + backend + "': cpu:N takes a thread count N from 1 to 1024, not '" + count + "'");
  return threads;
}

std::shared_ptr<Device> open_config_device(const TrackerConfig& config) {
  return Device::open(config.resolved_backend());
}

std::unique_ptr<FilterBackend> make_filter_backend(const Device& device, const Mesh& mesh, const Camera& working_camera,
                                                   const TrackerConfig& config) {
  if (DeviceAccess::context(device) && config.renderer == Renderer::Gl) {
    // The Device's GL context, and the compute context made against it where the platform shares GL.
    const GlAtlasDevice gl = DeviceAccess::gl_atlas(device, config.gl_path);
    return std::make_unique<DeviceFilter>(gl.compute, mesh, working_camera, config, &gl);
  }
  if (const auto& context = DeviceAccess::context(device))
    return std::make_unique<DeviceFilter>(context, mesh, working_camera, config);
  if (device.selector() == "reference")
    return std::make_unique<reference::ReferenceFilter>(mesh, working_camera, config);
  // The reference filter with its per-particle loops on a thread pool: the same results, bit for bit.
  return std::make_unique<reference::ReferenceFilter>(mesh, working_camera, config,
                                                      cpu_backend_threads(device.selector()));
}

std::unique_ptr<FilterBackend> make_filter_backend(const Mesh& mesh, const Camera& working_camera,
                                                   const TrackerConfig& config) {
  return make_filter_backend(*open_config_device(config), mesh, working_camera, config);
}

}  // namespace depthtrack
