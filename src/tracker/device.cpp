// depthtrack::Device: a host filter's name, or an open compute queue with its program cache.
#include <depthtrack/device.hpp>
#include <depthtrack/error.hpp>

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

Device::Device(std::string selector, std::shared_ptr<compute::DeviceContext> context)
    : selector_(std::move(selector)), context_(std::move(context)) {}

Device::~Device() = default;

std::string Device::name() const {
  return context_ ? context_->queue->info().name : "host";
}

size_t Device::program_builds() const {
  return context_ ? context_->programs.builds() : 0;
}

}  // namespace depthtrack
