// depthtrack::Device: a host filter's name, or an open compute queue with its program cache, and the GL
// context (with, for cl_khr_gl_sharing, a compute context against it) its GL trackers share.
#include <depthtrack/device.hpp>
#include <depthtrack/error.hpp>
#include <utility>

#include "compute/backend.hpp"
#include "tracker/device_access.hpp"
#include "tracker/make_filter_backend.hpp"

namespace depthtrack {

std::vector<DeviceDescription> Device::list() {
  std::vector<DeviceDescription> devices;
  for (const auto& info : compute::list_devices())
    devices.push_back({info.selector, info.backend, info.name, info.platform, info.is_gpu});
  return devices;
}

std::shared_ptr<Device> Device::open(const std::string& selector) {
  if (selector == "reference") return std::make_shared<OpenDevice>(selector, nullptr);
  if (selector == "cpu" || selector.rfind("cpu:", 0) == 0) {
    cpu_backend_threads(selector);  // checks N
    return std::make_shared<OpenDevice>(selector, nullptr);
  }
  // Every other name selects a compute device of a registered backend: opencl, opencl:pocl, cuda:<n>...
  if (compute::find_backend(selector.substr(0, selector.find(':'))))
    return std::make_shared<OpenDevice>(selector,
                                        std::make_shared<compute::DeviceContext>(compute::open_device(selector)));
  std::string available = "reference, cpu, cpu:<threads>";
  for (const auto& backend : compute::backends()) available += ", " + backend.grammar;
  throw InputError("unknown backend '" + selector + "'; available: " + available +
                   " (`depthtrack info` lists the devices)");
}

Device::~Device() = default;

const std::string& Device::selector() const {
  return DeviceAccess::of(*this).opened_selector;
}

bool Device::is_host() const {
  return !DeviceAccess::of(*this).compute_context;
}

std::string Device::name() const {
  const auto& context = DeviceAccess::of(*this).compute_context;
  return context ? context->queue->info().name : "host";
}

size_t Device::program_builds() const {
  return DeviceAccess::of(*this).program_builds();
}

size_t Device::gl_contexts() const {
  return DeviceAccess::of(*this).gl_contexts();
}

OpenDevice::OpenDevice(std::string opened, std::shared_ptr<compute::DeviceContext> device_context)
    : opened_selector(std::move(opened)), compute_context(std::move(device_context)) {}

// The GL sides' contexts go before the Device's own compute context.
OpenDevice::~OpenDevice() {
  gl_.clear();
}

GlAtlasDevice OpenDevice::gl_atlas(const std::string& gl_path) const {
  if (!compute_context)
    throw InputError("the gl renderer draws for a compute device; '" + opened_selector + "' is a host filter");
  const std::lock_guard lock(mutex_);
  const GlKey key{gl_path, std::this_thread::get_id()};
  if (const auto found = gl_.find(key); found != gl_.end()) return found->second;
  return gl_.emplace(key, open_gl_atlas_device(compute_context, gl_path)).first->second;
}

size_t OpenDevice::gl_contexts() const {
  const std::lock_guard lock(mutex_);
  return gl_.size();
}

size_t OpenDevice::program_builds() const {
  if (!compute_context) return 0;
  size_t builds = compute_context->programs.builds();
  const std::lock_guard lock(mutex_);
  for (const auto& [key, gl] : gl_)
    if (gl.compute != compute_context) builds += gl.compute->programs.builds();
  return builds;
}

}  // namespace depthtrack
