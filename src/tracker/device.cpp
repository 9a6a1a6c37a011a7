// depthtrack::Device: a host filter's name, or an open compute queue with its program cache, and the GL
// context (with, for cl_khr_gl_sharing, a compute context against it) its GL trackers share.
#include <depthtrack/device.hpp>
#include <depthtrack/error.hpp>
#include <map>
#include <mutex>
#include <thread>
#include <utility>

#include "atlas/gl_atlas_device.hpp"
#include "compute/backend.hpp"
#include "compute/program_cache.hpp"
#include "tracker/make_filter_backend.hpp"

namespace depthtrack {

std::vector<DeviceDescription> Device::list() {
  std::vector<DeviceDescription> devices;
  for (const auto& info : compute::list_devices())
    devices.push_back({info.selector, info.backend, info.name, info.platform, info.is_gpu});
  return devices;
}

std::shared_ptr<Device> Device::open(const std::string& selector) {
  if (selector == "reference") return std::shared_ptr<Device>(new Device(selector, nullptr));
  if (selector == "cpu" || selector.rfind("cpu:", 0) == 0) {
    cpu_backend_threads(selector);  // checks N
    return std::shared_ptr<Device>(new Device(selector, nullptr));
  }
  // Every other name selects a compute device of a registered backend: opencl, opencl:pocl, cuda:<n>...
  if (compute::find_backend(selector.substr(0, selector.find(':'))))
    return std::shared_ptr<Device>(
        new Device(selector, std::make_shared<compute::DeviceContext>(compute::open_device(selector))));
  std::string available = "reference, cpu, cpu:<threads>";
  for (const auto& backend : compute::backends()) available += ", " + backend.grammar;
  throw InputError("unknown backend '" + selector + "'; available: " + available +
                   " (`depthtrack info` lists the devices)");
}

struct Device::GlAtlases {
  std::mutex mutex;
  std::map<std::pair<std::string, std::thread::id>, GlAtlasDevice> made;
};

Device::Device(std::string selector, std::shared_ptr<compute::DeviceContext> context)
    : selector_(std::move(selector)), context_(std::move(context)), gl_(std::make_unique<GlAtlases>()) {}

Device::~Device() = default;

GlAtlasDevice Device::gl_atlas(const std::string& gl_path) const {
  if (!context_) throw InputError("the gl renderer draws for a compute device; '" + selector_ + "' is a host filter");
  const std::lock_guard lock(gl_->mutex);
  const auto key = std::make_pair(gl_path, std::this_thread::get_id());
  if (const auto found = gl_->made.find(key); found != gl_->made.end()) return found->second;
  return gl_->made.emplace(key, open_gl_atlas_device(context_, gl_path)).first->second;
}

size_t Device::gl_contexts() const {
  const std::lock_guard lock(gl_->mutex);
  return gl_->made.size();
}

std::string Device::name() const {
  return context_ ? context_->queue->info().name : "host";
}

size_t Device::program_builds() const {
  if (!context_) return 0;
  size_t builds = context_->programs.builds();
  const std::lock_guard lock(gl_->mutex);
  for (const auto& [key, gl] : gl_->made)
    if (gl.compute != context_) builds += gl.compute->programs.builds();
  return builds;
}

}  // namespace depthtrack
